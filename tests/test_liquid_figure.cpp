// Figures in a liquid (sim/liquid_segment_loads.h, 16.4): each segment's surface patches
// (figure/segment_surface.h) are closed and enclose the shape's volume, and the hydrostatic
// pressure integrated over them is Archimedes' force of the part under a water line, converging
// as the patches are refined; in a tank, a sphere on a free joint denser than the liquid sinks at
// g (1 - rho_l / rho_s) from rest, a box of half the liquid's density floats with half its height
// submerged, a hinged chain dipped into the water swings and settles without the stability guard
// refusing the buoyancy's work, and its runs are bit-identical. Two-way, a sunken segment
// displaces its volume and a swinging paddle moves the liquid (one way it does not).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/quaternion.h"
#include "figure/figure_build.h"
#include "figure/segment_surface.h"
#include "liquid_test_support.h"
#include "scene/scene_json.h"
#include "sim/liquid_segment_loads.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81, kRho = 1000, kPi = std::numbers::pi;

SegmentShapeDef shape_of(SegmentShapeKind kind, const Vec3& size) {
  SegmentShapeDef s;
  s.kind = kind;
  s.size = size;
  return s;
}

// The upward force per unit rho g of the hydrostatic pressure (water line at height w in the
// segment's frame, z up) over the patches: the submerged volume, by -oint p n dA.
Real submerged_by_patches(const std::vector<SurfacePatch>& patches, Real w) {
  Real f = 0;
  for (const SurfacePatch& p : patches) f -= std::max(0.0, w - p.point.z()) * p.area_normal.z();
  return f;
}

// A sphere's cap below a plane `d` above its lowest point [m^3].
Real cap_volume(Real r, Real d) {
  d = std::clamp(d, 0.0, 2 * r);
  return kPi * d * d * (3 * r - d) / 3;
}

TEST(SegmentSurface, PatchesAreClosedAndEncloseTheShapesVolume) {
  const SegmentShapeDef shapes[] = {
      shape_of(SegmentShapeKind::box, {0.1, 0.2, 0.05}),
      shape_of(SegmentShapeKind::sphere, {0.1, 0.1, 0.1}),
      shape_of(SegmentShapeKind::cylinder, {0.05, 0.05, 0.2}),
      shape_of(SegmentShapeKind::capsule, {0.04, 0.04, 0.15}),
  };
  for (SegmentShapeDef s : shapes) {
    // Turned and moved in its segment: the patches follow.
    s.center = Vec3(0.3, -0.1, 0.2);
    s.orientation = quaternion_from_axis_angle(Vec3(1, 2, 3).normalized(), 0.7);
    std::vector<SurfacePatch> patches;
    segment_surface_patches(s, kSegmentSurfaceDivisions, patches);
    Vec3 sum = Vec3::Zero();
    Real volume = 0, area = 0;
    for (const SurfacePatch& p : patches) {
      sum += p.area_normal;
      volume += (p.point - s.center).dot(p.area_normal) / 3;
      area += p.area_normal.norm();
    }
    const Real v = shape_volume(s);
    EXPECT_LT(sum.norm(), 1e-12) << static_cast<int>(s.kind);
    // Every point on the exact surface, its normal outward: x . n dA / 3 sums to the volume.
    EXPECT_NEAR(volume / v, 1, 1e-6) << static_cast<int>(s.kind);
    EXPECT_GT(area, 0);
  }
}

