#include "deform/nodal_loads.h"

namespace pbm {

namespace {

// The force fields that apply to body b, summed: an acceleration and a force on every node.
void sum_fields(std::span<const ForceFieldDef> fields, int b, Vec3& acceleration, Vec3& per_node) {
  for (const ForceFieldDef& field : fields) {
    bool applies = field.bodies.empty();
    for (int target : field.bodies) applies = applies || target == b;
    if (!applies) continue;
    if (field.kind == ForceFieldKind::acceleration)
      acceleration += field.value;
    else
      per_node += field.value;
  }
}

}  // namespace

void compute_nodal_loads(const BodyModel& body, int b, std::span<const ForceFieldDef> fields,
                         std::span<const SpringModel> springs, const NodalLoadDrive& drive, Real t,
                         BodyWorkspace& bw) {
  const bool second = body.order == DynamicsOrder::second;
  Vec3 acceleration = drive.gravity;
  Vec3 per_node = Vec3::Zero();
  sum_fields(fields, b, acceleration, per_node);
  for (int i = 0; i < body.n_nodes(); ++i) {
    const Real m = body.node_mass[i];
    bw.force[i] = m * acceleration + per_node;
    if (second) bw.force[i] -= body.damping * m * bw.x_dot[i];
  }
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const SpringModel& spring = springs[s];
    if (spring.body != b || t < spring.t_begin || t > spring.t_end) continue;
    const int i = spring.node;
    Vec3 f = drive.spring_stiffness[s] * (drive.spring_target[s] - bw.x[i]) -
             spring.damping * bw.x_dot[i];
    // A dragged point far from its body must not fling it: the pull saturates (mouse springs).
    const Real norm = f.norm();
    if (norm > spring.max_force) f *= spring.max_force / norm;
    bw.force[i] += f;
  }
}

Real nodal_load_potential(const BodyModel& body, int b, std::span<const ForceFieldDef> fields,
                          std::span<const SpringModel> springs, const NodalLoadDrive& drive, Real t,
                          const BodyWorkspace& bw) {
  Vec3 acceleration = Vec3::Zero();
  Vec3 per_node = Vec3::Zero();
  sum_fields(fields, b, acceleration, per_node);
  Real U = 0;
  if (!acceleration.isZero() || !per_node.isZero()) {
    for (int i = 0; i < body.n_nodes(); ++i) {
      U -= (body.node_mass[i] * acceleration + per_node).dot(bw.x[i]);
    }
  }
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const SpringModel& spring = springs[s];
    if (spring.body != b || t < spring.t_begin || t > spring.t_end) continue;
    const Real k = drive.spring_stiffness[s];
    const Real d = (drive.spring_target[s] - bw.x[spring.node]).norm();
    // The pull k d saturates at max_force F beyond d = F / k: U = F d - F^2 / (2 k) there.
    U += k * d <= spring.max_force
             ? 0.5 * k * d * d
             : spring.max_force * d - 0.5 * spring.max_force * spring.max_force / k;
  }
  return U;
}

}  // namespace pbm
