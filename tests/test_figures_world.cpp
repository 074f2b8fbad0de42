// Articulated figures in the World (sim/stages_figures.h): a figure read from a scene file steps
// with the World's integrators as the articulated-body method integrated on its own does, its
// energies are the closed-form ones, an undamped chain keeps its energy, joint damping decays a
// swing as the closed form says, a body beside a figure moves as it does alone, and the snapshot
// draws every segment.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "figure/articulated_body.h"
#include "figure/figure_build.h"
#include "figure_rk4.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"
#include "stage_watch.h"

namespace pbm {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

// n capsules hanging from a hinge 2 m up, each joined to the last by a revolute joint about y
// (every third a spherical joint), released from `angle` about y.
std::string chain_scene(int n, const std::string& integrator, Real damping = 0, Real angle = 0.6) {
  std::string segments;
  for (int i = 0; i < n; ++i) {
    const bool spherical = i % 3 == 2;
    const std::string q0 =
        i > 0 ? (spherical ? "[1, 0, 0, 0]" : "[0.2]") : "[" + std::to_string(angle) + "]";
    segments += std::string(i ? ", " : "") + "{\"name\": \"s" + std::to_string(i) + "\"" +
                (i ? ", \"parent\": \"s" + std::to_string(i - 1) + "\"" : "") +
                ", \"joint\": {\"kind\": \"" + (spherical ? "spherical" : "revolute") + "\"" +
                (spherical ? "" : ", \"axis\": [0, 1, 0]") + ", \"position\": [0, 0, " +
                (i ? "-0.6" : "2") + "], \"damping\": " + std::to_string(damping) +
                ", \"q0\": " + q0 + (spherical ? ", \"v0\": [0.3, 0, 0.5]" : "") +
                "}, \"shape\": {\"kind\": \"capsule\", \"size\": [0.05, 0.05, 0.25], " +
                "\"center\": [0, 0, -0.3]}}";
  }
  return R"({"name": "chain", "solver": {"dt": 0.002, "fps": 50, "integrator": ")" + integrator +
         R"("}, "figures": [{"name": "chain", "segments": [)" + segments + "]}]}";
}

Real total_energy(const FrameStats& s) {
  return s.kinetic + s.potential;
}

TEST(FiguresWorld, EnergiesAreTheClosedFormOnes) {
  // One capsule pendulum at angle 0.4 rad, swinging at 1.5 rad/s.
  const Scene scene = parse_scene(
      R"({"figures": [{"segments": [{"joint": {"axis": [0, 1, 0], "position": [0, 0, 2],
          "q0": [0.4], "v0": [1.5]}, "shape": {"kind": "capsule", "size": [0.05, 0.05, 0.25],
          "center": [0, 0, -0.35]}}]}]})",
      "pendulum.json");
  Simulation sim(scene);
  const SegmentShapeDef& shape = scene.figures[0].segments[0].shape;
  const Real m = 1000 * shape_volume(shape);
  const Real d = 0.35;
  const Real I_pivot = shape_inertia(shape, m)(1, 1) + m * d * d;
  EXPECT_NEAR(sim.stats.kinetic, 0.5 * I_pivot * 1.5 * 1.5, 1e-12);
  // The centre of mass R_y(0.4) (0, 0, -d) below the pivot at z = 2.
  EXPECT_NEAR(sim.stats.potential, m * 9.81 * (2 - d * std::cos(0.4)), 1e-11);
  EXPECT_EQ(sim.stats.elastic, 0);
}

TEST(FiguresWorld, StepsAsTheArticulatedBodyMethodIntegratedAlone) {
  Simulation sim(parse_scene(chain_scene(4, "rk4"), "chain.json"));
  const FigureModel& figure = sim.model.figures[0].model;
  VecX q = sim.model.figures[0].q0, v = sim.model.figures[0].v0;
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  const VecX tau = VecX::Zero(figure.n_v);
  auto rates = [&](const VecX& qq, const VecX& vv, VecX& q_dot, VecX& v_dot) {
    q_dot.resize(figure.n_q);
    v_dot.resize(figure.n_v);
    figure_q_dot(figure, qq.data(), vv.data(), q_dot.data());
    forward_dynamics(figure, qq.data(), vv.data(), tau.data(), {}, Vec3(0, 0, -9.81), ws,
                     v_dot.data());
  };
  for (int frame = 0; frame < 50; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    for (int k = 0; k < 10; ++k) test::figure_rk4_step(figure, q, v, 0.002, rates);
  }
  EXPECT_EQ(sim.stats.substeps, 10);
  const Real q_error = (sim.state.q - q).cwiseAbs().maxCoeff();
  const Real v_error = (sim.state.v - v).cwiseAbs().maxCoeff();
  std::printf("after 1 s: |q - q_alone| %.2e, |v - v_alone| %.2e\n", q_error, v_error);
  EXPECT_LT(q_error, 1e-12);
  EXPECT_LT(v_error, 1e-11);
}

