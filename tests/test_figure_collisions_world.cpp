// Collisions between segments in the World (sim/figure_collisions.h, sec. 15.3): two figures'
// spheres meeting obliquely keep their total linear and angular momentum through the impact and
// leave with restitution e along the normal; a lamp's bob swinging into its own base bounces
// with e, rests where its weight's torque balances the contact spring's, and passes through
// when the pair is declared non-colliding; segments overlapping at the initial pose are named
// and left alone; runs stay bit-identical.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "figure/figure_build.h"
#include "figure_momentum.h"
#include "figure_points.h"
#include "scene/scene_json.h"
#include "sim/figure_collisions.h"
#include "sim/simulation.h"
#include "stage_watch.h"

namespace pbm {
namespace {

using test::momentum;

// Two 1 kg spheres of radius 0.1 on free joints, no gravity, closing at 4 m/s along x with their
// centres 0.08 m apart in y: an oblique impact with restitution e and friction mu.
Scene two_spheres(Real e, Real mu, bool collide = true) {
  char text[2048];
  std::snprintf(text, sizeof text,
                R"({"gravity": [0, 0, 0], "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
          "figures": [
            {"name": "a", "restitution": %.17g, "friction": %.17g, "figure_collisions": %s,
             "segments": [{"joint": {"kind": "free", "q0": [-0.5, 0, 1, 1, 0, 0, 0],
                                     "v0": [0, 0, 0, 2, 0, 0]},
                           "shape": {"kind": "sphere", "size": [0.1, 0.1, 0.1]}, "mass": 1}]},
            {"name": "b", "restitution": 1, "friction": %.17g,
             "segments": [{"joint": {"kind": "free", "q0": [0.5, 0.08, 1, 1, 0, 0, 0],
                                     "v0": [0, 0, 0, -2, 0, 0]},
                           "shape": {"kind": "sphere", "size": [0.1, 0.1, 0.1]}, "mass": 1}]}]})",
                e, mu, collide ? "true" : "false", mu);
  return parse_scene(text, "spheres.json");
}

// Total momentum of every figure.
Vec6 total_momentum(const Model& model, const State& state) {
  Vec6 total = Vec6::Zero();
  for (const CompiledFigure& f : model.figures) {
    total += momentum(f.model, state.q.data() + f.model.state_q_offset,
                      state.v.data() + f.model.state_v_offset);
  }
  return total;
}

// The world velocity of a free sphere's centre (its frame's origin) and its centre.
Vec3 centre_velocity(const Model& model, const State& state, int f) {
  const FigureModel& figure = model.figures[f].model;
  const test::FigurePose pose = test::pose_of(figure, state.q.data() + figure.state_q_offset,
                                              state.v.data() + figure.state_v_offset);
  return segment_point_velocity(pose.world[0], pose.ws.v[0], pose.world[0].r);
}
Vec3 centre(const Model& model, const State& state, int f) {
  return state.q.segment<3>(model.figures[f].model.state_q_offset);
}

TEST(FigureCollisions, TwoFiguresKeepTheirMomentumAndLeaveWithTheirRestitution) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    Simulation sim(two_spheres(e, 0.5));
    ASSERT_TRUE(sim.model.segment_collisions);
    Vec6 p_before = Vec6::Zero(), p_after = Vec6::Zero();
    Real u_before = 0, u_after = 0;
    bool hit = false;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage != StepStage::impacts || hit) return;
      // The normal from b's centre to a's, the relative normal velocity of the centres.
      const Vec3 n = (centre(sim.model, state, 0) - centre(sim.model, state, 1)).normalized();
      const Real u =
          n.dot(centre_velocity(sim.model, state, 0) - centre_velocity(sim.model, state, 1));
      if (!done) {
        p_before = total_momentum(sim.model, state);
        u_before = u;
      } else {
        p_after = total_momentum(sim.model, state);
        u_after = u;
        hit = u_after != u_before;
      }
    };
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return hit; }, 400));
    const Real scale = p_before.tail<3>().cwiseAbs().maxCoeff() + 2.0;  // |m v| per sphere: 2
    std::printf("e = %.1f: u_n %.9f -> %.9f m/s (ratio %.9f); momentum change %.2e\n", e, u_before,
                u_after, -u_after / u_before, (p_after - p_before).norm());
    EXPECT_LT((p_after - p_before).norm(), 1e-10 * scale);
    // The centres' line is Bullet's normal to float precision.
    EXPECT_NEAR(u_after, -e * u_before, 1e-6 * std::abs(u_before));
    // Closing at 4 m/s with centres 0.08 m off a line, radii summing to 0.2: the normal part
    // is 4 sqrt(1 - 0.4^2) = 3.666 m/s (a little less, as the contact is seen 1 step in).
    EXPECT_NEAR(u_before, -4 * std::sqrt(1 - 0.4 * 0.4), 0.02);
  }
}

