// Lagrangian dynamics of one body (ch. 3): the inertial forces g_q, the mean-axis split and the
// global stiffness, checked against conservation laws and closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "deform/body_dynamics.h"
#include "scene_builders.h"
#include "sim/world.h"

namespace pbm {
namespace {

struct Totals {
  Real energy = 0;
  Vec3 p = Vec3::Zero(), l = Vec3::Zero();
};

Totals totals(const Model& model, const State& state, Workspace& ws) {
  FrameStats stats;
  measure_state(model, state, ws, stats);
  Totals t;
  t.energy = stats.kinetic + stats.elastic;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyEnergy e = compute_body_energy(model.bodies[b],
                                             state.q.segment(model.bodies[b].q_offset, model.bodies[b].q_size),
                                             state.v.segment(model.bodies[b].v_offset, model.bodies[b].v_size),
                                             model.gravity, ws.bodies[b]);
    t.p += e.linear_momentum;
    t.l += e.angular_momentum;
  }
  return t;
}

// A free body spinning about a tilted axis while its global and local coordinates oscillate:
// with no external force and no damping, sum m x-dot and sum m x cross x-dot are conserved
// exactly by (3.13) and the energy by the Lagrangian structure, if and only if g_q (3.24) is
// right. RK4 at a small step keeps the discretization error far below the tolerances.
TEST(BodyDynamics, SpinningDeformingFreeBodyConservesMomentaAndEnergy) {
  BodyDef body = test::ball(DeformLevel::local, 8);
  body.velocity = Vec3(0.3, -0.2, 0.1);
  body.angular_velocity = Vec3(0.5, 1.5, 2.5);
  Scene scene = test::free_space(body);
  scene.solver.integrator = IntegratorKind::rk4;
  scene.solver.dt = 2e-3;
  scene.solver.fps = 50;
  const Model model = build_model(scene);
  const Inputs inputs;
  Workspace ws;
  init_workspace(model, inputs, ws);
  State state = initial_state(model);
  // Excite q_s (a1 stretched) and q_d (a bump at one node) so both deform while spinning.
  const BodyModel& b = model.bodies[0];
  state.v[6 + 1] = 0.4;
  state.q[7 + 6 + 3 * 10 + 2] = 0.05;
  const Totals t0 = totals(model, state, ws);
  ASSERT_GT(t0.energy, 1.0);
  Real max_rel_p = 0, max_rel_l = 0, max_rel_e = 0;
  for (int frame = 0; frame < 500; ++frame) {  // 10 s
    FrameResult r = advance_frame(model, state, ws);
    ASSERT_TRUE(r.ok) << r.message;
    const Totals t = totals(model, state, ws);
    max_rel_p = std::max(max_rel_p, (t.p - t0.p).norm() / t0.p.norm());
    max_rel_l = std::max(max_rel_l, (t.l - t0.l).norm() / t0.l.norm());
    max_rel_e = std::max(max_rel_e, std::abs(t.energy - t0.energy) / t0.energy);
  }
  // The body really deformed and turned.
  EXPECT_GT(std::abs(state.q[7 + 1] - 1.0) + std::abs(state.q[7 + 6 + 3 * 10 + 2]), 1e-3);
  EXPECT_LT(max_rel_p, 1e-6);
  EXPECT_LT(max_rel_l, 1e-6);
  EXPECT_LT(max_rel_e, 1e-3);
  RecordProperty("max_rel_linear_momentum", std::to_string(max_rel_p));
  RecordProperty("max_rel_angular_momentum", std::to_string(max_rel_l));
  RecordProperty("max_rel_energy", std::to_string(max_rel_e));
  std::printf("relative drift over 10 s: linear %.3g angular %.3g energy %.3g (n_v = %d)\n",
              max_rel_p, max_rel_l, max_rel_e, b.v_size);
}

}  // namespace
}  // namespace pbm