TEST(FiguresWorld, AnUndampedChainKeepsItsEnergy) {
  // RK4 at dt = 2 ms over 10 s (the issue's span): the chain swings through 95 J of kinetic
  // energy.
  Simulation sim(parse_scene(chain_scene(5, "rk4"), "chain.json"));
  const Real e0 = total_energy(sim.stats);
  Real drift = 0, largest_kinetic = 0;
  for (int frame = 0; frame < 500; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    drift = std::max(drift, std::abs(total_energy(sim.stats) - e0));
    largest_kinetic = std::max(largest_kinetic, sim.stats.kinetic);
  }
  std::printf("undamped: largest kinetic %.4f J, energy drift %.2e J (%.2e relative)\n",
              largest_kinetic, drift, drift / largest_kinetic);
  EXPECT_GT(largest_kinetic, 1.0);
  EXPECT_LT(drift / largest_kinetic, 1e-6);
}

TEST(FiguresWorld, AJointsDampingDecaysASwingAsTheLinearOscillatorDoes) {
  // A capsule pendulum released 1 mrad from rest under joint damping d: at that amplitude it is
  // the oscillator I theta'' + d theta' + m g l theta = 0 (the nonlinearity is 1e-7 of theta),
  // whose solution is theta = A e^(-s t) (cos w t + s / w sin w t), s = d / (2 I),
  // w = sqrt(m g l / I - s^2), with I about the pivot.
  const Real A = 1e-3, d = 0.5;
  const Scene scene = parse_scene(
      R"({"solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"}, "figures": [{"segments": [
          {"joint": {"axis": [0, 1, 0], "position": [0, 0, 2], "damping": 0.5, "q0": [0.001]},
           "shape": {"kind": "capsule", "size": [0.05, 0.05, 0.25],
           "center": [0, 0, -0.35]}}]}]})",
      "pendulum.json");
  Simulation sim(scene);
  const SegmentShapeDef& shape = scene.figures[0].segments[0].shape;
  const Real m = 1000 * shape_volume(shape), l = 0.35;
  const Real I = shape_inertia(shape, m)(1, 1) + m * l * l;
  const Real s = d / (2 * I), w = std::sqrt(m * 9.81 * l / I - s * s);
  Real worst = 0;
  for (int frame = 0; frame < 250; ++frame) {  // 5 s, about 5 periods
    ASSERT_TRUE(advance_frame(sim).ok);
    const Real t = sim.state.time;
    const Real expected = A * std::exp(-s * t) * (std::cos(w * t) + s / w * std::sin(w * t));
    worst = std::max(worst, std::abs(sim.state.q[0] - expected));
  }
  std::printf(
      "damped pendulum: decay %.4f 1/s, period %.4f s; worst |theta - closed form| "
      "%.2e rad of %.0e\n",
      s, 2 * std::numbers::pi / w, worst, A);
  EXPECT_LT(worst, 1e-3 * A);
  // Without the damping the swing would keep its amplitude: e^(-5 s) is 0.15 here, so a run that
  // ignored d would be 0.85 A off by the end.
  EXPECT_LT(std::exp(-s * 5), 0.2);
}

