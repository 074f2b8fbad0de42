#include "constrain/hinge_spring.h"

#include <cmath>

#include "constrain/point_constraint.h"

namespace pbm {
namespace {

Mat3 rotation_of(int body, const std::vector<BodyWorkspace>& bodies) {
  return body < 0 ? Mat3::Identity() : bodies[body].R;
}

// omega of a body in the world frame (zero for the world).
Vec3 world_angular_velocity(const ConstrainedSystem& system, int body,
                            const std::vector<BodyWorkspace>& bodies, const VecX& v) {
  if (body < 0) return Vec3::Zero();
  return bodies[body].R * v.segment<3>(system.bodies[body].v_offset + 3);
}

void add_torque(const ConstrainedSystem& system, int body, const Vec3& tau_world,
                std::vector<BodyWorkspace>& bodies, std::vector<VecX>& force,
                std::vector<VecX>& delta, VecX& rates) {
  if (body < 0) return;
  const BodyModel& b = system.bodies[body];
  BodyWorkspace& bw = bodies[body];
  VecX& g = force[body];
  g.setZero();
  angular_part(g) = bw.R.transpose() * tau_world;
  VecX& x = delta[body];
  solve_generalized_mass(bw, g, x);
  if (b.order == DynamicsOrder::first) x /= b.damping;  // (3.51): nu A q-dot = f
  add_generalized_rate(b, bw, x, rates);
}

}  // namespace

Real hinge_angle(const HingeSpringModel& hinge, const std::vector<BodyWorkspace>& bodies) {
  const Mat3 R_a = rotation_of(hinge.body_a, bodies);
  const Mat3 R_b = rotation_of(hinge.body_b, bodies);
  const Vec3 n = R_a * hinge.axis_a;
  const Vec3 e_a = R_a * hinge.reference_a;
  const Vec3 e_b = R_b * hinge.reference_b;
  return std::atan2(n.dot(e_b.cross(e_a)), e_b.dot(e_a));
}

Real hinge_spring_energy(const ConstrainedSystem& system,
                         const std::vector<BodyWorkspace>& bodies) {
  Real energy = 0;
  for (const HingeSpringModel& hinge : system.constraints.hinges) {
    const Real stretch = hinge_angle(hinge, bodies) - hinge.rest_angle;
    energy += 0.5 * hinge.stiffness * stretch * stretch;
  }
  return energy;
}

void add_hinge_spring_rates(const ConstrainedSystem& system, const VecX& v,
                            std::vector<BodyWorkspace>& bodies, std::vector<VecX>& force,
                            std::vector<VecX>& delta, VecX& rates) {
  for (const HingeSpringModel& hinge : system.constraints.hinges) {
    if (hinge.stiffness == 0 && hinge.damping == 0) continue;
    const Vec3 n = bodies[hinge.body_a].R * hinge.axis_a;
    const Real spin = n.dot(world_angular_velocity(system, hinge.body_a, bodies, v) -
                            world_angular_velocity(system, hinge.body_b, bodies, v));
    // -dE/dtheta (3.33's form), plus the damper.
    const Real moment =
        -hinge.stiffness * (hinge_angle(hinge, bodies) - hinge.rest_angle) - hinge.damping * spin;
    add_torque(system, hinge.body_a, moment * n, bodies, force, delta, rates);
    add_torque(system, hinge.body_b, -moment * n, bodies, force, delta, rates);
  }
}

}  // namespace pbm
