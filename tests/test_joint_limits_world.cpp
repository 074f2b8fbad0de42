// Joint limits in the World (figure/joint_limits.h): a hinge striking its limit leaves at -e times
// its speed (e = 0, 0.5, 1); an elbow striking its limit in a swinging two-link arm keeps the
// arm's kinetic energy at e = 1 and moves the shoulder too; a pendulum held by its limit against
// gravity rests where the limit's spring balances its weight, the closed form at two steps (a
// shorter step, a harder limit); the spring's stiffness is k = I (0.5 / dt)^2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "figure/joint_space_inertia.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

// A capsule (r 0.05, straight half length 0.25, centre 0.3 m below the hinge) hinged about y at
// 2 m; below it, optionally, a second one on an elbow hinge 0.6 m down. Gravity g.
std::string arm(Real g, const std::string& shoulder, const std::string& elbow = "",
                Real dt = 0.001) {
  const std::string link =
      R"("shape": {"kind": "capsule", "size": [0.05, 0.05, 0.25], "center": [0, 0, -0.3]})";
  std::string segments =
      R"({"name": "upper", "joint": {"axis": [0, 1, 0], "position": [0, 0, 2], )" + shoulder +
      "}, " + link + "}";
  if (!elbow.empty()) {
    segments += R"(, {"name": "lower", "parent": "upper", "joint": {"axis": [0, 1, 0],
                     "position": [0, 0, -0.6], )" +
                elbow + "}, " + link + "}";
  }
  return R"({"gravity": [0, 0, )" + std::to_string(-g) + R"(], "solver": {"dt": )" +
         std::to_string(dt) +
         R"(, "fps": 50, "integrator": "rk4"}, "figures": [{"name": "arm", "segments": [)" +
         segments + "]}]}";
}

// Steps until the impact stage changes v[index]; returns (before, after).
std::pair<Real, Real> first_limit_impact(Simulation& sim, int index) {
  Real before = 0, after = 0;
  bool hit = false;
  auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
    if (stage != StepStage::impacts || hit) return;
    if (!done) {
      before = state.v[index];
    } else {
      after = state.v[index];
      hit = after != before;
    }
  };
  const StageObserver observer = watch;
  int evaluations = 0;
  for (int step = 0; step < 5000 && !hit; ++step) {
    EXPECT_TRUE(advance_substep(sim.world, sim.inputs, sim.state, sim.model.solver.dt, sim.ws,
                                evaluations, &observer));
  }
  EXPECT_TRUE(hit);
  return {before, after};
}

MatX inverse_inertia(const Model& model, const State& state) {
  const FigureModel& figure = model.figures[0].model;
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  MatX H;
  joint_space_inertia(figure, state.q.data(), ws, H);
  return H.inverse();
}

Real kinetic_energy(const Model& model, const State& state) {
  const FigureModel& figure = model.figures[0].model;
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  MatX H;
  joint_space_inertia(figure, state.q.data(), ws, H);
  const VecX v = state.v.head(figure.n_v);
  return 0.5 * v.dot(H * v);
}

TEST(JointLimits, AHingeStrikingItsLimitLeavesWithItsRestitution) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    Simulation sim(parse_scene(arm(0, R"("v0": [2], "lower": [-1], "upper": [0.5],
                                         "limit_restitution": )" +
                                          std::to_string(e)),
                               "arm.json"));
    const auto [before, after] = first_limit_impact(sim, 0);
    std::printf("e = %.1f: q %.6f rad, q-dot %.12f -> %.12f rad/s\n", e, sim.state.q[0], before,
                after);
    EXPECT_NEAR(before, 2.0, 1e-12);  // no force before the limit
    EXPECT_NEAR(after, -e * before, 1e-12);
    EXPECT_GT(sim.state.q[0], 0.5);
    EXPECT_LT(sim.state.q[0], 0.5 + 2.0 * sim.model.solver.dt);
  }
}

