// Levels of detail chosen automatically (sim/level_of_detail.h, issue 12): a body of level "auto"
// runs without its displacements far from contact and unpulled, wakes before contact, sleeps
// again once its dents have died down, and the switches are continuous (a wake exactly, a sleep
// within what it reports); what it saves is counted in substeps (speed itself is measured in
// benchmarks, not in tests).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/level_of_detail.h"
#include "sim/state.h"

namespace pbm {
namespace {

struct LevelRun {
  std::vector<FrameStats> frames;
  std::vector<VecX> q;
  State state;
  int substeps = 0;
};

LevelRun run(const Scene& scene, Real seconds) {
  test::Simulation sim(scene);
  LevelRun r;
  while (sim.state.time < seconds - 1e-9) {
    const FrameResult f = advance_frame(sim);
    EXPECT_TRUE(f.ok) << f.message;
    if (!f.ok) break;
    r.frames.push_back(sim.stats);
    r.q.push_back(sim.state.q);
    r.substeps += sim.stats.substeps;
  }
  r.state = sim.state;
  return r;
}

Vec3 centre(const LevelRun& r, std::size_t frame, const Model& model, int b) {
  return r.q[frame].segment<3>(model.bodies[b].q_offset);
}

// The shipped jello-ball (its dt is under its limit: one substep a frame either way) as "auto":
// dormant while it falls, awake at the start of every frame in which it touches the slope or
// the ground, and the same path as the local ball to rounding (a wake keeps the state exactly,
// and a dormant body's displacements are what a local body's are in free fall: zero).
TEST(LevelOfDetail, JelloBallFallsDormantWakesBeforeTheSlopeAndKeepsTheLocalPath) {
  Scene local = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/jello-ball.json");
  Scene automatic = local;
  automatic.bodies[0].level = DeformLevel::automatic;
  const LevelRun a = run(local, 3.0), b = run(automatic, 3.0);
  const Model model = build_model(local);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  int dormant_frames = 0, first_contact = -1, switches = 0;
  Real worst = 0;
  for (std::size_t f = 0; f < b.frames.size(); ++f) {
    dormant_frames += b.frames[f].levels.dormant_bodies;
    switches += b.frames[f].levels.switches;
    const bool touching = b.frames[f].contacts > 0 || b.frames[f].min_distance < 1e-6;
    if (touching && first_contact < 0) first_contact = static_cast<int>(f);
    if (touching) {
      EXPECT_EQ(b.frames[f].levels.dormant_bodies, 0) << "frame " << f;
    }
    worst = std::max(worst, (centre(a, f, model, 0) - centre(b, f, model, 0)).norm());
  }
  std::printf(
      "jello-ball auto: dormant %d frames of %zu, first contact at frame %d, %d switches, centre "
      "path off the local ball's by at most %.3g m\n",
      dormant_frames, b.frames.size(), first_contact, switches, worst);
  EXPECT_GT(dormant_frames, 10);
  EXPECT_GT(first_contact, dormant_frames - 1);
  EXPECT_GE(switches, 1);
  EXPECT_LT(worst, 1e-9);
}

// The same under the implicit integrator: a dormant body skips the implicit solve, and the path is
// still the local ball's.
TEST(LevelOfDetail, UnderTheImplicitIntegratorTheAutoBallKeepsTheLocalPath) {
  Scene local = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/jello-ball.json");
  local.solver.integrator = IntegratorKind::implicit;
  Scene automatic = local;
  automatic.bodies[0].level = DeformLevel::automatic;
  const LevelRun a = run(local, 2.0), b = run(automatic, 2.0);
  const Model model = build_model(local);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  Real worst = 0;
  int dormant_frames = 0;
  for (std::size_t f = 0; f < b.frames.size(); ++f) {
    worst = std::max(worst, (centre(a, f, model, 0) - centre(b, f, model, 0)).norm());
    dormant_frames += b.frames[f].levels.dormant_bodies;
  }
  std::printf("jello-ball auto, implicit: dormant %d frames, centre path off by at most %.3g m\n",
              dormant_frames, worst);
  EXPECT_GT(dormant_frames, 10);
  EXPECT_LT(worst, 1e-9);
}

// A finer ball (32 rings, 10 kg spread by area) whose membrane limits an explicit step to a
// fraction of the frame: dormant, it takes the frame's step (its global block's limit is far
// longer), so its fall costs fewer substeps; awake, it takes the same as the local ball. Its
// centre when it first touches the ground differs from the local ball's by Euler's error at
// the longer step, which halves with the step (order 1).
TEST(LevelOfDetail, DormantFallTakesTheGlobalBlocksStepAndConvergesWithIt) {
  auto scene = [](DeformLevel level, Real dt) {
    BodyDef ball = test::ball(level, 32);
    ball.material.nodal_mass = 0;
    ball.material.mass = 10;
    ball.material.w0 = 200;
    ball.material.w1 = 150;
    ball.material.damping = 1;
    ball.position = Vec3(0, 0, 3);
    Scene s;
    s.name = "drop";
    s.bodies.push_back(ball);
    ObstacleDef ground;
    ground.name = "ground";
    ground.kind = ObstacleKind::plane;
    ground.point = Vec3::Zero();
    ground.normal = Vec3::UnitZ();
    s.obstacles.push_back(ground);
    s.solver.dt = dt;
    s.solver.fps = 30;
    s.solver.shape_inertia_time = 1.0 / 30;
    return s;
  };
  const LevelRun local = run(scene(DeformLevel::local, 1.0 / 30), 1.0);
  const LevelRun coarse = run(scene(DeformLevel::automatic, 1.0 / 30), 1.0);
  const LevelRun fine = run(scene(DeformLevel::automatic, 1.0 / 60), 1.0);
  const Model model = build_model(scene(DeformLevel::local, 1.0 / 30));
  std::size_t landing = 0;
  while (landing < local.frames.size() && local.frames[landing].min_distance > 0.05) ++landing;
  ASSERT_LT(landing, local.frames.size());
  int dormant = 0;
  for (std::size_t f = 0; f < landing; ++f) dormant += coarse.frames[f].levels.dormant_bodies;
  const Real error_coarse =
      (centre(coarse, landing, model, 0) - centre(local, landing, model, 0)).norm();
  const Real error_fine =
      (centre(fine, landing, model, 0) - centre(local, landing, model, 0)).norm();
  const Real local_per_frame = static_cast<Real>(local.frames[0].substeps);
  std::printf(
      "32-ring drop: the local ball takes %.0f substeps a frame; auto dormant %d of the %zu "
      "frames before the ground, %d substeps in 1 s against %d; centre at frame %zu off the "
      "local ball's by %.3g m (dt 1/30 s) and %.3g m (1/60 s)\n",
      local_per_frame, dormant, landing, coarse.substeps, local.substeps, landing, error_coarse,
      error_fine);
  EXPECT_GT(local_per_frame, 4);
  EXPECT_GE(dormant, static_cast<int>(landing) - 3);
  EXPECT_LT(coarse.substeps, local.substeps / 2);
  for (std::size_t f = landing; f < coarse.frames.size(); ++f) {
    if (coarse.frames[f].levels.dormant_bodies == 0) {
      EXPECT_EQ(coarse.frames[f].substeps, local.frames[f].substeps) << "frame " << f;
    }
  }
  EXPECT_LT(error_fine, 0.7 * error_coarse);
}

// Two balls in free space meet head on and part: both wake before they meet, and once they are
// far apart and their dents have died down they sleep again, the switch zeroing less than
// kSleepDisplacement of the radius and an energy small against theirs. Their velocities after
// the collision are the local balls'.
TEST(LevelOfDetail, BallsWakeBeforeTheyMeetAndSleepWhenTheirDentsHaveDiedDown) {
  auto scene = [](DeformLevel level) {
    BodyDef a = test::ball(level, 8);
    a.position = Vec3(-1.5, 0, 0);
    a.velocity = Vec3(10, 0, 0);
    a.material.w0 = a.material.w1 = 50;
    a.material.damping = 3;  // D = nu M: the dents die down in a few seconds
    a.k_s = VecX::Constant(6, 5e4);
    BodyDef b = a;
    b.name = "other";
    b.position = Vec3(1.5, 0, 0);
    b.velocity = Vec3::Zero();
    Scene s = test::free_space(a);
    s.bodies.push_back(b);
    s.solver.dt = 1e-3;
    s.solver.fps = 50;
    s.solver.body_friction = 0;
    s.solver.body_elasticity = 2000;  // the dents push the balls apart
    return s;
  };
  const LevelRun local = run(scene(DeformLevel::local), 8.0);
  const LevelRun automatic = run(scene(DeformLevel::automatic), 8.0);
  int first_contact = -1, last_contact = -1, switches = 0;
  Real energy_jump = 0, position_jump = 0;
  for (std::size_t f = 0; f < automatic.frames.size(); ++f) {
    const FrameStats& s = automatic.frames[f];
    switches += s.levels.switches;
    energy_jump = std::max(energy_jump, s.levels.energy_jump);
    position_jump = std::max(position_jump, s.levels.position_jump);
    if (s.body_collisions.contacts > 0) {
      if (first_contact < 0) first_contact = static_cast<int>(f);
      last_contact = static_cast<int>(f);
      EXPECT_EQ(s.levels.dormant_bodies, 0) << "frame " << f;
    }
  }
  const FrameStats& end = automatic.frames.back();
  const Model model = build_model(scene(DeformLevel::local));
  Real speed_off = 0, kinetic = automatic.frames.front().kinetic;
  for (int b = 0; b < 2; ++b) {
    const int at = model.bodies[b].v_offset;
    speed_off = std::max(speed_off,
                         (automatic.state.v.segment<3>(at) - local.state.v.segment<3>(at)).norm());
  }
  std::printf(
      "head on, auto: contact in frames %d..%d, %d switches, %d dormant at the end; a switch off "
      "zeroed at most %.3g m of a node and %.3g J (kinetic before the collision %.3g J); centre "
      "velocities off the "
      "local balls' by %.3g m/s\n",
      first_contact, last_contact, switches, end.levels.dormant_bodies, position_jump, energy_jump,
      kinetic, speed_off);
  ASSERT_GE(first_contact, 0);
  EXPECT_EQ(end.levels.dormant_bodies, 2);
  EXPECT_GE(switches, 4);                               // two wakes, two sleeps
  EXPECT_LE(position_jump, kSleepDisplacement * 1.01);  // radius 1 m
  EXPECT_LT(energy_jump, 1e-4 * kinetic);
  EXPECT_LT(speed_off, 0.01 * 10);
  // The same run twice: bit-identical states, the levels included.
  const LevelRun again = run(scene(DeformLevel::automatic), 8.0);
  EXPECT_EQ(hash_state(again.state), hash_state(automatic.state));
}

}  // namespace
}  // namespace pbm
