// Joint limits in the World (figure/joint_limits.h): a hinge striking its limit leaves at -e times
// its speed (e = 0, 0.5, 1); an elbow striking its limit in a swinging two-link arm keeps the
// arm's kinetic energy at e = 1 and moves the shoulder too; a pendulum held by its limit against
// gravity rests where the limit's spring balances its weight, the closed form at two steps (a
// shorter step, a harder limit); the spring's stiffness is k = I (0.5 / dt)^2. A spherical joint's
// swing cone: a rod swinging and twisting into it leaves at -e times its swing rate with its twist
// untouched, and a rod held out sideways rests on its cone where the spring holds its weight. Its
// twist limit: the twist's row is its angle's rate, and a rod twisting into the limit leaves at -e
// times its twist rate.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "figure/joint_limits.h"
#include "figure/joint_space_inertia.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "stage_watch.h"

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
  EXPECT_TRUE(test::step_until(
      sim, watch, [&] { return hit; }, 5000));
  return {before, after};
}

// The first figure's joint-space inertia H at the state.
MatX inertia(const Model& model, const State& state) {
  const FigureModel& figure = model.figures[0].model;
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  MatX H;
  joint_space_inertia(figure, state.q.data(), ws, H);
  return H;
}

MatX inverse_inertia(const Model& model, const State& state) {
  return inertia(model, state).inverse();
}

Real kinetic_energy(const Model& model, const State& state) {
  const VecX v = state.v.head(model.figures[0].model.n_v);
  return 0.5 * v.dot(inertia(model, state) * v);
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
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return hit; }, 5000));
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

// A rod (capsule r 0.05, straight half length 0.3, centre 0.35 m out along the child's z, 2 kg)
// on a spherical joint with a swing cone of 0.5 rad (0.3 with gravity). `orientation`: the joint
// frame's axes in the world's.
std::string rod_on_a_cone(Real g, Real e, Real cone, const std::string& orientation,
                          const std::string& v0) {
  char text[1536];
  std::snprintf(
      text, sizeof text,
      R"({"gravity": [0, 0, %.17g], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
                    "figures": [{"name": "rod", "segments": [
                      {"joint": {"kind": "spherical", "position": [0, 0, 1],
                                 "orientation": %s, "swing_limit": %.17g,
                                 "limit_restitution": %.17g, "damping": %g, "v0": %s},
                       "shape": {"kind": "capsule", "size": [0.05, 0.05, 0.3],
                                 "center": [0, 0, 0.35]}, "mass": 2}]}]})",
      -g, orientation.c_str(), cone, e, g > 0 ? 0.5 : 0.0, v0.c_str());
  return text;
}

TEST(JointLimits, ARodSwingingIntoItsConeLeavesWithItsRestitutionAndKeepsItsTwist) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    // Swinging at 2 rad/s about (1, 1, 0) / sqrt 2 and twisting at 1 rad/s about its own axis.
    Simulation sim(parse_scene(rod_on_a_cone(0, e, 0.5, "[1, 0, 0, 0]",
                                             "[1.4142135623730951, "
                                             "1.4142135623730951, 1]"),
                               "cone.json"));
    const JointLimit& cone = sim.model.figures[0].limits.at(0);
    ASSERT_TRUE(cone.swing);
    Real before = 0, after = 0, twist_before = 0, twist_after = 0, angle = 0;
    bool hit = false;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage != StepStage::impacts || hit) return;
      const Vec3 g = limit_row(cone, state.q.data());
      const Real rate = g.dot(state.v.head<3>());
      if (!done) {
        before = rate;
        twist_before = state.v[2];
        angle = limit_coordinate(cone, state.q.data());
      } else {
        after = rate;
        twist_after = state.v[2];
        hit = after != before;
      }
    };
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return hit; }, 2000));
    std::printf("e = %.1f: at %.6f rad, swing rate %.12f -> %.12f rad/s, twist %.15f -> %.15f\n", e,
                angle, before, after, twist_before, twist_after);
    EXPECT_GT(angle, 0.5);
    EXPECT_LT(angle, 0.5 + 2 * 0.001 * 2.1);  // found within the step that crossed it
    EXPECT_NEAR(after, -e * before, 1e-12 * std::abs(before));
    EXPECT_NEAR(twist_after, twist_before, 1e-12);
  }
}

TEST(JointLimits, ARodHeldOutSidewaysRestsOnItsConeWhereTheSpringHoldsItsWeight) {
  // The joint frame's z along the world's x (a quarter turn about y): the rod starts horizontal
  // and swings down until its cone of 0.3 rad holds it. At rest the cone's spring balances the
  // weight's torque: k (theta - 0.3) = m g d cos theta, d = 0.35 m.
  const Real g = 9.81;
  Simulation sim(parse_scene(
      rod_on_a_cone(g, 0, 0.3, "[0.7071067811865476, 0, 0.7071067811865476, 0]", "[0, 0, 0]"),
      "cone.json"));
  for (int frame = 0; frame < 250; ++frame) ASSERT_TRUE(advance_frame(sim).ok) << frame;
  const JointLimit& cone = sim.model.figures[0].limits.at(0);
  const Real k = cone.stiffness;
  Real theta = 0.3;
  for (int it = 0; it < 50; ++it) {  // Newton on k (theta - 0.3) - m g d cos theta
    const Real f = k * (theta - 0.3) - 2 * g * 0.35 * std::cos(theta);
    theta -= f / (k + 2 * g * 0.35 * std::sin(theta));
  }
  const Real rest = limit_coordinate(cone, sim.state.q.data());
  std::printf("k = %.6f N m/rad: rests at %.12f rad, closed form %.12f; speed %.2e rad/s\n", k,
              rest, theta, sim.state.v.norm());
  EXPECT_NEAR(rest, theta, 1e-9);
  EXPECT_LT(sim.state.v.norm(), 1e-8);
  EXPECT_NEAR(sim.stats.figures[0].elastic, 0.5 * k * (rest - 0.3) * (rest - 0.3), 1e-12);
  // The spring is the swing's: k = I (0.5 / dt)^2 with I the rod's inertia about the joint across
  // its axis, m (d^2 + ...) from H at q0: at least m d^2.
  EXPECT_GT(k, 2 * 0.35 * 0.35 * 250 * 250);
}