TEST(SegmentSurface, PressureOverThePatchesIsArchimedesAndConvergesUnderRefinement) {
  // A sphere cut at several water lines: the submerged cap's volume, the error as a fraction of
  // the sphere's (the scale of the force on it); wholly under water, exact.
  const Real r = 0.1;
  const Real volume = 4 * kPi * r * r * r / 3;
  const SegmentShapeDef sphere = shape_of(SegmentShapeKind::sphere, {r, r, r});
  Real last = 1e300;
  for (int divisions : {2, 4, 8, 16}) {
    std::vector<SurfacePatch> patches;
    segment_surface_patches(sphere, divisions, patches);
    Real worst = 0;
    for (Real w : {-0.07, -0.03, 0.0, 0.011, 0.05, 0.09}) {
      const Real exact = cap_volume(r, w + r);
      worst = std::max(worst, std::abs(submerged_by_patches(patches, w) - exact) / volume);
    }
    std::printf("sphere, %2d divisions (%4zu points): worst error %.5f of its volume\n", divisions,
                patches.size(), worst);
    EXPECT_NEAR(submerged_by_patches(patches, 0.2) / volume, 1, 1e-12);
    EXPECT_LT(worst, last) << divisions;
    if (divisions >= kSegmentSurfaceDivisions) {
      EXPECT_LT(worst, 0.0015) << divisions;
    }
    last = worst;
  }
  // Upright cylinder and capsule: the water line along their length.
  for (SegmentShapeKind kind : {SegmentShapeKind::cylinder, SegmentShapeKind::capsule}) {
    const Real rc = 0.05, h = 0.2;
    const SegmentShapeDef s = shape_of(kind, {rc, rc, h});
    std::vector<SurfacePatch> patches;
    segment_surface_patches(s, kSegmentSurfaceDivisions, patches);
    for (Real w : {-0.13, 0.0, 0.07}) {
      Real exact = kPi * rc * rc * (w + h);
      if (kind == SegmentShapeKind::capsule) exact += 2 * kPi * rc * rc * rc / 3;
      EXPECT_NEAR(submerged_by_patches(patches, w) / exact, 1, 0.005) << static_cast<int>(kind);
    }
  }
}

// A tank of still water (a height field, one way: the figure feels it, the water does not see
// the figure), 1 x 1 m, depth `depth`, with a floor plane, and the figures given.
std::string tank_scene(Real depth, Real drag, const std::string& figures, Real top = 0.8) {
  char text[4096];
  std::snprintf(text, sizeof text,
                R"({"name": "tank", "solver": {"fps": 30, "dt": 0.005, "integrator": "rk4"},
      "obstacles": [{"name": "floor", "kind": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
                     "size": [4, 4], "elasticity": 20000, "friction": 0.3}],
      "liquids": [{"name": "water", "domain": {"min": [0, 0, 0], "max": [1, 1, %.17g]},
                   "resolution": [16, 16, 16], "surface": "height_field",
                   "coupling": "one_way", "drag": %.17g,
                   "fluid": [{"box": {"min": [0, 0, 0], "max": [1, 1, %.17g]}}]}],
      "figures": [%s]})",
                top, drag, depth, figures.c_str());
  return text;
}

TEST(LiquidFigure, ADenseSphereSinksFromRestAtGravityLessBuoyancy) {
  const Real r = 0.05, density = 2000, depth = 0.6;
  char figure[512];
  std::snprintf(figure, sizeof figure,
                R"({"name": "ball", "segments": [{"name": "ball",
                     "joint": {"kind": "free", "q0": [0.5, 0.5, 0.4, 1, 0, 0, 0]},
                     "shape": {"kind": "sphere", "size": [%.17g, %.17g, %.17g]},
                     "density": %.17g}]})",
                r, r, r, density);
  Simulation sim(parse_scene(tank_scene(depth, 0, figure), "tank.json"));
  const Real volume = 4 * kPi * r * r * r / 3;
  // Archimedes' force on the sphere at rest, wholly under the surface.
  const Vec3 f = sim.stats.liquids.at(0).body_force;
  std::printf("buoyancy %.5f N, rho g V %.5f N\n", f.z(), kRho * kG * volume);
  EXPECT_NEAR(f.z() / (kRho * kG * volume), 1, 1e-6);
  EXPECT_NEAR(f.x(), 0, 1e-9);
  EXPECT_NEAR(f.y(), 0, 1e-9);
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(advance_frame(sim).ok);
  const Real t = sim.state.time;
  // v = (omega, v_O) in the segment's frame; it has not turned.
  const Real vz = sim.state.v[sim.model.figures[0].model.state_v_offset + 5];
  const Real expected = -kG * (1 - kRho / density) * t;
  std::printf("after %.3f s: v_z %.5f m/s, g (1 - rho_l/rho_s) t %.5f m/s\n", t, vz, expected);
  EXPECT_NEAR(vz / expected, 1, 0.01);
}

