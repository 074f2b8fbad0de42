// Impulse events and site actuators in the World (sim/stages_figure_control.h): an impulse is
// applied exactly once, in the substep that holds its time, whatever the step, the frame rate and
// the integrator; its work is input work, so the stability guard takes a huge one without a
// retry; a site actuator on a free body is the closed-form damped oscillator and never passes its
// max_force; and the book's scenes that use them (the soldier of fig. 15.6, the marionette) do
// what they show.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "figure/figure_build.h"
#include "figure_points.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

// A capsule pendulum at rest about y, 2 m up, without gravity, struck at its tip (0.6 m below
// the pivot) by `impulse` along x at t = 0.2 s.
std::string struck_pendulum(Real dt, Real fps, const std::string& integrator, Real impulse) {
  return R"({"gravity": [0, 0, 0], "solver": {"dt": )" + std::to_string(dt) + R"(, "fps": )" +
         std::to_string(fps) + R"(, "integrator": ")" + integrator +
         R"("}, "figures": [{"segments": [{"name": "rod", "joint": {"axis": [0, 1, 0],
         "position": [0, 0, 2]}, "shape": {"kind": "capsule", "size": [0.05, 0.05, 0.25],
         "center": [0, 0, -0.3]}, "sites": [{"name": "tip", "position": [0, 0, -0.6]}]}],
         "impulses": [{"time": 0.2, "segment": "rod", "site": "tip", "impulse": [)" +
         std::to_string(impulse) + R"(, 0, 0]}]}]})";
}

Real pivot_inertia(const Scene& scene) {
  const SegmentShapeDef& shape = scene.figures[0].segments[0].shape;
  const Real m = 1000 * shape_volume(shape);
  return shape_inertia(shape, m)(1, 1) + m * 0.3 * 0.3;
}

TEST(FigureEventsWorld, ImpulseFallsInExactlyOneSubstep) {
  struct Case {
    Real dt, fps;
    const char* integrator;
  };
  for (const Case& k : {Case{0.001, 30, "rk4"}, Case{0.003, 24, "rk4"}, Case{0.0005, 60, "euler"},
                        Case{0.002, 50, "rk45"}, Case{0.01, 10, "rk4"}}) {
    const Scene scene = parse_scene(struck_pendulum(k.dt, k.fps, k.integrator, 2), "struck.json");
    Simulation sim(scene);
    // (0, 0, -0.6) x (2, 0, 0) = (0, -1.2, 0): the angular impulse about the pivot's y.
    const Real omega = -1.2 / pivot_inertia(scene);
    bool before = true;
    while (sim.state.time < 0.5 - 1e-9) {
      ASSERT_TRUE(advance_frame(sim).ok);
      const Real v = sim.state.v[0];
      if (sim.state.time < 0.2 - k.dt) {
        EXPECT_EQ(v, 0) << "t = " << sim.state.time;
      } else if (sim.state.time > 0.2 + 1e-9) {
        // Once, not twice: the free rotation keeps exactly the impulse's rate.
        EXPECT_NEAR(v, omega, 1e-12 * std::abs(omega)) << k.integrator << " dt " << k.dt;
        before = false;
      }
    }
    EXPECT_FALSE(before);
    // Applied at the start of the substep that holds t = 0.2: at most one dt early.
    const Real q = sim.state.q[0];
    EXPECT_LE(std::abs(q - omega * (sim.state.time - 0.2)), std::abs(omega) * k.dt * (1 + 1e-9))
        << k.integrator << " dt " << k.dt;
    // Its work is the kinetic energy it gave, and the run-level guard sees no surplus.
    const Real kinetic = 0.5 * pivot_inertia(scene) * omega * omega;
    EXPECT_NEAR(sim.stats.figures[0].work, kinetic, 1e-12 * kinetic);
    EXPECT_NEAR(sim.stats.kinetic, kinetic, 1e-9 * kinetic);
    EXPECT_LT(sim.stats.energy_surplus, 1e-9 * kinetic);
  }
}

TEST(FigureEventsWorld, GuardTakesAHugeImpulseAsInputWork) {
  // 10^4 N s on a 4 kg rod: 10^8 J in one substep, from rest. Counted as the inputs' work, the
  // frame is accepted at once; the energy stays what the impulse gave.
  const Scene scene = parse_scene(struck_pendulum(0.001, 30, "rk4", 1e4), "struck.json");
  Simulation sim(scene);
  const Real omega = -0.6e4 / pivot_inertia(scene);  // (0, 0, -0.6) x (10^4, 0, 0)
  const Real kinetic = 0.5 * pivot_inertia(scene) * omega * omega;
  ASSERT_GT(kinetic, 1e7);
  for (int frame = 0; frame < 15; ++frame) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    EXPECT_EQ(sim.stats.retries, 0) << "frame " << frame;
  }
  EXPECT_NEAR(sim.state.v[0], omega, 1e-12 * std::abs(omega));
  EXPECT_NEAR(sim.stats.kinetic + sim.stats.potential, 0, 1e-9 * kinetic);  // potential: -work
  EXPECT_LT(sim.stats.energy_surplus, 1e-9 * kinetic);
}

// A free sphere (radius 0.1 m, 1000 kg/m^3) at the origin without gravity, its centre pulled
// toward (1, 0, 0) by a site actuator of stiffness k and damping d.
std::string pulled_sphere(Real k, Real d, const std::string& max_force) {
  return R"({"gravity": [0, 0, 0], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
         "figures": [{"segments": [{"name": "ball", "joint": {"kind": "free"},
         "shape": {"kind": "sphere", "size": [0.1, 0.1, 0.1]}}],
         "site_actuators": [{"segment": "ball", "x": [[0, 1]], "y": [[0, 0]], "z": [[0, 0]],
         "stiffness": )" +
         std::to_string(k) + R"(, "damping": )" + std::to_string(d) + max_force + "}]}]}";
}

// The ball's centre in the world: the free joint's position coordinates.
Vec3 ball_position(const Simulation& sim) {
  return sim.state.q.segment<3>(sim.model.figures[0].model.state_q_offset);
}

TEST(FigureEventsWorld, SitePullOnAFreeBodyIsTheDampedOscillator) {
  const Real k = 100, d = 4;
  const Scene scene = parse_scene(pulled_sphere(k, d, ""), "pulled.json");
  Simulation sim(scene);
  const Real m = 1000 * shape_volume(scene.figures[0].segments[0].shape);
  const Real w0 = std::sqrt(k / m), zeta = d / (2 * std::sqrt(k * m));
  const Real wd = w0 * std::sqrt(1 - zeta * zeta);
  Real worst = 0;
  while (sim.state.time < 2 - 1e-9) {
    ASSERT_TRUE(advance_frame(sim).ok);
    const Real t = sim.state.time;
    const Real x =
        1 - std::exp(-zeta * w0 * t) * (std::cos(wd * t) + zeta * w0 / wd * std::sin(wd * t));
    const Vec3 p = ball_position(sim);
    worst = std::max(worst, std::abs(p.x() - x));
    EXPECT_LT(std::abs(p.y()) + std::abs(p.z()), 1e-12);
    // The frame's sample: target, site and the force on it.
    const SitePull& pull = sim.stats.figures[0].site_actuators.at(0);
    EXPECT_EQ(pull.target, Vec3(1, 0, 0));
    EXPECT_NEAR((pull.position - p).norm(), 0, 1e-12);
    EXPECT_NEAR(pull.force.x(), k * (1 - p.x()) - d * pull.velocity.x(), 1e-9);
  }
  EXPECT_LT(worst, 1e-9);  // RK4 at dt = 1 ms on a 0.8 s period
  // The actuator's work is what the ball holds: kinetic energy, no potential of its own.
  EXPECT_NEAR(sim.stats.figures[0].work, sim.stats.kinetic, 1e-6 * (1 + sim.stats.kinetic) + 1e-9);
  EXPECT_LT(sim.stats.energy_surplus, 1e-6);
}

TEST(FigureEventsWorld, SitePullNeverPassesItsMaxForce) {
  // A stiff string (10^5 N/m, 1 m away: 10^5 N asked) held at 5 N: the ball accelerates at
  // 5 / m along x until it nears the target.
  const Scene scene = parse_scene(pulled_sphere(1e5, 0, R"(, "max_force": 5)"), "pulled.json");
  Simulation sim(scene);
  const Real m = 1000 * shape_volume(scene.figures[0].segments[0].shape);
  while (sim.state.time < 0.2 - 1e-9) {
    ASSERT_TRUE(advance_frame(sim).ok);
    const SitePull& pull = sim.stats.figures[0].site_actuators.at(0);
    EXPECT_TRUE(pull.saturated);
    EXPECT_NEAR(pull.force.norm(), 5, 1e-12);
    EXPECT_NEAR(pull.velocity.x(), 5 / m * sim.state.time, 1e-12);
  }
  EXPECT_NEAR(ball_position(sim).x(), 0.5 * 5 / m * 0.04, 1e-12);
}

// The segment's world frame at the simulation's state.
SpatialTransform segment_frame(const Simulation& sim, int segment) {
  const FigureModel& figure = sim.model.figures[0].model;
  return test::pose_of(figure, sim.state.q.data() + figure.state_q_offset).world[segment];
}

int segment_index(const Simulation& sim, const std::string& name) {
  const FigureModel& figure = sim.model.figures[0].model;
  for (int i = 0; i < figure.size(); ++i) {
    if (figure.segments[i].name == name) return i;
  }
  return -1;
}

Real max_speed(const Simulation& sim) {
  const FigureModel& figure = sim.model.figures[0].model;
  return sim.state.v.segment(figure.state_v_offset, figure.n_v).cwiseAbs().maxCoeff();
}

TEST(FigureEventsWorld, SoldierStandsThenFallsOnHisBack) {
  Simulation sim(load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/soldier.json"));
  const int torso = segment_index(sim, "torso");
  ASSERT_GE(torso, 0);
  const Real shot = sim.model.scene.figures[0].impulses.at(0).time;
  // Standing on his own feet (his joints' springs) until the shot.
  while (sim.state.time < shot - 0.05) ASSERT_TRUE(advance_frame(sim).ok);
  EXPECT_LT(max_speed(sim), 0.05) << "still before the shot";
  const Real standing = segment_frame(sim, torso).r.z();
  EXPECT_GT(standing, 0.95);
  // Landing: the first frame after the shot with the torso below 0.5 m. From then the ground
  // must take his energy: within 0.5 s his kinetic energy falls below 5% of its peak.
  const int standing_contacts = sim.stats.figures[0].contacts;
  int retries = 0;
  Real peak = 0, landed = -1, settled = -1;
  while (sim.state.time < sim.model.solver.duration - 1e-9) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    retries += sim.stats.retries;
    const Real kinetic = sim.stats.figures[0].kinetic;
    peak = std::max(peak, kinetic);
    if (landed < 0 && sim.state.time > shot && segment_frame(sim, torso).r.z() < 0.5) {
      landed = sim.state.time;
    }
    if (landed >= 0 && settled < 0 && sim.state.time >= landed + 0.5 - 1e-9) settled = kinetic;
  }
  std::printf(
      "soldier: %d contacts standing; kinetic peak %.1f J, landed at %.2f s, %.3f J 0.5 s "
      "later, %d contacts at the end\n",
      standing_contacts, peak, landed, settled, sim.stats.figures[0].contacts);
  EXPECT_EQ(retries, 0);
  ASSERT_GE(landed, 0) << "never landed";
  ASSERT_GE(settled, 0) << "landed too late to settle before the end";
  EXPECT_LT(settled, 0.05 * peak);
  EXPECT_GT(sim.stats.figures[0].contacts, standing_contacts) << "lying on more points";
  // On his back: the torso low, its front (the segment's x) facing up, at rest on the ground.
  const SpatialTransform t = segment_frame(sim, torso);
  const Vec3 front = t.E.transpose() * Vec3::UnitX();
  EXPECT_LT(t.r.z(), 0.3);
  EXPECT_GT(front.z(), 0.8) << "front " << front.transpose();
  EXPECT_LT(sim.stats.kinetic, 1.0);
}

}  // namespace
}  // namespace pbm