TEST(FiguresWorld, ABodyBesideAFigureMovesAsItDoesAlone) {
  const std::string body = R"({"name": "ball", "position": [3, 0, 1], "velocity": [0, 0, 2],
      "material": {"mass": 1}})";
  const std::string alone = R"({"solver": {"dt": 0.002, "fps": 50}, "bodies": [)" + body + "]}";
  std::string both = chain_scene(3, "euler");
  both.insert(1, R"("bodies": [)" + body + "], ");
  Simulation a(parse_scene(alone, "alone.json")), b(parse_scene(both, "both.json"));
  ASSERT_EQ(b.model.figures[0].model.state_q_offset, a.model.n_q);
  for (int frame = 0; frame < 25; ++frame) {
    ASSERT_TRUE(advance_frame(a).ok);
    ASSERT_TRUE(advance_frame(b).ok);
  }
  EXPECT_TRUE(a.state.q == b.state.q.head(a.model.n_q));
  EXPECT_TRUE(a.state.v == b.state.v.head(a.model.n_v));
  EXPECT_NE(b.state.q.tail(b.model.figures[0].model.n_q), b.model.figures[0].q0);
}

// A box on a sprung revolute joint about z, without gravity, released 0.2 rad from its spring's
// rest 0.1 rad: a torsional oscillator, q = 0.1 + 0.2 cos(sqrt(k / I_zz) t).
TEST(FiguresWorld, AJointSpringOscillatesAtItsClosedFormFrequency) {
  const Scene scene = parse_scene(
      R"({"gravity": [0, 0, 0], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
          "figures": [{"segments": [{"joint": {"stiffness": 3, "rest": [0.1], "q0": [0.3]},
          "shape": {"kind": "box", "size": [0.3, 0.1, 0.05]}}]}]})",
      "torsion.json");
  Simulation sim(scene);
  const SegmentShapeDef& shape = scene.figures[0].segments[0].shape;
  const Real I = shape_inertia(shape, 1000 * shape_volume(shape))(2, 2);
  const Real w = std::sqrt(3 / I);
  EXPECT_NEAR(sim.stats.elastic, 0.5 * 3 * 0.2 * 0.2, 1e-15);
  Real worst = 0;
  for (int frame = 0; frame < 100; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    worst = std::max(worst, std::abs(sim.state.q[0] - (0.1 + 0.2 * std::cos(w * sim.state.time))));
  }
  std::printf("torsion spring: period %.4f s, worst |q - closed form| %.2e rad\n",
              2 * std::numbers::pi / w, worst);
  EXPECT_LT(worst, 1e-8);
}

// A spherical joint's spring keeps kinetic plus spring energy (no gravity, RK4): a spring of the
// wrong sign would trade them the other way, and one that is not the gradient of k |theta|^2 / 2
// would drift.
TEST(FiguresWorld, ASphericalSpringKeepsItsEnergy) {
  Simulation sim(parse_scene(
      R"({"gravity": [0, 0, 0], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
          "figures": [{"segments": [{"joint": {"kind": "spherical", "stiffness": 4,
          "rest": [0.9, 0.1, 0.3, 0], "q0": [1, 0.4, -0.2, 0.3], "v0": [0.5, -1, 2]},
          "shape": {"kind": "box", "size": [0.3, 0.15, 0.05], "center": [0.2, 0, 0]}}]}]})",
      "ball.json"));
  const Real e0 = sim.stats.kinetic + sim.stats.elastic;
  Real drift = 0, largest_elastic = 0;
  for (int frame = 0; frame < 150; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    drift = std::max(drift, std::abs(sim.stats.kinetic + sim.stats.elastic - e0));
    largest_elastic = std::max(largest_elastic, sim.stats.elastic);
  }
  std::printf("spherical spring: energy %.4f J, spring energy up to %.4f J, drift %.2e J\n", e0,
              largest_elastic, drift);
  EXPECT_GT(largest_elastic, 0.1 * e0);
  EXPECT_LT(drift, 1e-8 * e0);
}

TEST(FiguresWorld, RunsAreBitIdentical) {
  Simulation a(parse_scene(chain_scene(6, "rk45"), "chain.json"));
  Simulation b(parse_scene(chain_scene(6, "rk45"), "chain.json"));
  for (int frame = 0; frame < 20; ++frame) {
    ASSERT_TRUE(advance_frame(a).ok);
    ASSERT_TRUE(advance_frame(b).ok);
  }
  EXPECT_EQ(hash_state(a.state), hash_state(b.state));
}