TEST(LiquidFigure, AHalfDensityBoxFloatsHalfSubmerged) {
  const Real depth = 0.47, half_height = 0.05;
  char figure[512];
  std::snprintf(figure, sizeof figure,
                R"({"name": "raft", "segments": [{"name": "raft",
                     "joint": {"kind": "free", "q0": [0.5, 0.5, 0.6, 1, 0, 0, 0]},
                     "shape": {"kind": "box", "size": [0.15, 0.15, %.17g]},
                     "density": 500}]})",
                half_height);
  const Scene scene = parse_scene(tank_scene(depth, 1, figure), "tank.json");
  Simulation sim(scene), again(scene);
  Real late_sum = 0;
  for (int f = 0; f < 150; ++f) {
    const FrameResult res = advance_frame(sim);
    ASSERT_TRUE(res.ok) << "frame " << f << ": " << res.message;
    ASSERT_TRUE(advance_frame(again).ok);
    if (f >= 120) late_sum += sim.state.q[sim.model.figures[0].model.state_q_offset + 2];
  }
  EXPECT_EQ(hash_state(sim.state), hash_state(again.state));
  const Real mean = late_sum / 30;
  std::printf("raft's centre over the 5th second %.4f m, the surface at %.4f m\n", mean, depth);
  // Half its height under the surface: its centre at the surface, within 5% of its height.
  EXPECT_NEAR(mean, depth, 0.05 * 2 * half_height);
}

TEST(LiquidFigure, AChainDippedIntoWaterSwingsAndSettlesUnderTheGuard) {
  // Two capsules of density 800 hinged in a chain from a pivot 0.2 m above the water, released
  // horizontal: they swing down into the water, which drags them and holds them up.
  const char* figure = R"({"name": "chain", "segments": [
      {"name": "upper", "joint": {"kind": "revolute", "axis": [0, 1, 0], "position": [0.2, 0.5, 0.67],
                                  "q0": [1.5707963267948966], "damping": 0.001},
       "shape": {"kind": "capsule", "size": [0.03, 0.03, 0.1], "center": [0, 0, -0.13]},
       "density": 800, "sites": [{"name": "tip", "position": [0, 0, -0.26]}]},
      {"name": "lower", "parent": "upper",
       "joint": {"kind": "revolute", "axis": [0, 1, 0], "position": [0, 0, -0.26], "damping": 0.001},
       "shape": {"kind": "capsule", "size": [0.03, 0.03, 0.1], "center": [0, 0, -0.13]},
       "density": 800}]})";
  const Scene scene = parse_scene(tank_scene(0.47, 1, figure), "chain.json");
  Simulation sim(scene), dry(parse_scene(tank_scene(0.01, 1, figure), "dry.json"));
  // The upper joint's range over the 4th second, in water and in air.
  const int q0 = sim.model.figures[0].model.state_q_offset;
  Real wet_lo = 1e300, wet_hi = -1e300, dry_lo = 1e300, dry_hi = -1e300;
  for (int f = 0; f < 120; ++f) {
    const FrameResult res = advance_frame(sim);
    ASSERT_TRUE(res.ok) << "frame " << f << ": " << res.message;
    ASSERT_TRUE(advance_frame(dry).ok);
    if (f < 90) continue;
    wet_lo = std::min(wet_lo, sim.state.q[q0]);
    wet_hi = std::max(wet_hi, sim.state.q[q0]);
    dry_lo = std::min(dry_lo, dry.state.q[q0]);
    dry_hi = std::max(dry_hi, dry.state.q[q0]);
  }
  std::printf("the upper joint's range over the 4th second: %.4f rad in water, %.4f in air\n",
              wet_hi - wet_lo, dry_hi - dry_lo);
  // In the water the drag has taken the swing; in air only the joints' light damping.
  EXPECT_LT(wet_hi - wet_lo, 0.2 * (dry_hi - dry_lo));
  // It rests in the water, held up by it: some of it wet.
  EXPECT_GT(sim.stats.liquids.at(0).wetted_area, 0.005);
  EXPECT_EQ(dry.stats.liquids.at(0).wetted_area, 0);
}

