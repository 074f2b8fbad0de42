// Obstacles moved by tracks (kinematic obstacles, sec. 5.2.1 with the obstacle's velocity): the
// contact acts on the velocity relative to the obstacle, so a moving plane lifts, pushes and
// drags bodies (it is infinitely massive), and the dragonfly of sec. 7.4 is swatted by a paddle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/snapshot.h"
#include "sim/tracks.h"
#include "sim/world.h"

namespace pbm {
namespace {

constexpr Real kRadius = 1.0;  // test::ball's default superquadric is the unit sphere

// A ball of the given level at the origin, the given obstacle, and tracks on it; 1 ms steps,
// 100 frames per second.
Scene ball_and_obstacle(DeformLevel level, const ObstacleDef& obstacle,
                        const std::vector<TrackDef>& tracks, const Vec3& gravity) {
  Scene s = test::free_space(test::ball(level));
  s.gravity = gravity;
  s.obstacles.push_back(obstacle);
  s.tracks = tracks;
  s.solver.dt = 0.001;
  s.solver.fps = 100;
  s.solver.duration = 3;
  return s;
}

ObstacleDef plane(const Vec3& point, const Vec3& normal, Real friction) {
  ObstacleDef o;
  o.name = "plane";
  o.point = point;
  o.normal = normal;
  o.friction = friction;
  return o;
}

// World velocity of the body point at offset r from the centre (rigid motion of the frame).
Vec3 point_velocity(const State& state, const Vec3& r) {
  const Mat3 R = rotation_from_quaternion(state.q.segment<4>(3));
  return state.v.segment<3>(0) + (R * state.v.segment<3>(3)).cross(r);
}

// (a) A rigid ball resting on a plane that rises at 0.5 m/s from t = 0.2 s rides with it: the
// inelastic impacts against the moving plane leave its vertical velocity at the plane's.
TEST(MovingObstacles, BallRidesARisingPlane) {
  const Real v = 0.5;
  const Scene scene = ball_and_obstacle(
      DeformLevel::rigid, plane(Vec3(0, 0, -kRadius), Vec3::UnitZ(), 0.3),
      {{.target = "obstacles[0].point[2]", .keys = {{0.2, -kRadius}, {2.2, -kRadius + 2 * v}}}},
      Vec3(0, 0, -9.81));
  test::Simulation sim(scene);
  Real worst_velocity_error = 0, worst_sink = 0, min_distance = 1e300;
  for (int f = 0; f < 200; ++f) {  // to 2.0 s
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    min_distance = std::min(min_distance, sim.stats.min_distance);
    const Real t = sim.state.time;
    const Real plane_z = -kRadius + v * std::max(0.0, t - 0.2);
    worst_sink = std::max(worst_sink, plane_z + kRadius - sim.state.q[2]);
    if (t >= 0.3) {
      worst_velocity_error = std::max(worst_velocity_error, std::abs(sim.state.v[2] - v));
    }
  }
  // Measured: at every frame's end the impact of the last substep has set v_z to the plane's
  // exactly (error 0), the centre never below its resting height, the nodes 1e-9 m above.
  std::printf(
      "rising plane: worst |v_z - v| %.3g m/s after 0.3 s, worst sink %.3g m, end z %.4f m\n",
      worst_velocity_error, worst_sink, sim.state.q[2]);
  EXPECT_LT(worst_velocity_error, 0.02);
  EXPECT_LT(worst_sink, 1e-6);
  EXPECT_GE(min_distance, 0.0);
  EXPECT_NEAR(sim.state.q[2], 0.9, 0.01);  // lifted by v (2.0 - 0.2) s
}

// (b) A frictionless box moving at 1 m/s hits a resting rigid ball (no gravity), pushes it until
// it stops at t = 1 s: an inelastic impact with an infinitely massive pusher leaves the ball
// with the box's speed, which it keeps after the box has stopped.
Scene box_hits_ball(DeformLevel level) {
  ObstacleDef box;
  box.name = "paddle";
  box.kind = ObstacleKind::box;
  box.point = Vec3(-2.0, 0, 0);
  box.half_extents = Vec3(0.25, 2, 2);
  box.friction = 0;
  return ball_and_obstacle(level, box,
                           {{.target = "obstacles[0].point[0]", .keys = {{0, -2.0}, {1.0, -1.0}}}},
                           Vec3::Zero());
}

TEST(MovingObstacles, BoxGivesARestingBallItsSpeed) {
  test::Simulation sim(box_hits_ball(DeformLevel::rigid));
  for (int f = 0; f < 200; ++f) {  // to 2.0 s
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
  }
  // Measured: v = (1.0000, 0, 0) m/s, x = 1.235 m (the sampled sphere's nodes are met later
  // than its true surface).
  std::printf("box hits a rigid ball: v = (%.4f, %.3g, %.3g) m/s, x = %.4f m\n", sim.state.v[0],
              sim.state.v[1], sim.state.v[2], sim.state.q[0]);
  EXPECT_NEAR(sim.state.v[0], 1.0, 0.01);
  EXPECT_NEAR(sim.state.v[1], 0.0, 1e-6);
  EXPECT_NEAR(sim.state.v[2], 0.0, 1e-6);
  EXPECT_NEAR(sim.state.q[0], 1.25, 0.03);  // 0.25 m pushed by 1 s, then 1 s at 1 m/s
}

// The same hit on a deformable (local) ball goes through (5.11)'s spring and the dashpot: its
// centre of mass leaves with at least the box's speed and at most twice it (an elastic bounce).
// Measured: 1.303 m/s.
TEST(MovingObstacles, BoxLaunchesADeformableBall) {
  test::Simulation sim(box_hits_ball(DeformLevel::local));
  for (int f = 0; f < 200; ++f) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
  }
  const Real speed = sim.state.v[0];
  std::printf("box hits a deformable ball: it leaves at %.4f m/s\n", speed);
  EXPECT_GT(speed, 0.95);
  EXPECT_LT(speed, 2.05);
  EXPECT_NEAR(sim.state.v[1], 0.0, 1e-3);
}

// (c) A rigid ball resting on the ground while the ground slides at 1 m/s along x: friction
// (5.12) drags it, never faster than beta_f g t, until its contact point moves with the ground
// (it then rolls on it). Without friction it stays where it is.
struct DragRun {
  Real worst_excess = 0;  // max over frames of v_x - beta_f g t [m/s]
  Real centre_speed = 0;  // v_x at the end [m/s]
  Real contact_slip = 0;  // |bottom point's v_x - ground's| at the end [m/s]
};

DragRun drag(Real friction) {
  const Scene scene = ball_and_obstacle(
      DeformLevel::rigid, plane(Vec3(0, 0, -kRadius), Vec3::UnitZ(), friction),
      {{.target = "obstacles[0].point[0]", .keys = {{0, 0}, {10, 10}}}}, Vec3(0, 0, -9.81));
  test::Simulation sim(scene);
  DragRun run;
  for (int f = 0; f < 150; ++f) {  // to 1.5 s
    const FrameResult r = advance_frame(sim);
    EXPECT_TRUE(r.ok) << r.message;
    if (!r.ok) break;
    run.worst_excess =
        std::max(run.worst_excess, sim.state.v[0] - friction * 9.81 * sim.state.time);
  }
  run.centre_speed = sim.state.v[0];
  run.contact_slip = std::abs(point_velocity(sim.state, Vec3(0, 0, -kRadius)).x() - 1.0);
  return run;
}

TEST(MovingObstacles, SlidingGroundDragsABallByFriction) {
  const DragRun rough = drag(0.3);
  // Measured: never faster than beta_f g t; the centre at 0.388 m/s (a shell of lumped nodes,
  // I ~ 2/3 m r^2, rolls without slip at V / (1 + m r^2 / I) = 0.4 V), its contact point within
  // 0.006 m/s of the ground's; frictionless, it stays at rest (6e-30 m/s).
  std::printf(
      "sliding ground: ball centre %.4f m/s, contact slip %.4f m/s, worst excess over "
      "beta_f g t %.3g m/s\n",
      rough.centre_speed, rough.contact_slip, rough.worst_excess);
  EXPECT_LT(rough.worst_excess, 1e-3);
  EXPECT_GT(rough.centre_speed, 0.3);
  EXPECT_LT(rough.centre_speed, 0.5);
  EXPECT_LT(rough.contact_slip, 0.02);
  const DragRun smooth = drag(0.0);
  EXPECT_LT(std::abs(smooth.centre_speed), 1e-9);
}

// (d) Same scene, same states, bit for bit.
TEST(MovingObstacles, RunsAreBitIdentical) {
  const Scene scene = box_hits_ball(DeformLevel::local);
  std::uint64_t hashes[2] = {0, 0};
  for (std::uint64_t& hash : hashes) {
    test::Simulation sim(scene);
    for (int f = 0; f < 120; ++f) ASSERT_TRUE(advance_frame(sim).ok);
    hash = hash_state(sim.state);
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

// The velocities the contact uses are the tracks' derivatives: against central differences of
// the placement, for a smooth point track and a rotation track about a tilted axis.
TEST(MovingObstacles, PlacementVelocitiesAreTheTracksDerivatives) {
  ObstacleDef box;
  box.kind = ObstacleKind::box;
  box.point = Vec3(3, 0, 0);
  box.orientation = Vec4(0.9, 0.1, 0.3, 0.2);
  Scene scene =
      ball_and_obstacle(DeformLevel::rigid, box,
                        {{.target = "obstacles[0].point[1]",
                          .interpolation = Interpolation::smooth,
                          .keys = {{0, 0}, {1, 2}, {2, -1}, {3, 0.5}}},
                         {.target = "obstacles[0].rotation[0]", .keys = {{0, 0}, {2, 1.2}}},
                         {.target = "obstacles[0].rotation[2]",
                          .interpolation = Interpolation::smooth,
                          .keys = {{0, 0}, {1, 2.0}, {2, 0.5}}}},
                        Vec3::Zero());
  const Model model = build_model(scene);
  ASSERT_TRUE(model.obstacles[0].moving);
  std::vector<ObstacleModel> at, before, after;
  const Real h = 1e-6;
  for (const Real t : {0.3, 0.77, 1.4, 1.9}) {
    place_obstacles(model, Inputs{}, t, at);
    place_obstacles(model, Inputs{}, t - h, before);
    place_obstacles(model, Inputs{}, t + h, after);
    const Vec3 velocity = (after[0].point - before[0].point) / (2 * h);
    EXPECT_LT((velocity - at[0].velocity).norm(), 1e-6) << t;
    // R-dot R^T = [omega]x.
    const Mat3 W = (after[0].rotation - before[0].rotation) / (2 * h) * at[0].rotation.transpose();
    const Vec3 omega(W(2, 1), W(0, 2), W(1, 0));
    EXPECT_LT((omega - at[0].angular_velocity).norm(), 1e-5) << t;
    EXPECT_GT(at[0].angular_velocity.norm(), 0.1) << t;
  }
}

// The snapshot (renderer and studio) draws an obstacle where it is at the state's time.
TEST(MovingObstacles, SnapshotShowsTheObstacleWhereItIs) {
  test::Simulation sim(box_hits_ball(DeformLevel::rigid));
  const Snapshot at_start = make_snapshot(sim);
  for (int f = 0; f < 50; ++f) ASSERT_TRUE(advance_frame(sim).ok);
  const Snapshot later = make_snapshot(sim);
  ASSERT_EQ(later.primitives.size(), 1u);  // the box
  EXPECT_FLOAT_EQ(at_start.primitives[0].center.x(), -2.0f);
  EXPECT_NEAR(later.primitives[0].center.x(), -1.5f, 1e-5f);  // 1 m/s for 0.5 s
}

// (e) Obstacle tracks in the file: round trip, the kind's own key stored as point, errors at
// the target's JSON path.
const char* kTrackScene = R"({
  "bodies": [{"name": "ball", "level": "rigid", "material": {"mass": 1}}],
  "obstacles": [{"kind": "plane"}, {"name": "paddle", "kind": "box", "center": [0, 0, 3]}],
  "tracks": [
    {"target": "obstacles[1].center[2]", "interpolation": "smooth", "keys": [[0, 3], [1, 2]]},
    {"target": "obstacles[1].rotation[1]", "keys": [[0, 0], [1, 0.5]]},
    {"target": "obstacles[0].point[0]", "keys": [[0.5, 0]]}
  ]
})";

TEST(MovingObstacles, TracksRoundTripThroughTheFile) {
  const Scene scene = parse_scene(kTrackScene, "tracks.json");
  ASSERT_EQ(scene.tracks.size(), 3u);
  EXPECT_EQ(scene.tracks[0].target, "obstacles[1].point[2]");
  EXPECT_EQ(scene.tracks[1].target, "obstacles[1].rotation[1]");
  EXPECT_EQ(scene.tracks[2].target, "obstacles[0].point[0]");
  const Scene again = parse_scene(scene_to_json(scene), "tracks.json");
  // Every field of every track read back, compared with what the file gave (not with the
  // writer's own output).
  ASSERT_EQ(again.tracks.size(), 3u);
  const Interpolation interpolation[] = {Interpolation::smooth, Interpolation::linear,
                                         Interpolation::linear};
  const std::vector<std::vector<Keyframe>> keys = {
      {{0, 3}, {1, 2}}, {{0, 0}, {1, 0.5}}, {{0.5, 0}}};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(again.tracks[i].target, scene.tracks[i].target) << i;
    EXPECT_EQ(again.tracks[i].interpolation, interpolation[i]) << i;
    ASSERT_EQ(again.tracks[i].keys.size(), keys[i].size()) << i;
    for (std::size_t k = 0; k < keys[i].size(); ++k) {
      EXPECT_EQ(again.tracks[i].keys[k].time, keys[i][k].time) << i << " " << k;
      EXPECT_EQ(again.tracks[i].keys[k].value, keys[i][k].value) << i << " " << k;
    }
  }
  EXPECT_EQ(again.obstacles[1].name, "paddle");
  EXPECT_EQ(again.obstacles[1].point, Vec3(0, 0, 3));
  const Model model = build_model(again);
  EXPECT_TRUE(model.obstacles[0].moving);
  EXPECT_TRUE(model.obstacles[1].moving);
}

