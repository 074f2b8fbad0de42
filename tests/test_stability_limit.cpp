// A body's explicit stability limit (deform/stability_limit.h, sec. 6.1): the power iteration's
// fastest membrane mode against the largest eigenvalue of M^-1 K_dd from the assembled matrix;
// the book's Euler on a free body just under the limit stays bounded and just over it explodes;
// the model shortens the substep with a note when solver.dt is past the limit (the jello-ball at
// 128 rings, which exploded at the book's 0.031 s, now runs), and leaves shipped scenes alone.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <string>

#include "deform/stability_limit.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

BodyDef stiff_ball(int resolution) {
  BodyDef b = test::ball(DeformLevel::local, resolution);
  b.material.w0 = 400;
  b.material.w1 = 300;
  b.material.damping = 0.5;
  return b;
}

TEST(StabilityLimit, PowerIterationFindsTheFastestMembraneMode) {
  Simulation sim(test::free_space(stiff_ball(8)));
  const BodyModel& body = sim.model.bodies[0];
  const MatX K = MatX(assemble_membrane_stiffness(body.tessellation, body.stiffness));
  VecX inv_sqrt_m(K.rows());
  for (int i = 0; i < K.rows(); ++i) inv_sqrt_m[i] = 1 / std::sqrt(body.node_mass[i / 3]);
  const MatX A = inv_sqrt_m.asDiagonal() * K * inv_sqrt_m.asDiagonal();
  const Real exact = std::sqrt(Eigen::SelfAdjointEigenSolver<MatX>(A).eigenvalues().maxCoeff());
  const StabilityLimit limit = body.stability;
  std::printf(
      "fastest mode: power iteration %.6g rad/s, eigensolver %.6g rad/s; Euler limit "
      "%.4g s\n",
      limit.omega, exact, limit.dt_euler);
  EXPECT_NEAR(limit.omega, exact, 1e-3 * exact);
  // The Euler limit of the faster of the membrane and the shape parameters' floor (1 / tau,
  // tau = solver.dt = 1 ms here, which dominates; at the scene's dt it never limits).
  const Real nu = body.damping;
  const Real w = std::max(exact, 1.0 / sim.model.solver.dt);
  EXPECT_NEAR(limit.omega_shape, 1.0 / sim.model.solver.dt, 1e-9 / sim.model.solver.dt);
  EXPECT_NEAR(limit.dt_euler, 2 / (nu / 2 + std::sqrt(nu * nu / 4 + w * w)), 1e-3 * 2 / w);
}

// Largest kinetic + elastic energy over 400 substeps of dt of a free, undamped ball whose nodes
// start displaced at random, relative to the start.
Real energy_growth(Real dt) {
  BodyDef body = stiff_ball(8);
  body.material.damping = 0;
  Scene scene = test::free_space(body);
  scene.solver.dt = dt;
  Simulation sim(scene);
  const BodyModel& b = sim.model.bodies[0];
  auto q_d = sim.state.q.segment(b.q_offset + b.layout.displacement_in_q(), b.layout.n_d);
  for (int i = 0; i < q_d.size(); ++i) q_d[i] = 0.01 * std::sin(7.3 * i);  // every mode a little
  measure_state(sim.world, sim.inputs, sim.state, sim.ws, sim.stats);
  const Real e0 = sim.stats.kinetic + sim.stats.elastic;
  Real worst = 1;
  int evaluations = 0;
  for (int k = 0; k < 400; ++k) {
    if (!advance_substep(sim.world, sim.inputs, sim.state, dt, sim.ws, evaluations)) return 1e300;
    measure_state(sim.world, sim.inputs, sim.state, sim.ws, sim.stats);
    worst = std::max(worst, (sim.stats.kinetic + sim.stats.elastic) / e0);
  }
  return worst;
}

TEST(StabilityLimit, EulerStaysBoundedUnderTheLimitAndExplodesOverIt) {
  Simulation probe(test::free_space(stiff_ball(8)));
  const StabilityLimit limit = explicit_stability_limit(probe.model.bodies[0]);
  const Real limit_undamped = 2 / limit.omega;
  const Real under = energy_growth(0.95 * limit_undamped),
             over = energy_growth(1.1 * limit_undamped);
  std::printf("free ball, limit %.4g s: energy grew %.3g x at 0.95 of it, %.3g x at 1.1\n",
              limit_undamped, under, over);
  // Under the limit the book's Euler keeps a modified energy: the true one oscillates within
  // 1 / (1 - (w dt / 2)^2) of its start (10.3 at w dt = 1.9) but does not grow.
  EXPECT_LT(under, 1 / (1 - 0.95 * 0.95));
  EXPECT_GT(over, 1e3);
}

Scene jello_at(int rings) {
  Scene scene = load_scene(PBM_SOURCE_DIR "/scenes/jello-ball.json");
  BodyDef& b = scene.bodies[0];
  b.tessellation.rings = b.tessellation.segments = rings;
  b.material.nodal_mass = 0;
  b.material.mass = 2064;  // the shipped ball's mass at every resolution
  return scene;
}

TEST(StabilityLimit, TheSubstepShrinksToTheLimitWithANote) {
  const Simulation shipped(load_scene(PBM_SOURCE_DIR "/scenes/jello-ball.json"));
  EXPECT_EQ(shipped.model.substep, shipped.model.solver.dt);
  EXPECT_EQ(shipped.model.notes.find("stability limit"), std::string::npos);

  Simulation fine(jello_at(128));
  const Real limit = fine.model.bodies[0].stability.dt_euler;
  std::printf("jello-ball at 128 rings: dt %.3g s, limit %.3g s, substep %.3g s\n  note: %s\n",
              fine.model.solver.dt, limit, fine.model.substep, fine.model.notes.c_str());
  EXPECT_LT(limit, fine.model.solver.dt);
  EXPECT_LT(fine.model.substep, limit);
  EXPECT_NE(fine.model.notes.find("body 'jello'"), std::string::npos);
  EXPECT_NE(fine.model.notes.find("stability limit"), std::string::npos);
  // It exploded at 0.031 s (kinetic energy 1.5e4 J to 1.7e9 J over 1.2 s); now it drops, lands
  // and stays on the slope for 1.5 s, with no retry of the guard.
  int retries = 0;
  Real top_kinetic = 0;
  while (fine.state.time < 1.5) {
    const FrameResult r = advance_frame(fine);
    ASSERT_TRUE(r.ok) << r.message;
    retries += fine.stats.retries;
    top_kinetic = std::max(top_kinetic, fine.stats.kinetic);
  }
  // Released 4 m up (its centre; 3 m above where it lands) it can have at most m g 4 m.
  const Real bound = 2064 * 9.81 * 4.0;
  std::printf("  1.5 s: %d retries, largest kinetic energy %.4g J (bound m g h = %.4g J)\n",
              retries, top_kinetic, bound);
  EXPECT_EQ(retries, 0);
  EXPECT_LT(top_kinetic, bound);
}

// With rk45 the integrator chooses its own steps: no limit, no note.
TEST(StabilityLimit, Rk45NeedsNoShorterSubstep) {
  Scene scene = jello_at(128);
  scene.solver.integrator = IntegratorKind::rk45;
  const Simulation sim(scene);
  EXPECT_EQ(sim.model.substep, scene.solver.dt);
}

}  // namespace
}  // namespace pbm
