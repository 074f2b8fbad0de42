// Collisions between figures' segments and deformable bodies (sim/segment_body_collisions.h):
// the segments' signed distance against finite differences; a segment striking a rigid ball
// head on keeps the total linear momentum and leaves both with the inelastic common velocity;
// a sprung platform carries a ball's weight (rigid and local: the weight goes through the dent)
// and rests where the closed-form balance puts it; the figure-and-jello scene knocks its ball
// and dents it; body_collisions: false passes through; runs are bit-identical.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "collide/convex_contacts.h"
#include "core/quaternion.h"
#include "figure/figure_build.h"
#include "figure_momentum.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/state.h"

namespace pbm {
namespace {

TEST(SegmentBodyCollisions, SignedDistanceIsExactAndItsNormalIsItsGradient) {
  const Mat3 turn = rotation_from_quaternion(Vec4(0.9, 0.2, -0.3, 0.25).normalized());
  const Vec3 centre(0.3, -0.2, 1.1);
  const ConvexSolid solids[] = {
      {.kind = ConvexKind::box, .size = Vec3(0.3, 0.2, 0.1), .rotation = turn, .center = centre},
      {.kind = ConvexKind::sphere, .size = Vec3(0.25, 0, 0), .rotation = turn, .center = centre},
      {.kind = ConvexKind::cylinder, .size = Vec3(0.2, 0, 0.4), .rotation = turn, .center = centre},
      {.kind = ConvexKind::capsule, .size = Vec3(0.15, 0, 0.3), .rotation = turn, .center = centre},
  };
  // Closed forms in the shape's frame: a point 0.05 off the box's +x face, 0.05 inside its -z
  // face, diagonally off a corner; on the cylinder's rim; off the capsule's cap along its axis.
  const auto at = [&](const Vec3& local) { return Vec3(centre + turn * local); };
  Vec3 n;
  EXPECT_NEAR(convex_signed_distance(solids[0], at({0.35, 0.05, 0.02}), n), 0.05, 1e-15);
  EXPECT_NEAR((n - turn.col(0)).norm(), 0, 1e-15);
  EXPECT_NEAR(convex_signed_distance(solids[0], at({0.1, 0.05, -0.05}), n), -0.05, 1e-15);
  EXPECT_NEAR((n + turn.col(2)).norm(), 0, 1e-15);
  EXPECT_NEAR(convex_signed_distance(solids[0], at({0.4, 0.3, 0.1}), n), std::sqrt(0.02), 1e-15);
  EXPECT_NEAR(convex_signed_distance(solids[2], at({0.3, 0, 0.5}), n), std::sqrt(0.02), 1e-15);
  EXPECT_NEAR(convex_signed_distance(solids[3], at({0, 0, -0.6}), n), 0.15, 1e-15);
  EXPECT_NEAR((n + turn.col(2)).norm(), 0, 1e-15);
  // The normal is the distance's gradient wherever the distance is smooth (points off every
  // shape, and inside away from the medial surfaces).
  int checked = 0;
  for (const ConvexSolid& solid : solids) {
    for (int k = 0; k < 200; ++k) {
      const Vec3 local =
          0.6 * Vec3(std::sin(1.7 * k + 0.3), std::cos(2.3 * k + 1.1), std::sin(0.7 * k * k + 2.0));
      const Vec3 x = at(local);
      const Real d = convex_signed_distance(solid, x, n);
      if (d < 0.01) continue;  // inside, the medial surfaces are kinks
      const Real h = 1e-6;
      Vec3 gradient;
      for (int i = 0; i < 3; ++i) {
        Vec3 e = Vec3::Zero(), unused;
        e[i] = h;
        gradient[i] = (convex_signed_distance(solid, x + e, unused) -
                       convex_signed_distance(solid, x - e, unused)) /
                      (2 * h);
      }
      EXPECT_NEAR((gradient - n).norm(), 0, 1e-8) << static_cast<int>(solid.kind) << " " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

// A 2 kg sphere (radius 0.2) on a free joint moving at v0 along x, no gravity, toward a ball body
// (radius 0.5, 3 kg) of the given level at rest.
Scene strike(const char* level, Real v0, bool collide = true, Real elasticity = 0) {
  char text[2048];
  std::snprintf(text, sizeof text,
                R"({"gravity": [0, 0, 0],
          "solver": {"dt": 0.0005, "fps": 50, "integrator": "rk4", "body_elasticity": %.17g},
          "bodies": [{"name": "ball", "level": "%s", "position": [0.8, 0, 1],
                      "shape": {"kind": "superquadric",
                                "q_s": {"a0": 0.5, "a1": 1, "a2": 1, "a3": 1, "eps1": 1, "eps2": 1}},
                      "tessellation": {"kind": "triangles", "rings": 16, "segments": 16},
                      "material": {"w0": 20, "w1": 15, "mass": 3, "damping": 0}}],
          "figures": [{"name": "striker", "body_collisions": %s, "friction": 0,
                       "segments": [{"joint": {"kind": "free", "q0": [0, 0, 1, 1, 0, 0, 0],
                                               "v0": [0, 0, 0, %.17g, 0, 0]},
                                     "shape": {"kind": "sphere", "size": [0.2, 0.2, 0.2]},
                                     "mass": 2}]}]})",
                elasticity, level, collide ? "true" : "false", v0);
  return parse_scene(text, "strike.json");
}

// Linear momentum of every body (sum of m_i x-dot_i over its nodes) and figure.
Vec3 linear_momentum(Simulation& sim) {
  Vec3 p = Vec3::Zero();
  for (std::size_t b = 0; b < sim.model.bodies.size(); ++b) {
    const BodyModel& body = sim.model.bodies[b];
    BodyWorkspace& bw = sim.ws.bodies[b];
    compute_body_kinematics(body, body_q(body, sim.state.q), body_v(body, sim.state.v), bw, false);
    for (int i = 0; i < body.n_nodes(); ++i) p += body.node_mass[i] * bw.x_dot[i];
  }
  for (const CompiledFigure& f : sim.model.figures) {
    p += test::momentum(f.model, sim.state.q.data() + f.model.state_q_offset,
                        sim.state.v.data() + f.model.state_v_offset)
             .tail<3>();
  }
  return p;
}

Real striker_speed(const Simulation& sim) {
  return sim.state.v[sim.model.figures[0].model.state_v_offset + 3];  // its free joint's v_x
}

TEST(SegmentBodyCollisions, AStrikeOnARigidBallKeepsMomentumAndEndsAtTheCommonVelocity) {
  Simulation sim(strike("rigid", 2.0));
  const Vec3 p0 = linear_momentum(sim);
  EXPECT_NEAR(p0.x(), 4.0, 1e-12);
  for (int frame = 0; frame < 10; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    const Vec3 p = linear_momentum(sim);
    EXPECT_LT((p - p0).norm(), 1e-10 * p0.norm()) << frame;
  }
  // Inelastic: both at m1 v0 / (m1 + m2) = 0.8 m/s, the ball's centre and the striker's.
  const BodyModel& ball = sim.model.bodies[0];
  const Real v_ball = velocity_of(body_v(ball, sim.state.v)).x();
  std::printf("striker %.9f m/s, ball %.9f m/s (closed form 0.8)\n", striker_speed(sim), v_ball);
  EXPECT_NEAR(v_ball, 0.8, 2e-3);
  EXPECT_NEAR(striker_speed(sim), 0.8, 2e-3);
}

TEST(SegmentBodyCollisions, AStrikeOnALocalBallKeepsMomentumAndDentsIt) {
  for (const Real elasticity : {0.0, 2.0}) {
    Simulation sim(strike("local", 2.0, true, elasticity));
    const Vec3 p0 = linear_momentum(sim);
    Real dent = 0;
    for (int frame = 0; frame < 15; ++frame) {
      ASSERT_TRUE(advance_frame(sim).ok);
      const Vec3 p = linear_momentum(sim);
      EXPECT_LT((p - p0).norm(), 1e-9 * p0.norm()) << frame;
      const BodyModel& ball = sim.model.bodies[0];
      const auto q_d = displacement_of(ball.layout, body_q(ball, sim.state.q));
      for (int i = 0; i < ball.n_nodes(); ++i) dent = std::max(dent, q_d.segment<3>(3 * i).norm());
    }
    const BodyModel& ball = sim.model.bodies[0];
    const Real v_ball = velocity_of(body_v(ball, sim.state.v)).x();
    std::printf("a = %g: striker %.6f m/s, ball frame %.6f m/s, deepest dent %.4f m\n", elasticity,
                striker_speed(sim), v_ball, dent);
    // The blow went into the ball (its frame moves away) and dented it; the striker slowed.
    EXPECT_GT(v_ball, 0.2);
    EXPECT_LT(striker_speed(sim), 1.6);
    EXPECT_GT(dent, 1e-3);
  }
}

TEST(SegmentBodyCollisions, WithoutBodyCollisionsTheSegmentPassesThrough) {
  Simulation sim(strike("rigid", 2.0, false));
  for (int frame = 0; frame < 10; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  EXPECT_EQ(striker_speed(sim), 2.0);
  EXPECT_EQ(velocity_of(body_v(sim.model.bodies[0], sim.state.v)).x(), 0.0);
}

// A 1 kg platform (box, half extents 0.4 x 0.4 x 0.05) on a vertical prismatic joint with a
// spring (k = 2000 N/m, rest 1 m) and damping 60 N s/m; a 2 kg ball of the given level dropped
// onto it from just above. At rest the spring holds both: k (rest - q) = (m_p + m_b) g.
Scene platform(const char* level) {
  char text[2048];
  std::snprintf(text, sizeof text,
                R"({"gravity": [0, 0, -9.81],
          "solver": {"dt": 0.001, "fps": 50, "integrator": "rk4", "body_elasticity": 2,
                     "body_friction": 0.5},
          "bodies": [{"name": "ball", "level": "%s", "position": [0, 0, 1.36],
                      "shape": {"kind": "superquadric",
                                "q_s": {"a0": 0.3, "a1": 1, "a2": 1, "a3": 1, "eps1": 1, "eps2": 1},
                                "stiffness": {"a0": 2000, "a1": 2000, "a2": 2000, "a3": 2000,
                                              "eps1": 2000, "eps2": 2000}},
                      "tessellation": {"kind": "triangles", "rings": 12, "segments": 12},
                      "material": {"w0": 20, "w1": 15, "mass": 2, "damping": 2}}],
          "figures": [{"name": "platform",
                       "segments": [{"joint": {"kind": "prismatic", "axis": [0, 0, 1],
                                               "q0": [1], "stiffness": 2000, "rest": [1],
                                               "damping": 60},
                                     "shape": {"kind": "box", "size": [0.4, 0.4, 0.05]},
                                     "mass": 1}]}]})",
                level);
  return parse_scene(text, "platform.json");
}

TEST(SegmentBodyCollisions, ASprungPlatformCarriesTheBallsWeight) {
  for (const char* level : {"rigid", "local"}) {
    Simulation sim(platform(level));
    for (int frame = 0; frame < 150; ++frame) ASSERT_TRUE(advance_frame(sim).ok) << frame;
    const Real q = sim.state.q[sim.model.figures[0].model.state_q_offset];
    const Real expected = 1 - 3 * 9.81 / 2000;
    std::printf("%s ball: platform at %.6f m, closed form %.6f m; contacts %d\n", level, q,
                expected, sim.stats.segment_bodies.contacts);
    EXPECT_NEAR(q, expected, 2e-4 * 3 * 9.81 / 2000 * 50);  // 1% of the deflection
    EXPECT_GT(sim.stats.segment_bodies.contacts, 0);
    // The ball sits on the platform's top face (z = q + 0.05): its lowest node no deeper than
    // the projection leaves it, and no higher than the push's recovery lets it float.
    const BodyModel& ball = sim.model.bodies[0];
    BodyWorkspace& bw = sim.ws.bodies[0];
    compute_body_kinematics(ball, body_q(ball, sim.state.q), body_v(ball, sim.state.v), bw, false);
    Real bottom = 1e300;
    for (const Vec3& x : bw.x) bottom = std::min(bottom, x.z());
    std::printf("  lowest node %.3e m above the top face\n", bottom - (q + 0.05));
    EXPECT_GT(bottom - (q + 0.05), -1e-6);
    EXPECT_LT(bottom - (q + 0.05), 2e-3);
  }
}

// scenes/figure-and-jello.json: a figure twists at the waist (MRAC on the torso) and its
// outstretched arm sweeps a jello ball off a pedestal. Until the arm arrives the ball rests where
// it was put; the arm dents it and drives it along the sweep's tangent, off the pedestal.
TEST(SegmentBodyCollisions, TheFiguresSwingKnocksTheJelloOffItsPedestal) {
  Simulation sim(load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/figure-and-jello.json"));
  const BodyModel& ball = sim.model.bodies[0];
  const Vec3 start = position_of(body_q(ball, sim.state.q));
  Real dent = 0;
  int touched_frames = 0;
  for (int frame = 1; frame <= 36; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok) << frame;
    const Vec3 c = position_of(body_q(ball, sim.state.q));
    if (frame == 12) {  // 0.4 s: the arm is still 0.7 rad away
      EXPECT_LT((c - start).head<2>().norm(), 2e-3);
    }
    touched_frames += sim.stats.segment_bodies.contacts > 0;
    const auto q_d = displacement_of(ball.layout, body_q(ball, sim.state.q));
    for (int i = 0; i < ball.n_nodes(); ++i) dent = std::max(dent, q_d.segment<3>(3 * i).norm());
  }
  const Vec3 moved = position_of(body_q(ball, sim.state.q)) - start;
  // The arm meets the ball 1 rad into its sweep: the sweep's tangent there is (cos 1, sin 1).
  const Vec3 tangent(std::cos(1.0), std::sin(1.0), 0);
  const Real along = moved.head<2>().normalized().dot(tangent.head<2>());
  std::printf(
      "ball moved %.3f m horizontally (cosine to the tangent %.3f), %.3f m down; deepest "
      "dent %.4f m; %d frames in contact with the arm\n",
      moved.head<2>().norm(), along, -moved.z(), dent, touched_frames);
  EXPECT_GT(moved.head<2>().norm(), 0.4);  // off the pedestal (half width 0.15 + radius 0.22)
  EXPECT_GT(along, 0.9);
  EXPECT_GT(-moved.z(), 0.3);  // falling to the floor
  EXPECT_GT(dent, 2e-3);
  EXPECT_GT(touched_frames, 2);
}

TEST(SegmentBodyCollisions, RunsAreBitIdentical) {
  Simulation a(strike("local", 2.0, true, 2.0)), b(strike("local", 2.0, true, 2.0));
  for (int frame = 0; frame < 12; ++frame) {
    ASSERT_TRUE(advance_frame(a).ok);
    ASSERT_TRUE(advance_frame(b).ok);
  }
  EXPECT_EQ(hash_state(a.state), hash_state(b.state));
}

}  // namespace
}  // namespace pbm