TEST(JointLimits, AnElbowStrikingItsLimitMovesTheShoulderAndKeepsTheEnergyAtEOne) {
  for (const Real e : {0.0, 1.0}) {
    Simulation sim(parse_scene(arm(0, R"("v0": [0.5])",
                                   R"("v0": [3], "lower": [-0.2], "upper": [0.4],
                                      "limit_restitution": )" +
                                       std::to_string(e)),
                               "arm.json"));
    Real energy_before = 0, energy_after = 0, shoulder_before = 0, shoulder_after = 0;
    Real before = 0, after = 0, h_inv_elbow = 0;
    bool hit = false;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage != StepStage::impacts || hit) return;
      if (!done) {
        h_inv_elbow = inverse_inertia(sim.model, state)(1, 1);
        energy_before = kinetic_energy(sim.model, state);
        shoulder_before = state.v[0];
        before = state.v[1];
      } else {
        energy_after = kinetic_energy(sim.model, state);
        shoulder_after = state.v[0];
        after = state.v[1];
        hit = after != before;
      }
    };
    const StageObserver observer = watch;
    int evaluations = 0;
    for (int step = 0; step < 5000 && !hit; ++step) {
      ASSERT_TRUE(advance_substep(sim.world, sim.inputs, sim.state, sim.model.solver.dt, sim.ws,
                                  evaluations, &observer));
    }
    ASSERT_TRUE(hit);
    std::printf(
        "e = %.0f: elbow %.9f -> %.9f, shoulder %.9f -> %.9f rad/s, energy %.12f -> "
        "%.12f J\n",
        e, before, after, shoulder_before, shoulder_after, energy_before, energy_after);
    EXPECT_NEAR(after, -e * before, 1e-12 * std::abs(before));
    EXPECT_GT(std::abs(shoulder_after - shoulder_before), 0.1);  // the arm answers as a whole
    // The impulse along the elbow's coordinate takes (1 - e^2) v^2 / (2 (H^-1)_kk) of the
    // kinetic energy: none at e = 1.
    const Real lost = (1 - e * e) * before * before / (2 * h_inv_elbow);
    std::printf("  energy lost %.12f J, closed form %.12f J\n", energy_before - energy_after, lost);
    EXPECT_NEAR(energy_before - energy_after, lost, 1e-12 * energy_before);
  }
}

TEST(JointLimits, APendulumRestsOnItsLimitWhereTheSpringHoldsItsWeight) {
  Real overshoot[2];
  const Real steps[2] = {0.002, 0.001};
  for (int run = 0; run < 2; ++run) {
    const Real dt = steps[run];
    // Released at -0.5 rad, it swings toward 0 and stops on its upper limit -0.3 rad.
    Simulation sim(parse_scene(
        arm(9.81, R"("q0": [-0.5], "damping": 0.5, "lower": [-1], "upper": [-0.3])", "", dt),
        "arm.json"));
    for (int frame = 0; frame < 150; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
    const CompiledFigure& figure = sim.model.figures[0];
    ASSERT_EQ(figure.limits.size(), 1u);
    // One DOF: its apparent inertia is H itself, about the hinge.
    FigureWorkspace ws;
    size_figure_workspace(figure.model, ws);
    MatX H;
    joint_space_inertia(figure.model, figure.q0.data(), ws, H);
    const Real k = H(0, 0) * (0.5 / dt) * (0.5 / dt);
    EXPECT_NEAR(figure.limits[0].stiffness, k, 1e-12 * k);
    // Rest: k (q + 0.3) = -m g l sin q, with l = 0.3 m to the capsule's centre.
    const Real m = figure.model.segments[0].inertia.m, g = 9.81, l = 0.3;
    Real q = -0.3;
    for (int i = 0; i < 50; ++i) q = -0.3 - m * g * l * std::sin(q) / k;
    overshoot[run] = sim.state.q[0] + 0.3;
    std::printf(
        "dt %.3f s: k %.1f N m/rad, rest %.12f rad (closed form %.12f), overshoot %.3e "
        "rad, limit spring %.3e J\n",
        dt, k, sim.state.q[0], q, overshoot[run], sim.stats.figures[0].elastic);
    EXPECT_NEAR(sim.state.q[0], q, 1e-9);
    EXPECT_LT(std::abs(sim.state.v[0]), 1e-9);
    EXPECT_NEAR(sim.stats.figures[0].elastic, 0.5 * k * overshoot[run] * overshoot[run],
                1e-6 * 0.5 * k * overshoot[run] * overshoot[run]);
  }
  // k grows as 1 / dt^2: half the step, a quarter of the overshoot.
  EXPECT_NEAR(overshoot[1] / overshoot[0], 0.25, 0.01);
}

}  // namespace
}  // namespace pbm
