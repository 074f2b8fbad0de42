// The loads on the nodes (deform/nodal_loads.h, secs. 6.1 and 6.4), measured on the motion they
// cause against closed forms: force fields act on the bodies they name only, an acceleration
// field as g does and a force field per node; a spring's stiffness and damping make the damped
// oscillator m x'' = -k x - c x', and a spring acts only inside its time window.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "deform/body_dynamics.h"
#include "deform/nodal_loads.h"
#include "scene_builders.h"
#include "sim/state.h"

namespace pbm {
namespace {

BodyDef rigid_ball(const char* name, const Vec3& position) {
  BodyDef b = test::ball(DeformLevel::rigid, 8);
  b.name = name;
  b.position = position;
  return b;
}

Vec3 centre(const Simulation& sim, int body) {
  return sim.state.q.segment<3>(sim.model.bodies[body].q_offset);
}

// Two rigid balls (10 kg, 58 nodes each) in free space. An acceleration field (0, 0, -2) names
// body 0 only; a force field of (0.1, 0, 0) N per node names none, so it acts on both. From rest,
// c(t) = c0 + 1/2 a t^2 with a = (n 0.1 / m, 0, -2) for body 0 and (n 0.1 / m, 0, 0) for body 1.
// RK4 integrates a constant acceleration exactly.
TEST(NodalLoads, ForceFieldsActOnTheBodiesTheyName) {
  Scene s = test::free_space(rigid_ball("a", Vec3(0, 0, 0)));
  s.bodies.push_back(rigid_ball("b", Vec3(0, 5, 0)));
  s.solver.integrator = IntegratorKind::rk4;
  s.solver.dt = 0.01;
  ForceFieldDef pull_down{
      .kind = ForceFieldKind::acceleration, .value = Vec3(0, 0, -2), .bodies = {0}};
  ForceFieldDef push{
      .kind = ForceFieldKind::force_per_node, .value = Vec3(0.1, 0, 0), .bodies = {}};
  s.force_fields = {pull_down, push};
  Simulation sim(s);
  const int n = sim.model.bodies[0].n_nodes();
  const Real m = sim.model.bodies[0].mass;
  while (sim.state.time < 1.0 - 1e-9) ASSERT_TRUE(advance_frame(sim).ok);
  const Real t = sim.state.time;
  const Vec3 a0(n * 0.1 / m, 0, -2), a1(n * 0.1 / m, 0, 0);
  const Vec3 expected0 = 0.5 * a0 * t * t, expected1 = Vec3(0, 5, 0) + 0.5 * a1 * t * t;
  std::printf(
      "force fields at t = %.3f s: body a at (%.6f, %.6f, %.6f), body b at (%.6f, %.6f, "
      "%.6f) m\n",
      t, centre(sim, 0).x(), centre(sim, 0).y(), centre(sim, 0).z(), centre(sim, 1).x(),
      centre(sim, 1).y(), centre(sim, 1).z());
  EXPECT_LT((centre(sim, 0) - expected0).norm(), 1e-9);
  EXPECT_LT((centre(sim, 1) - expected1).norm(), 1e-9);
}

// The pole node of a rigid ball pulled by a spring toward a point straight above it: the force
// runs through the centre, so the ball translates along z as m z'' = -k z - c z' (z from the
// spring's rest), started 0.1 m below rest at rest. Its centre follows
//   z(t) = -0.1 e^(-gamma t) (cos w t + gamma / w sin w t),  gamma = c / 2m,
//   w = sqrt(k / m - gamma^2),
// while the spring is on; nothing moves before t_begin, and after t_end the velocity is constant.
// The window is closed, so the substep that ends at t_begin already sees the spring in its last
// rate evaluation: the switch-on costs an error of order dt, which halves with dt.
struct SpringRun {
  Real worst = 0;         // max |centre - closed form| while the spring is on [m]
  Real moved_before = 0;  // |c| + |c-dot| before the substep that ends at t_begin
  Real v_after_end = 0;   // |c-dot| at the first frame after t_end [m/s]
  Real v_drift = 0;       // its change over the frames after [m/s]
};

SpringRun spring_run(Real dt) {
  Scene s = test::free_space(rigid_ball("ball", Vec3::Zero()));
  s.solver.integrator = IntegratorKind::rk4;
  s.solver.dt = dt;
  s.solver.fps = 100;
  const Real k = 1000, c = 40, t_begin = 0.5, t_end = 2.5;
  SpringDef spring;
  spring.body = 0;
  spring.node = Simulation(s).model.bodies[0].tessellation.north_pole;
  spring.stiffness = k;
  spring.damping = c;
  spring.t_begin = t_begin;
  spring.t_end = t_end;
  spring.target = Vec3(0, 0, 1.1);  // the unit ball's pole is at z = 1: 0.1 m short
  s.springs.push_back(spring);
  Simulation sim(s);
  const Real m = sim.model.bodies[0].mass;
  const Real gamma = c / (2 * m), w = std::sqrt(k / m - gamma * gamma);
  SpringRun run;
  Vec3 v_after_end = Vec3::Constant(std::nan(""));
  while (sim.state.time < 3.0 - 1e-9) {
    EXPECT_TRUE(advance_frame(sim).ok);
    const Real t = sim.state.time;
    const Vec3 x = centre(sim, 0);
    const Vec3 v = sim.state.v.segment<3>(0);
    if (t < t_begin - 1e-12) {
      run.moved_before = std::max(run.moved_before, x.norm() + v.norm());
    } else if (t <= t_end + 1e-12) {
      const Real tau = t - t_begin;
      const Real z =
          -0.1 * std::exp(-gamma * tau) * (std::cos(w * tau) + gamma / w * std::sin(w * tau));
      run.worst = std::max(run.worst, std::abs(x.z() - (z + 0.1)) + std::hypot(x.x(), x.y()));
    } else if (std::isnan(v_after_end.x())) {
      v_after_end = v;
      run.v_after_end = v.norm();
    } else {
      run.v_drift = std::max(run.v_drift, (v - v_after_end).norm());
    }
  }
  std::printf(
      "spring, dt %g: worst |z - closed form| %.3g m; moved %.2g before t_begin; "
      "|v| after t_end %.4f m/s, drift %.2g\n",
      dt, run.worst, run.moved_before, run.v_after_end, run.v_drift);
  return run;
}

TEST(NodalLoads, SpringIsADampedOscillatorInsideItsTimeWindow) {
  const SpringRun coarse = spring_run(1e-3), fine = spring_run(5e-4);
  for (const SpringRun& run : {coarse, fine}) {
    EXPECT_EQ(run.moved_before, 0.0);
    EXPECT_LT(run.worst, 2e-3 * 0.1);  // 0.2% of the amplitude
    EXPECT_GT(run.v_after_end, 1e-4);  // released while still moving
    EXPECT_LT(run.v_drift, 1e-12);
  }
  EXPECT_NEAR(coarse.worst / fine.worst, 2.0, 0.3);
}

// The potential the stability guard counts (nodal_load_potential) is the one whose gradient is
// the loads: -dU/dx_i against the force compute_nodal_loads writes (no gravity, no damping), by
// central differences at every node, with a spring inside and past its max_force.
TEST(NodalLoads, ThePotentialOfTheLoadsIsTheirGradient) {
  for (const Real max_force : {1e300, 0.5}) {
    BodyDef b = test::ball(DeformLevel::local, 6);
    b.material.damping = 0;
    Scene s = test::free_space(b);
    s.force_fields = {
        {.kind = ForceFieldKind::acceleration, .value = Vec3(0.3, -1, 2), .bodies = {}},
        {.kind = ForceFieldKind::force_per_node, .value = Vec3(0.1, 0.2, -0.4), .bodies = {}}};
    SpringDef spring;
    spring.node = 3;
    spring.stiffness = 40;
    spring.damping = 0;
    spring.max_force = max_force;
    spring.target = Vec3(0.3, 0.5, 2);
    s.springs = {spring};
    Simulation sim(s);
    const BodyModel& body = sim.model.bodies[0];
    BodyWorkspace& bw = sim.ws.bodies[0];
    compute_body_kinematics(body, body_q(body, sim.state.q), body_v(body, sim.state.v), bw);
    const std::vector<Real> k = {spring.stiffness};
    const std::vector<Vec3> target = {spring.target};
    const NodalLoadDrive drive{Vec3::Zero(), target, k};
    compute_nodal_loads(body, 0, sim.model.force_fields, sim.model.springs, drive, 0.0, bw);
    const std::vector<Vec3> force(bw.force.begin(), bw.force.begin() + body.n_nodes());
    Real worst = 0;
    const Real h = 1e-6;
    for (int i = 0; i < body.n_nodes(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const Real x = bw.x[i][c];
        bw.x[i][c] = x + h;
        const Real up = nodal_load_potential(body, 0, sim.model.force_fields, sim.model.springs,
                                             drive, 0.0, bw);
        bw.x[i][c] = x - h;
        const Real down = nodal_load_potential(body, 0, sim.model.force_fields, sim.model.springs,
                                               drive, 0.0, bw);
        bw.x[i][c] = x;
        worst = std::max(worst, std::abs(-(up - down) / (2 * h) - force[i][c]));
      }
    }
    std::printf("max_force %g: |-dU/dx - f| at most %.2e N\n", max_force, worst);
    EXPECT_LT(worst, 1e-7);
  }
}

}  // namespace
}  // namespace pbm