TEST(FiguresWorld, TheSnapshotDrawsEverySegmentWhereItIs) {
  Simulation sim(parse_scene(chain_scene(3, "euler", 0, kPi / 2), "chain.json"));
  const draw::Snapshot snap = make_snapshot(sim);
  ASSERT_EQ(snap.primitives.size(), 3u);
  // The first capsule, turned a right angle about y: its centre 0.3 m from the pivot along -z
  // turned to -x, its long axis along x.
  const draw::Primitive& p = snap.primitives[0];
  EXPECT_EQ(p.shape, draw::PrimitiveShape::capsule);
  EXPECT_NEAR(p.center.x(), -0.3f, 1e-6f);
  EXPECT_NEAR(p.center.z(), 2.0f, 1e-6f);
  EXPECT_NEAR(std::abs(p.rotation.col(2).x()), 1.0f, 1e-6f);
  EXPECT_FALSE(snap.focus.empty());
  // The overlays: the revolute joints' axes (along y, the first at the pivot), a dot at the
  // spherical joint.
  ASSERT_EQ(snap.lines.size(), 1u);
  ASSERT_EQ(snap.lines[0].points.size(), 4u);
  EXPECT_EQ(snap.lines[0].layer, draw::Layer::overlay);
  const draw::Vec3f middle = 0.5f * (snap.lines[0].points[0] + snap.lines[0].points[1]);
  EXPECT_LT((middle - draw::Vec3f(0, 0, 2)).norm(), 1e-6f);
  EXPECT_NEAR(std::abs((snap.lines[0].points[1] - snap.lines[0].points[0]).normalized().y()), 1.0f,
              1e-6f);
  ASSERT_EQ(snap.points.size(), 1u);
  EXPECT_EQ(snap.points[0].positions.size(), 1u);
}

TEST(FiguresWorld, AFigureGoneNaNIsNamed) {
  Simulation sim(parse_scene(chain_scene(3, "euler"), "chain.json"));
  sim.state.v[1] = std::nan("");
  const FrameResult result = advance_frame(sim);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("figure 'chain', segment '"), std::string::npos) << result.message;
}

// Joint damping far past explicit Euler's limit (dt d / I > 2) makes the swing grow every step:
// the guard stops the run naming the figure.
TEST(FiguresWorld, AFigureWhoseEnergyGrowsIsNamed) {
  Scene scene = parse_scene(chain_scene(3, "rk4", 60), "chain.json");
  scene.solver.max_retries = 0;
  // Under RK4 the joint damping is explicit, and the World keeps the substep below the chain's
  // fastest damped mode, where it runs without a retry. Past it (the step the scene asks for,
  // 2 ms), as at a pose where the limit's inertia no longer holds, the energy grows and the guard
  // names the figure.
  Model model = build_model(scene);
  {
    Simulation limited(scene);
    EXPECT_LT(limited.model.substep, 0.002);
    FrameResult ok;
    for (int frame = 0; frame < 30 && ok.ok; ++frame) ok = advance_frame(limited);
    EXPECT_TRUE(ok.ok) << ok.message;
  }
  model.substep = scene.solver.dt;
  const World world = make_world(model);
  Workspace ws;
  init_workspace(world, ws);
  State state = initial_state(model);
  FrameStats stats;
  const Inputs inputs;
  measure_state(world, inputs, state, ws, stats);
  FrameResult result;
  for (int frame = 0; frame < 30 && result.ok; ++frame) {
    result = advance_frame(world, inputs, state, ws, stats);
  }
  std::printf("%s\n", result.message.c_str());
  EXPECT_FALSE(result.ok);
  EXPECT_EQ(result.message.rfind("figure 'chain'", 0), 0u) << result.message;
}

// A 1 kg box (0.4 x 0.2 x 0.1 m) on a free joint over a floor of friction mu, its centre at
// height z moving at (vx, 0, vz), with restitution e.
Scene box_over_floor(Real z, Real vx, Real vz, Real e, Real mu) {
  char text[1024];
  std::snprintf(text, sizeof text,
                R"({"solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
                    "obstacles": [{"name": "floor", "friction": %.17g}],
                    "figures": [{"name": "box", "restitution": %.17g, "segments": [
                      {"joint": {"kind": "free", "q0": [0, 0, %.17g, 1, 0, 0, 0],
                                 "v0": [0, 0, 0, %.17g, 0, %.17g]},
                       "shape": {"kind": "box", "size": [0.2, 0.1, 0.05]}, "mass": 1}]}]})",
                mu, e, z, vx, vz);
  return parse_scene(text, "box.json");
}

