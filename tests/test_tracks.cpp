// Keyframed tracks (sim/tracks.h) and the springs they drive: interpolation modes and the force
// limit of a spring (studio drags, scene key max_force).
#include <gtest/gtest.h>

#include "scene_builders.h"
#include "sim/tracks.h"

namespace pbm {
namespace {

TrackModel track(Interpolation interpolation) {
  TrackModel t;
  t.interpolation = interpolation;
  t.keys = {{0.0, 1.0}, {1.0, 3.0}, {3.0, -1.0}};
  return t;
}

TEST(Tracks, LinearInterpolatesAndHoldsOutsideTheKeys) {
  const TrackModel t = track(Interpolation::linear);
  EXPECT_DOUBLE_EQ(evaluate_track(t, -1.0), 1.0);
  EXPECT_DOUBLE_EQ(evaluate_track(t, 0.25), 1.5);
  EXPECT_DOUBLE_EQ(evaluate_track(t, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(evaluate_track(t, 5.0), -1.0);
}

TEST(Tracks, StepHoldsEachKeyUntilTheNext) {
  // A recorded drag replays the target the live drag used over each frame: the key's value
  // from its time up to (not including) the next key.
  const TrackModel t = track(Interpolation::step);
  EXPECT_EQ(evaluate_track(t, 0.0), 1.0);
  EXPECT_EQ(evaluate_track(t, 0.999999), 1.0);
  EXPECT_EQ(evaluate_track(t, 1.0), 3.0);
  EXPECT_EQ(evaluate_track(t, 2.9), 3.0);
  EXPECT_EQ(evaluate_track(t, 3.0), -1.0);
}

TEST(Tracks, SmoothPassesThroughEveryKey) {
  const TrackModel t = track(Interpolation::smooth);
  for (const Keyframe& k : t.keys) EXPECT_NEAR(evaluate_track(t, k.time), k.value, 1e-15);
}

TEST(Tracks, SpringForceSaturatesAtItsLimit) {
  // A stiff spring to a far target on a rigid 10 kg ball in free space: with the limit F the
  // ball accelerates at F/m, so after T its velocity is F T / m along the pull (the target is
  // 100 m away, so the direction hardly turns and the spring's damping term is a small part).
  Scene scene = test::free_space(test::ball(DeformLevel::rigid));
  SpringDef spring;
  spring.body = 0;
  spring.node = 0;
  spring.target = Vec3(100.0, 0.0, 0.0);
  spring.stiffness = 1e4;  // 1e6 N unclamped
  spring.damping = 0.0;
  spring.max_force = 20.0;
  scene.springs.push_back(spring);
  test::Simulation sim(scene);
  for (int frame = 0; frame < 15; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  const Real T = sim.state.time;
  const Vec3 velocity = sim.state.v.segment<3>(0);
  EXPECT_NEAR(velocity.x(), 20.0 * T / 10.0, 1e-3 * 20.0 * T / 10.0);
  EXPECT_LT(std::abs(velocity.y()) + std::abs(velocity.z()), 1e-2 * velocity.x());
}

}  // namespace
}  // namespace pbm