void expect_target_error(const std::string& target, const std::string& message) {
  std::string text = kTrackScene;
  const std::string first = "obstacles[1].center[2]";
  text.replace(text.find(first), first.size(), target);
  try {
    parse_scene(text, "tracks.json");
    ADD_FAILURE() << "expected an error for " << target;
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "tracks.json");
    EXPECT_EQ(e.path(), "tracks[0].target") << e.what();
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(MovingObstacles, MalformedObstacleTracksNameTheirPath) {
  expect_target_error("obstacles[2].point[0]", "obstacle index 2 is out of range (2 available)");
  expect_target_error("obstacles[1].point[3]", "point component index 3 is out of range");
  expect_target_error("obstacles[1].rotation[5]", "rotation component index 5 is out of range");
  expect_target_error("obstacles[1].normal[0]", "unknown obstacle track target");
  // A box has a centre, not a mesh's position.
  expect_target_error("obstacles[1].position[0]", "unknown obstacle track target");
  expect_target_error("obstacles[x].point[0]", "unknown track target");
}

// (f) The dragonfly (sec. 7.4), assembled by 2 s, is swatted by a paddle (a thin box) that comes
// down from 4.3 s and meets it at about 4.7 s: its
// centre of mass moves away, where without the paddle's motion it stays.
Vec3 centre_of_mass(const Model& model, const State& state) {
  Vec3 sum = Vec3::Zero();
  Real mass = 0;
  for (const BodyModel& body : model.bodies) {
    sum += body.mass * state.q.segment<3>(body.q_offset);
    mass += body.mass;
  }
  return sum / mass;
}

struct SwatRun {
  Vec3 before = Vec3::Zero(), after = Vec3::Zero();  // centre of mass at 4.2 s and at the end
  Real min_distance = 1e300;
};

SwatRun run_dragonfly(bool swat) {
  Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/dragonfly.json");
  if (!swat)
    std::erase_if(scene.tracks,
                  [](const TrackDef& t) { return t.target.starts_with("obstacles"); });
  test::Simulation sim(scene);
  SwatRun run;
  const int frames = static_cast<int>(std::lround(scene.solver.duration * scene.solver.fps));
  for (int f = 0; f < frames; ++f) {
    const FrameResult r = advance_frame(sim);
    EXPECT_TRUE(r.ok) << r.message;
    if (!r.ok) break;
    run.min_distance = std::min(run.min_distance, sim.stats.min_distance);
    if (std::abs(sim.state.time - 4.2) < 0.5 / scene.solver.fps) {
      run.before = centre_of_mass(sim.model, sim.state);
    }
  }
  run.after = centre_of_mass(sim.model, sim.state);
  return run;
}

TEST(MovingObstacles, DragonflyIsSwattedAway) {
  const SwatRun swatted = run_dragonfly(true);
  const SwatRun still = run_dragonfly(false);
  const Vec3 moved = swatted.after - swatted.before;
  const Real drift = (still.after - still.before).norm();
  // Measured: 3.11 m, almost all of it down (the paddle's direction), against 0.16 m of drift
  // without the paddle's motion (the wings' springs let go at 4.75 s).
  std::printf(
      "dragonfly: centre of mass moved %.3f m (z %.3f m) after the swat, %.3f m with the "
      "paddle still\n",
      moved.norm(), moved.z(), drift);
  EXPECT_GT(moved.norm(), 2.0);
  EXPECT_LT(moved.z(), -2.0);
  EXPECT_LT(drift, 0.4);
  EXPECT_GE(swatted.min_distance, -1e-6);
}

}  // namespace
}  // namespace pbm