TEST(FigureCollisions, FiguresThatDoNotCollidePassThrough) {
  Simulation sim(two_spheres(1, 0.5, false));
  EXPECT_FALSE(sim.model.segment_collisions);
  for (int frame = 0; frame < 25; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  // 0.5 s at 2 m/s each: they swapped sides untouched.
  EXPECT_NEAR(centre(sim.model, sim.state, 0).x(), 0.5, 1e-9);
  EXPECT_NEAR(centre(sim.model, sim.state, 1).x(), -0.5, 1e-9);
}

// A lamp: a fixed 1 m post (box, half width 0.1), an arm hinged about y at its top, horizontal
// along x at q = 0, and a bob (sphere, r 0.1) welded 0.6 m out. Released, the bob swings down
// into the post's side x = 0.1 at q = acos(0.2 / 0.6).
std::string lamp(Real e, Real q0, const std::string& extra = "", Real damping = 0) {
  char text[2048];
  std::snprintf(text, sizeof text,
                R"({"solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
          "figures": [{"name": "lamp", "restitution": %.17g, "friction": 0 %s, "segments": [
            {"name": "post", "joint": {"kind": "fixed"},
             "shape": {"kind": "box", "size": [0.1, 0.1, 0.5], "center": [0, 0, 0.5]}},
            {"name": "arm", "parent": "post",
             "joint": {"axis": [0, 1, 0], "position": [0, 0, 1], "q0": [%.17g],
                       "damping": %.17g},
             "shape": {"kind": "capsule", "size": [0.03, 0.03, 0.25], "center": [0.3, 0, 0],
                       "orientation": [0.7071067811865476, 0, 0.7071067811865476, 0]}},
            {"name": "bob", "parent": "arm", "joint": {"kind": "fixed", "position": [0.6, 0, 0]},
             "shape": {"kind": "sphere", "size": [0.1, 0.1, 0.1]}}]}]})",
                e, extra.c_str(), q0, damping);
  return text;
}

const Real kHitAngle = std::acos(0.2 / 0.6);

TEST(FigureCollisions, ABobBouncesOffItsOwnPostWithItsRestitution) {
  for (const Real e : {0.0, 0.5, 1.0}) {
    Simulation sim(parse_scene(lamp(e, 0), "lamp.json"));
    ASSERT_TRUE(sim.model.figures[0].collides(0, 2));   // post and bob
    ASSERT_FALSE(sim.model.figures[0].collides(0, 1));  // the arm's parent
    Real before = 0, after = 0;
    auto watch = [&](StepStage stage, SubsystemId, bool done, const State& state, Workspace&) {
      if (stage == StepStage::impacts) (done ? after : before) = state.v[0];
    };
    ASSERT_TRUE(test::step_until(
        sim, watch, [&] { return after != before; }, 2000));
    std::printf("e = %.1f: q %.6f rad (contact at %.6f), q-dot %.9f -> %.9f rad/s\n", e,
                sim.state.q[0], kHitAngle, before, after);
    ASSERT_GT(before, 3.0);
    EXPECT_NEAR(sim.state.q[0], kHitAngle, 0.01);
    // One DOF, no friction: the contact's normal velocity is q-dot times a fixed lever.
    EXPECT_NEAR(after, -e * before, 1e-6 * before);
  }
}