// A tank 0.6 x 0.6 m with water 0.4 m deep, h = 0.025 m, markers, coupled `coupling`, and the
// figures given.
std::string two_way_tank(const std::string& coupling, const std::string& figures,
                         const std::string& resolution = "[24, 24, 28]",
                         const std::string& y_max = "0.6") {
  return R"({"name": "tank", "solver": {"fps": 30, "dt": 0.004, "integrator": "rk4"},
    "obstacles": [{"name": "floor", "kind": "plane", "point": [0, 0, 0], "normal": [0, 0, 1],
      "size": [2, 2], "elasticity": 20000, "friction": 0.5}],
    "liquids": [{"name": "water", "domain": {"min": [0, 0, 0], "max": [0.6, )" +
         y_max + R"(, 0.7]}, "resolution": )" + resolution + R"(, "coupling": ")" + coupling +
         R"(", "drag": 1, "volume_correction": 0.2,
      "fluid": [{"box": {"min": [0, 0, 0], "max": [0.6, )" +
         y_max + R"(, 0.4]}}]}],
    "figures": [)" +
         figures + "]}";
}

TEST(LiquidFigure, TwoWayASunkenSegmentDisplacesItsVolume) {
  // A box 0.16 x 0.16 x 0.12 m of three times the liquid's density on a free joint, released
  // with its bottom just over the water: it sinks to the floor.
  const char* figure = R"({"name": "block", "segments": [{"name": "block",
      "joint": {"kind": "free", "q0": [0.3, 0.3, 0.47, 1, 0, 0, 0]},
      "shape": {"kind": "box", "size": [0.08, 0.08, 0.06]}, "density": 3000}]})";
  Simulation sim(parse_scene(two_way_tank("two_way", figure), "block.json"));
  const LiquidModel& m = sim.model.liquids[0];
  const Real area = 0.36, volume = 0.16 * 0.16 * 0.12;
  const Real level0 = test::mean_surface_height(m, sim.ws.liquids[0]);
  const Real volume0 = sim.stats.liquids.at(0).volume;
  for (int f = 0; f < 24; ++f) {
    const FrameResult res = advance_frame(sim);
    ASSERT_TRUE(res.ok) << "frame " << f << ": " << res.message;
  }
  const Real z = sim.state.q[sim.model.figures[0].model.state_q_offset + 2];
  EXPECT_LT(z, 0.06 + 0.01) << "the block rests on the floor";
  const Real rise = test::mean_surface_height(m, sim.ws.liquids[0]) - level0;
  const int covered = sim.stats.liquids.at(0).step.solid_cells;
  const Real cells_volume = covered * m.grid.cell_volume();
  const Real liquid_change = (sim.stats.liquids.at(0).volume - volume0) / area;
  std::printf(
      "sunken block: %d cells (%.6f m^3, the block %.6f), the water rose %.5f m "
      "(volume over area %.5f m, the liquid's own change %.5f m)\n",
      covered, cells_volume, volume, rise, volume / area, liquid_change);
  // Its cells are its volume: 6.4 x 6.4 x 4.8 cells, centres inside 6 x 6 x 4 or 7 x 7 x 5.
  EXPECT_NEAR(cells_volume / volume, 1, 0.25);
  // The level is the liquid's volume plus the solid's.
  EXPECT_NEAR(rise, cells_volume / area + liquid_change, 0.002);
  EXPECT_GT(rise, 0.5 * volume / area);
}

TEST(LiquidFigure, TwoWayASwingingPaddleMakesWavesOneWayItDoesNot) {
  // A paddle hinged over a 2D tank, released from horizontal: it swings down through the water.
  const char* figure = R"({"name": "paddle", "segments": [{"name": "paddle",
      "joint": {"kind": "revolute", "axis": [0, 1, 0], "position": [0.3, 0.0125, 0.6],
                "q0": [1.5707963267948966]},
      "shape": {"kind": "box", "size": [0.02, 0.2, 0.15], "center": [0, 0, -0.2]},
      "density": 2000}]})";
  Real fastest[2] = {0, 0}, worst_volume = 0;
  for (int k = 0; k < 2; ++k) {
    Simulation sim(
        parse_scene(two_way_tank(k == 0 ? "two_way" : "one_way", figure, "[24, 1, 28]", "0.025"),
                    "paddle.json"));
    const Real volume0 = sim.stats.liquids.at(0).volume;
    for (int f = 0; f < 30; ++f) {
      const FrameResult res = advance_frame(sim);
      ASSERT_TRUE(res.ok) << "frame " << f << ": " << res.message;
      fastest[k] = std::max(fastest[k], sim.stats.liquids.at(0).max_speed);
      if (k == 0) {
        worst_volume =
            std::max(worst_volume, std::abs(sim.stats.liquids.at(0).volume / volume0 - 1));
      }
    }
  }
  std::printf(
      "swinging paddle: the liquid's fastest face %.4f m/s two-way (its volume within %.2f%%), "
      "%.2g one-way\n",
      fastest[0], 100 * worst_volume, fastest[1]);
  EXPECT_GT(fastest[0], 0.2);
  EXPECT_LT(fastest[1], 1e-6);
  EXPECT_LT(worst_volume, 0.05);
}

}  // namespace
}  // namespace pbm
