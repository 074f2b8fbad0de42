// PIC/FLIP advection (liquid/particle_transfer.h): the markers carry the velocity. Still water
// stays still, volume is kept as with the grid's own advection, the sloshing mode keeps its
// period and loses less of its height than with the semi-Lagrangian backtrace, the same start
// gives the same bits, and a height field is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bits.h"
#include "core/error.h"
#include "liquid/cell_labels.h"
#include "liquid/liquid_step.h"
#include "liquid_test_support.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81;

// Frames of 1/60 s.
struct Liquid : test::LoneLiquid {
  using LoneLiquid::LoneLiquid;
  void run(Real seconds) { LoneLiquid::run(seconds, 60); }
  Real max_marker_speed() const {
    Real v = 0;
    for (const Vec3& u : state.marker_velocity) v = std::max(v, u.norm());
    return v;
  }
};

// A 2D tank 1 m x 1 m.
LiquidDef tank(int cells, Real depth, LiquidAdvection advection) {
  LiquidDef def;
  def.domain = {Vec3(0, 0, 0), Vec3(1, 1.0 / cells, 1)};
  def.resolution = Eigen::Vector3i(cells, 1, cells);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(1, 1, depth)}, Vec3::Zero()});
  def.advection = advection;
  return def;
}

TEST(LiquidFlip, StillWaterStaysStill) {
  Liquid liquid(tank(16, 0.5, LiquidAdvection::flip));
  ASSERT_EQ(liquid.state.marker_velocity.size(), liquid.state.markers.size());
  liquid.run(2);
  std::printf("still water, flip: markers' fastest %.3g m/s after 2 s\n",
              liquid.max_marker_speed());
  EXPECT_LT(liquid.max_marker_speed(), 1e-6);
}

TEST(LiquidFlip, DamBreakKeepsItsVolumeAndItsMarkersTheirVelocities) {
  for (const LiquidAdvection advection :
       {LiquidAdvection::semi_lagrangian, LiquidAdvection::flip}) {
    LiquidDef def = tank(32, 0, advection);
    def.fluid = {{{Vec3(0, 0, 0), Vec3(0.25, 1, 0.5)}, Vec3::Zero()}};
    def.volume_correction = 0.2;
    Liquid liquid(def);
    const Real v0 = liquid.volume();
    liquid.run(2);
    const Real v1 = liquid.volume();
    std::printf("dam break 2 s, %s: volume %.5f -> %.5f m^3\n",
                advection == LiquidAdvection::flip ? "flip" : "semi-Lagrangian", v0, v1);
    EXPECT_NEAR(v1, v0, 0.02 * v0);
    if (advection == LiquidAdvection::flip) {
      EXPECT_EQ(liquid.state.marker_velocity.size(), liquid.state.markers.size());
      // The column fell 0.5 m: its markers move at about sqrt(2 g h) at most, not faster.
      EXPECT_GT(liquid.max_marker_speed(), 0.5);
      EXPECT_LT(liquid.max_marker_speed(), 2 * std::sqrt(2 * kG * 0.5));
    }
  }
}

// The first sloshing mode of a 16-cell tank (the amplitude as the left half's excess over the
// right, as in tests/test_liquid_solver.cpp): its period, and the height its last swing keeps of
// its first.
struct Sloshing {
  Real period = 0, kept = 0;
};
Sloshing slosh(LiquidAdvection advection) {
  constexpr Real kDepth = 0.5, kAmplitude = 0.04;
  constexpr int kCells = 16;
  LiquidDef def = tank(kCells, 1.0, advection);
  def.markers_per_axis = 3;
  Liquid liquid(def);
  std::vector<Vec3>& markers = liquid.state.markers;
  std::vector<Vec3>& velocities = liquid.state.marker_velocity;
  std::size_t kept = 0;
  for (std::size_t m = 0; m < markers.size(); ++m) {
    if (markers[m].z() > kDepth + kAmplitude * std::cos(M_PI * markers[m].x())) continue;
    if (!velocities.empty()) velocities[kept] = velocities[m];
    markers[kept++] = markers[m];
  }
  markers.resize(kept);
  if (!velocities.empty()) velocities.resize(kept);
  auto signal = [&] {
    Real left = 0, right = 0;
    for (const Vec3& x : markers) (x.x() < 0.5 ? left : right) += 1;
    return (left - right) / (left + right);
  };
  constexpr Real kFrame = 1.0 / 120;
  constexpr int kFrames = 480;  // 4 s, about 3.5 periods
  std::vector<Real> s{signal()};
  for (int f = 1; f < kFrames; ++f) {
    liquid.run(kFrame);
    s.push_back(signal());
  }
  // Averaged over 0.1 s against the markers' flicker; the upward zero crossings give the period.
  constexpr int kWindow = 6;
  std::vector<Real> smooth(s.size(), 0.0), crossings;
  for (int f = kWindow; f + kWindow < kFrames; ++f) {
    for (int w = -kWindow; w <= kWindow; ++w) smooth[f] += s[f + w] / (2 * kWindow + 1);
    if (f > kWindow && smooth[f - 1] < 0 && smooth[f] >= 0) {
      crossings.push_back(kFrame * (f - smooth[f] / (smooth[f] - smooth[f - 1])));
    }
  }
  Sloshing out;
  if (crossings.size() >= 2) {
    out.period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  }
  auto peak = [&](int from, int to) {
    Real p = 0;
    for (int f = std::max(from, kWindow); f < std::min(to, kFrames - kWindow); ++f) {
      p = std::max(p, std::abs(smooth[f]));
    }
    return p;
  };
  out.kept = peak(kFrames - 150, kFrames) / peak(0, 150);
  return out;
}

TEST(LiquidFlip, SloshingKeepsItsPeriodAndMoreOfItsHeight) {
  const Real expected = 2 * M_PI / std::sqrt(kG * M_PI * std::tanh(M_PI * 0.5));
  const Sloshing flip = slosh(LiquidAdvection::flip);
  const Sloshing backtrace = slosh(LiquidAdvection::semi_lagrangian);
  std::printf(
      "sloshing 16 cells: theory %.4f s; flip %.4f s, %.3f of its height kept after 3 "
      "periods; semi-Lagrangian %.4f s, %.3f kept\n",
      expected, flip.period, flip.kept, backtrace.period, backtrace.kept);
  EXPECT_NEAR(flip.period, expected, 0.05 * expected);
  EXPECT_GT(flip.kept, backtrace.kept);
}

TEST(LiquidFlip, SameStartSameBits) {
  auto run = [](Real seconds) {
    LiquidDef def = tank(24, 0, LiquidAdvection::flip);
    def.fluid = {{{Vec3(0, 0, 0), Vec3(0.25, 1, 0.5)}, Vec3::Zero()}};
    Liquid liquid(def);
    liquid.run(seconds);
    std::uint64_t h = kFnvOffset;
    hash_liquid_state(liquid.state, h);
    return h;
  };
  EXPECT_EQ(run(0.5), run(0.5));
  EXPECT_NE(run(0.5), run(0.0));
}

TEST(LiquidFlip, HeightFieldIsRefused) {
  LiquidDef def = tank(8, 0.5, LiquidAdvection::flip);
  def.surface = SurfaceMethod::height_field;
  try {
    build_liquid_model(def, Vec3(0, 0, -kG), "f.json", 2);
    FAIL() << "a height field with flip advection was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("liquids[2].advection"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pbm
