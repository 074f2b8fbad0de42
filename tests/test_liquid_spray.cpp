// Spray and foam (liquid/spray.h): the spray's flight against closed forms (a ballistic arc
// without drag, the terminal speed sqrt(g / k) with it), none from still water, a dam break
// hitting the far wall throws spray that lands as foam and fades, and reruns give the same bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bits.h"
#include "liquid/liquid_step.h"
#include "liquid/spray.h"
#include "liquid_test_support.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81;

TEST(LiquidSpray, FlightIsBallisticWithoutDragAndReachesTheTerminalSpeedWithIt) {
  const Vec3 g(0, 0, -kG);
  // No drag: x0 + v0 t + g t^2 / 2, to the step's first order.
  Vec3 x(0, 0, 0), v(1, 0, 3);
  constexpr Real kDt = 1e-4;
  for (int k = 0; k < 5000; ++k) fly_spray(g, 0, kDt, x, v);
  const Real t = 0.5;
  EXPECT_NEAR(x.x(), 1 * t, 1e-9);
  EXPECT_NEAR(x.z(), 3 * t - 0.5 * kG * t * t, 1e-3);
  // Drag k: the fall settles at sqrt(g / k), from rest or thrown down faster, at any step.
  constexpr Real kDrag = 2;
  const Real terminal = std::sqrt(kG / kDrag);
  for (const Real dt : {1e-3, 0.05}) {
    for (const Real v0 : {0.0, -10.0}) {
      Vec3 y(0, 0, 0), w(0, 0, v0);
      for (int k = 0; k < static_cast<int>(20 / dt); ++k) fly_spray(g, kDrag, dt, y, w);
      EXPECT_NEAR(w.norm(), terminal, 1e-6 * terminal) << "dt " << dt << " v0 " << v0;
    }
  }
}

using Tank = test::LoneLiquid;

LiquidDef splash_tank(Real column_width) {
  LiquidDef def;
  def.domain = {Vec3(0, 0, 0), Vec3(1, 1.0 / 32, 0.5)};
  def.resolution = Eigen::Vector3i(32, 1, 16);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(column_width, 1, 0.3)}, Vec3::Zero()});
  def.spray_speed = 1.0;
  def.foam_lifetime = 0.5;
  return def;
}

TEST(LiquidSpray, StillWaterThrowsNone) {
  Tank tank(splash_tank(1.0));
  tank.run_to(1);
  EXPECT_EQ(tank.stats.spray_emitted, 0);
  EXPECT_TRUE(tank.state.spray.empty());
}

TEST(LiquidSpray, ADamBreakThrowsSprayThatLandsAsFoamAndFades) {
  Tank tank(splash_tank(0.3));
  // The front reaches the far wall (about 1.7 m/s) and runs up it.
  tank.run_to(1.2);
  std::printf("dam break 1.2 s: %d spray emitted, %d landed as foam; %zu in the air, %zu foam\n",
              tank.stats.spray_emitted, tank.stats.foam_landed, tank.state.spray.size(),
              tank.state.foam.size());
  EXPECT_GT(tank.stats.spray_emitted, 20);
  EXPECT_GT(tank.stats.foam_landed, 0);
  for (std::size_t p = 0; p < tank.state.spray.size(); ++p) {
    EXPECT_TRUE(tank.state.spray[p].allFinite());
    EXPECT_EQ(tank.state.spray[p].y(), 0.5 / 32);  // the 2D liquid's middle plane
  }
  for (const Real age : tank.state.foam_age) EXPECT_LE(age, 0.5);
  EXPECT_EQ(tank.state.spray.size(), tank.state.spray_velocity.size());
  EXPECT_EQ(tank.state.foam.size(), tank.state.foam_age.size());
  // With the emission turned off every particle lands or leaves, and foam fades in its lifetime.
  tank.model.def.spray_rate = 0;
  tank.run_to(4);
  EXPECT_TRUE(tank.state.spray.empty());
  EXPECT_TRUE(tank.state.foam.empty());
}

TEST(LiquidSpray, SameStartSameBits) {
  auto run = [] {
    Tank tank(splash_tank(0.3));
    tank.run_to(1.0);
    std::uint64_t h = kFnvOffset;
    hash_liquid_state(tank.state, h);
    return h;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace pbm