TEST(FigureCollisions, ABobRestsWhereItsWeightBalancesTheContactSpring) {
  Simulation sim(parse_scene(lamp(0, 0, "", 2.0), "lamp.json"));
  for (int frame = 0; frame < 150; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  // Torques about the hinge: the arm's and bob's weights (levers 0.3 cos q and 0.6 cos q) against
  // the spring k d pushing the bob out along x at 0.6 sin q below the hinge; d = 0.2 - 0.6 cos q.
  const FigureDef& def = sim.model.scene.figures[0];
  const Real m_arm = 1000 * shape_volume(def.segments[1].shape);
  const Real m_bob = 1000 * shape_volume(def.segments[2].shape);
  const Real k = def.contact_stiffness, g = 9.81;
  Real q = kHitAngle;
  for (int i = 0; i < 100; ++i) {  // fixed point: cos q from the balance
    const Real force = g * (0.3 * m_arm + 0.6 * m_bob) * std::cos(q) / (0.6 * std::sin(q));
    q = std::acos((0.2 - force / k) / 0.6);
  }
  std::printf("rest q %.9f rad, closed form %.9f, q-dot %.2e, %d contacts, spring %.6f J\n",
              sim.state.q[0], q, sim.state.v[0], sim.stats.figures[0].contacts,
              sim.stats.figures[0].elastic);
  EXPECT_NEAR(sim.state.q[0], q, 1e-5);
  EXPECT_LT(std::abs(sim.state.v[0]), 1e-6);
  EXPECT_EQ(sim.stats.figures[0].contacts, 1);
  const Real d = 0.2 - 0.6 * std::cos(sim.state.q[0]);
  EXPECT_NEAR(sim.stats.figures[0].elastic, 0.5 * k * d * d, 1e-3 * 0.5 * k * d * d);
}

// A 2 kg can (a cylinder of radius 0.05 m, 0.3 m tall) set down 2 cm off the centre of a table
// top (another figure's fixed box) stands on four rim points (collide/convex_contacts.h): their
// equal springs hold it upright without a torque, each sunk by m g / (4 k).
TEST(FigureCollisions, ACanStandsUprightOnATableOnFourRimSprings) {
  const Scene scene = parse_scene(
      R"({"solver": {"dt": 0.001, "fps": 50, "integrator": "rk4"},
          "figures": [
            {"name": "table", "segments": [{"name": "top",
              "joint": {"kind": "fixed", "position": [0, 0, 0.5]},
              "shape": {"kind": "box", "size": [0.5, 0.5, 0.05]}, "mass": 20}]},
            {"name": "can", "segments": [{"name": "can",
              "joint": {"kind": "free", "q0": [0.02, 0, 0.7, 1, 0, 0, 0]},
              "shape": {"kind": "cylinder", "size": [0.05, 0.05, 0.15]}, "mass": 2}]}]})",
      "can.json");
  Simulation sim(scene);
  for (int frame = 0; frame < 50; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  const int offset = sim.model.figures[1].model.state_q_offset;
  const Vec3 centre = sim.state.q.segment<3>(offset);
  const Vec4 quaternion = sim.state.q.segment<4>(offset + 3);
  const Real tilt = 2 * std::asin(std::min(1.0, quaternion.tail<3>().norm()));
  const Real k = sim.model.scene.figures[1].contact_stiffness;
  const Real sink = 2 * 9.81 / (4 * k);
  std::printf(
      "can after 1 s: centre (%.3e, %.3e, %.9f) m, tilt %.3e rad, %d contacts; "
      "standing on four springs: z %.9f\n",
      centre.x(), centre.y(), centre.z(), tilt, sim.stats.figures[1].contacts, 0.7 - sink);
  EXPECT_EQ(sim.stats.figures[1].contacts, 4);
  EXPECT_NEAR(centre.z(), 0.7 - sink, 1e-6);
  EXPECT_LT(tilt, 1e-6);
  EXPECT_NEAR(centre.x(), 0.02, 1e-6);
  EXPECT_NEAR(centre.y(), 0, 1e-6);
}

TEST(FigureCollisions, ANonCollidingPairPassesThrough) {
  for (const std::string extra :
       {R"(, "non_colliding": [{"a": "bob", "b": "post"}])", R"(, "self_collisions": false)"}) {
    Simulation sim(parse_scene(lamp(0, 0, extra), "lamp.json"));
    EXPECT_FALSE(sim.model.segment_collisions) << extra;
    Real deepest = 0;
    for (int frame = 0; frame < 75; ++frame) {
      ASSERT_TRUE(advance_frame(sim).ok);
      deepest = std::max(deepest, sim.state.q[0]);
    }
    EXPECT_GT(deepest, 2.5) << extra;  // through the post and up the other side
  }
}

TEST(FigureCollisions, SegmentsOverlappingAtTheStartAreNamedAndLeftAlone) {
  Simulation sim(parse_scene(lamp(0, 1.4), "lamp.json"));  // the bob inside the post
  std::printf("%s\n", sim.model.notes.c_str());
  EXPECT_NE(sim.model.notes.find("figure 'lamp': segments 'post' and 'bob' overlap at the initial "
                                 "pose"),
            std::string::npos);
  EXPECT_FALSE(sim.model.figures[0].collides(0, 2));
  Real deepest = 0;
  for (int frame = 0; frame < 75; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    deepest = std::max(deepest, sim.state.q[0]);
  }
  // Through the post's bottom (pi / 2) to near its turning point pi - 1.4, untouched.
  EXPECT_GT(deepest, 1.7);
}

TEST(FigureCollisions, RunsAreBitIdentical) {
  const Scene scene = parse_scene(lamp(0.5, 0), "lamp.json");
  Simulation a(scene), b(scene);
  for (int frame = 0; frame < 60; ++frame) {
    ASSERT_TRUE(advance_frame(a).ok);
    ASSERT_TRUE(advance_frame(b).ok);
  }
  EXPECT_EQ(a.state.q, b.state.q);
  EXPECT_EQ(a.state.v, b.state.v);
}

}  // namespace
}  // namespace pbm