constexpr Real kG = 9.81, kContactStiffness = 2e4;
// Where the box rests: its four lower corners share its weight over their springs.
constexpr Real kRestHeight = 0.05 - kG / (4 * kContactStiffness);

TEST(FiguresWorld, ABoxDroppedOnTheFloorLeavesWithItsRestitution) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    Simulation sim(box_over_floor(1.0, 0, 0, e, 0.5));
    Real before = 0, after = 0;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage != StepStage::impacts) return;
      (done ? after : before) = state.v[5];
    };
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return after > before; }, 1000));
    std::printf("e = %.1f: v_z %.6f -> %.12f m/s\n", e, before, after);
    ASSERT_LT(before, -4.0);  // it fell 1 m
    EXPECT_NEAR(after, -e * before, 1e-9 * std::abs(before));
    // Level, it stays level: the four corners' impulses are equal.
    EXPECT_LT(sim.state.v.head(3).norm(), 1e-9);
  }
}

// A sphere on a free joint, no gravity, falling at 2 m/s onto a floor that rises at 1 m/s (a
// track drives its point): the impact's law (15.2) holds relative to the floor, so the sphere
// leaves at 1 + 3 e m/s.
TEST(FiguresWorld, AnImpactOnAMovingFloorTakesTheFloorsVelocity) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    char text[1024];
    std::snprintf(text, sizeof text,
                  R"({"gravity": [0, 0, 0], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
                      "obstacles": [{"name": "floor"}],
                      "tracks": [{"target": "obstacles[0].point[2]", "interpolation": "linear",
                                  "keys": [[0, 0], [1, 1]]}],
                      "figures": [{"name": "ball", "restitution": %.17g, "segments": [
                        {"joint": {"kind": "free", "q0": [0, 0, 0.5, 1, 0, 0, 0],
                                   "v0": [0, 0, 0, 0, 0, -2]},
                         "shape": {"kind": "sphere", "size": [0.1, 0.1, 0.1]}, "mass": 1}]}]})",
                  e);
    Simulation sim(parse_scene(text, "moving-floor.json"));
    Real before = 0, after = 0;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage == StepStage::impacts) (done ? after : before) = state.v[5];
    };
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return after != before; }, 1000));
    std::printf("e = %.1f: v_z %.12f -> %.12f m/s at t = %.3f s\n", e, before, after,
                sim.state.time);
    EXPECT_EQ(before, -2.0);
    EXPECT_NEAR(after, 1 + 3 * e, 1e-12);
  }
}

TEST(FiguresWorld, ABoxRestsOnTheFloorWhereItsWeightBalancesTheSprings) {
  Simulation sim(box_over_floor(0.3, 0, 0, 0, 0.5));
  for (int frame = 0; frame < 100; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  std::printf("rest height %.9f m (closed form %.9f), speed %.2e m/s, %d contacts\n",
              sim.state.q[2], kRestHeight, sim.state.v.norm(), sim.stats.figures[0].contacts);
  EXPECT_NEAR(sim.state.q[2], kRestHeight, 1e-7);
  EXPECT_LT(sim.state.v.norm(), 1e-6);
  EXPECT_EQ(sim.stats.figures[0].contacts, 4);
  EXPECT_NEAR(sim.stats.figures[0].elastic,
              4 * 0.5 * kContactStiffness * std::pow(0.05 - kRestHeight, 2), 1e-9);
}

TEST(FiguresWorld, ABoxSlidesTheDistanceCoulombsLawGives) {
  // Sliding at 2 m/s on mu = 0.5 it decelerates at mu g and stops after v^2 / (2 mu g).
  const Real v0 = 2, mu = 0.5;
  Simulation sim(box_over_floor(kRestHeight, v0, 0, 0, mu));
  for (int frame = 0; frame < 100; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  const Real expected = v0 * v0 / (2 * mu * kG);
  std::printf("slid %.5f m (Coulomb: %.5f m), speed now %.2e m/s\n", sim.state.q[0], expected,
              sim.state.v.norm());
  EXPECT_NEAR(sim.state.q[0], expected, 0.01 * expected);
  EXPECT_LT(sim.state.v.norm(), 1e-3);
}

}  // namespace
}  // namespace pbm
