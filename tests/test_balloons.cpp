// The balloon pendulums of sec. 7.4 (figs. 7.2, 7.3): balloons on strings hung from world anchors
// by point-to-point constraints, the left one released from the side into its neighbours, body
// collisions inelastic (5.2.2) with the dents' push on the whole bodies (body_elasticity 100,
// collide/body_push.h). Checked here: no two balloon surfaces interpenetrate (beyond 1% of a
// radius) in any frame, the four or six constraints hold to 1 mm once the swing is under way, and
// the book's observation that with a third balloon in the middle the left one swings a shorter
// distance past its rest spot. The effect is small here: 0.2119 m against 0.2179 m (2.8%; 1.4% at
// a = 30, 2.7% at a = 1000). Without the push (a = 0) the two runs agree to 0.2% (0.3245 m
// against 0.3251 m): the impulses on the touching nodes alone let the neighbour's skin dent
// ~0.3 m before its frame moves, and nothing reaches a third balloon in time. Rigid balloons show
// it more strongly (0.139 m against 0.186 m): the local balloons' membranes spring back after the
// blow, and the left balloon leaves its neighbour before the neighbour meets the third.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/snapshot.h"
#include "snapshot_penetration.h"

namespace pbm {
namespace {

using test::penetration_depth;

// Deepest node of one balloon inside another [m].
double max_penetration(const std::vector<const draw::Mesh*>& balloons) {
  double worst = 0;
  for (const draw::Mesh* a : balloons) {
    for (const draw::Mesh* b : balloons) {
      if (a != b) worst = std::max(worst, penetration_depth(*a, *b));
    }
  }
  return worst;
}

std::vector<const draw::Mesh*> balloons_of(const Snapshot& snap) {
  std::vector<const draw::Mesh*> out;
  for (const draw::Mesh& b : snap.meshes) {
    if (b.pick >= 0 && b.name.starts_with("balloon")) out.push_back(&b);
  }
  return out;
}

struct BalloonRun {
  double radius = 0;
  double max_penetration = 0;     // over every frame [m]
  double max_violation_late = 0;  // max |C| over the frames after t = 1 s [m]
  double first_contact = -1;      // first frame with the left balloon's neighbour within reach [s]
  double left_rest_x = 0;         // where the left balloon hangs at rest [m]
  double left_max_past_rest = 0;  // its largest x beyond that after first contact [m]
  double left_return = 0;         // its largest leftward excursion from rest, 0.3 s after contact
  double left_speed_after = 0;    // its largest |x-dot| after the first collision [m/s]
  double release_offset = 0;      // how far left of its rest spot it is released [m]
  double release_speed = 0;       // its speed at the bottom without losses, sqrt(2 g h) [m/s]
};

BalloonRun simulate(const std::string& name, double seconds) {
  const Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/" + name + ".json");
  test::Simulation sim(scene);
  BalloonRun run;
  int left = -1, neighbour = -1;
  for (int i = 0; i < static_cast<int>(scene.bodies.size()); ++i) {
    if (scene.bodies[i].name == "balloon_left") left = i;
    if (neighbour < 0 && scene.bodies[i].name.starts_with("balloon") &&
        scene.bodies[i].name != "balloon_left") {
      neighbour = i;
    }
  }
  EXPECT_GE(left, 0);
  EXPECT_GE(neighbour, 0);
  run.radius = scene.bodies[left].q_s[0];
  // The neighbour hangs at rest at the start; the left one's rest spot is one spacing left of it.
  const double spacing = 2 * run.radius + 0.02;
  run.left_rest_x = scene.bodies[neighbour].position.x() - spacing;
  run.release_offset = run.left_rest_x - scene.bodies[left].position.x();
  const double drop = scene.bodies[left].position.z() - scene.bodies[neighbour].position.z();
  run.release_speed = std::sqrt(2 * scene.gravity.norm() * drop);
  double prev_x = scene.bodies[left].position.x(), prev_t = 0;
  bool rebounded = false;
  while (sim.state.time < seconds - 1e-9) {
    const FrameResult r = advance_frame(sim);
    EXPECT_TRUE(r.ok) << r.message;
    if (!r.ok) break;
    const Snapshot snap = make_snapshot(sim);
    run.max_penetration = std::max(run.max_penetration, max_penetration(balloons_of(snap)));
    if (sim.state.time > 1.0) {
      run.max_violation_late = std::max(run.max_violation_late, sim.stats.constraint_violation);
    }
    const double x = sim.stats.bodies[left].position.x();
    const double xn = sim.stats.bodies[neighbour].position.x();
    const double vx = (x - prev_x) / (sim.state.time - prev_t);
    if (run.first_contact < 0 && xn - x < spacing) run.first_contact = sim.state.time;
    if (run.first_contact >= 0) {
      run.left_max_past_rest = std::max(run.left_max_past_rest, x - run.left_rest_x);
      if (vx <= 0) rebounded = true;
      if (rebounded) run.left_speed_after = std::max(run.left_speed_after, std::abs(vx));
      if (sim.state.time > run.first_contact + 0.3) {
        run.left_return = std::max(run.left_return, run.left_rest_x - x);
      }
    }
    prev_x = x;
    prev_t = sim.state.time;
  }
  std::printf(
      "%s: first contact %.3f s; left balloon past rest %.4f m, return %.4f m, speed after "
      "the first collision %.4f m/s; max penetration %.3g m (%.2f%% of r); max |C| after 1 s "
      "%.3g m\n",
      name.c_str(), run.first_contact, run.left_max_past_rest, run.left_return,
      run.left_speed_after, run.max_penetration, 100 * run.max_penetration / run.radius,
      run.max_violation_late);
  return run;
}

// The inside test finds a known overlap: the scene's right balloon moved 0.1 m into the left
// one's place at rest has its nodes inside by about 0.1 m (so (b) below can fail).
TEST(Balloons, PenetrationMeasureSeesAKnownOverlap) {
  const Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/balloons-2.json");
  test::Simulation sim(scene);
  Snapshot snap = make_snapshot(sim);
  std::vector<const draw::Mesh*> balloons = balloons_of(snap);
  ASSERT_EQ(balloons.size(), 2u);
  EXPECT_EQ(max_penetration(balloons), 0.0);  // released from the side: apart
  draw::Mesh copy = *balloons[1];
  auto moved = std::make_shared<std::vector<draw::Vec3f>>(*copy.positions);
  for (draw::Vec3f& x : *moved) x.x() -= 0.1f;  // overlaps the original by 0.1 m
  copy.positions = moved;
  const double depth = max_penetration({balloons[1], &copy});
  std::printf("known 0.1 m overlap measured as %.4f m\n", depth);
  EXPECT_NEAR(depth, 0.1, 0.02);
}

// Fig. 7.2 and 7.3 run for 6 s: the balloons collide (first contact near a quarter period of the
// 2.4 m pendulum, ~1.1 s) and dent each other, but no node of one balloon is ever inside another
// by more than 1% of the 0.4 m radius (the inelastic mid-plane projection keeps the surfaces
// apart); the constraints, started satisfied, hold to 1 mm through the collisions (Baumgarte
// alpha = 60 / s).
TEST(Balloons, NoInterpenetrationAndConstraintsHoldAndTheMiddleBalloonCushions) {
  std::vector<BalloonRun> runs;
  for (const char* name : {"balloons-2", "balloons-3"}) {
    const BalloonRun run = runs.emplace_back(simulate(name, 6.0));
    EXPECT_GT(run.first_contact, 0.8) << name;  // they do collide, once the swing is under way
    EXPECT_LT(run.first_contact, 1.6) << name;
    EXPECT_GT(run.left_max_past_rest, 0.02) << name;  // the collision happened, not a near miss
    EXPECT_LT(run.max_penetration, 0.01 * run.radius) << name;
    EXPECT_LT(run.max_violation_late, 1e-3) << name;
    // Momentum: meeting a balloon of its own mass at rest, inelastically or pushed apart, the
    // left one keeps at most half its velocity, so it swings past its rest spot less than half
    // as far as it was released from it and moves at most half its free speed at the bottom.
    EXPECT_LT(run.left_max_past_rest, 0.5 * run.release_offset) << name;
    EXPECT_LT(run.left_speed_after, 0.5 * run.release_speed) << name;
    // It swings back: 0.3 s after the blow it is left of its rest spot again.
    EXPECT_GT(run.left_return, 0.02) << name;
  }
  // Fig. 7.3: "the left balloon therefore swings a shorter distance". The README quotes these
  // two distances (0.2179 m, 0.2119 m: 2.8%); they are checked to 1% so that it stays true.
  EXPECT_LT(runs[1].left_max_past_rest, 0.99 * runs[0].left_max_past_rest);
  EXPECT_NEAR(runs[0].left_max_past_rest, 0.2179, 0.01 * 0.2179);
  EXPECT_NEAR(runs[1].left_max_past_rest, 0.2119, 0.01 * 0.2119);
}

}  // namespace
}  // namespace pbm