// The twist limit's coordinate and row (figure/joint_limits.h): a pure twist about z by 0.3 rad
// is psi = 0.3, a swing alone leaves psi = 0, and g . omega is psi's rate, against a central
// difference of psi along q (0, omega) / 2 at random orientations and rates.
TEST(JointLimits, TheTwistsRowIsItsAnglesRate) {
  const JointLimit twist{.twist = true, .lower = -1, .upper = 1};
  const auto psi = [&](const Eigen::Quaterniond& u) {
    const Real q[4] = {u.w(), u.x(), u.y(), u.z()};
    return limit_coordinate(twist, q);
  };
  EXPECT_NEAR(psi(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3::UnitZ()))), 0.3, 1e-15);
  EXPECT_NEAR(psi(Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Vec3(1, 2, 0).normalized()))), 0,
              1e-15);
  // A swing after a twist: the twist is read back through the swing.
  EXPECT_NEAR(psi(Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Vec3(0, 1, 0))) *
                  Eigen::Quaterniond(Eigen::AngleAxisd(-0.4, Vec3::UnitZ()))),
              -0.4, 1e-15);
  std::srand(7);
  Real worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Quaterniond u = Eigen::Quaterniond(Vec4::Random().normalized());
    const Vec3 omega = Vec3::Random();
    const Real h = 1e-6;
    const auto turned = [&](Real t) {
      return u * Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * t, omega.normalized()));
    };
    const Real q[4] = {u.w(), u.x(), u.y(), u.z()};
    const Real rate = limit_row(twist, q).dot(omega);
    Real difference = psi(turned(h)) - psi(turned(-h));
    // Across the wrap at +-pi the angle jumps by 2 pi.
    if (difference > std::numbers::pi) difference -= 2 * std::numbers::pi;
    if (difference < -std::numbers::pi) difference += 2 * std::numbers::pi;
    worst = std::max(worst, std::abs(difference / (2 * h) - rate) / (1 + std::abs(rate)));
  }
  std::printf("twist row against a central difference: worst relative error %.2e\n", worst);
  EXPECT_LT(worst, 1e-7);
}

// A rod on a spherical joint twisting at 2 rad/s about its own axis (and swinging at 0.3 rad/s)
// strikes its twist limit of 0.5 rad and leaves at -e times its twist rate (e = 0, 0.5, 1); after
// it, the twist stays within the limit and the spring's small overshoot.
TEST(JointLimits, ARodTwistingIntoItsLimitLeavesWithItsRestitution) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    char text[1024];
    std::snprintf(text, sizeof text,
                  R"({"gravity": [0, 0, 0], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
            "figures": [{"name": "rod", "segments": [
              {"joint": {"kind": "spherical", "position": [0, 0, 1], "twist_limit": 0.5,
                         "limit_restitution": %.17g, "v0": [0.3, 0, 2]},
               "shape": {"kind": "capsule", "size": [0.05, 0.05, 0.3], "center": [0, 0, 0.35]},
               "mass": 2}]}]})",
                  e);
    Simulation sim(parse_scene(text, "twist.json"));
    const JointLimit& limit = sim.model.figures[0].limits.at(0);
    ASSERT_TRUE(limit.twist);
    Real before = 0, after = 0, angle = 0;
    bool hit = false;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage != StepStage::impacts || hit) return;
      const Real rate = limit_row(limit, state.q.data()).dot(state.v.head<3>());
      if (!done) {
        before = rate;
        angle = limit_coordinate(limit, state.q.data());
      } else {
        after = rate;
        hit = after != before;
      }
    };
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return hit; }, 2000));
    std::printf("e = %.1f: at %.6f rad, twist rate %.12f -> %.12f rad/s\n", e, angle, before,
                after);
    EXPECT_GT(angle, 0.5);
    EXPECT_LT(angle, 0.5 + 0.001 * 2.1);  // found within the step that crossed it
    EXPECT_NEAR(after, -e * before, 1e-12 * std::abs(before));
    Real largest = 0;
    for (int frame = 0; frame < 50; ++frame) {
      ASSERT_TRUE(advance_frame(sim).ok);
      largest = std::max(largest, std::abs(limit_coordinate(limit, sim.state.q.data())));
    }
    EXPECT_LT(largest, 0.5 + 0.01);
  }
}

}  // namespace
}  // namespace pbm
