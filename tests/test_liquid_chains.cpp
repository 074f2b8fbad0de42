// Free-surface marker chains (16.3.2, fig. 16.5; liquid/surface_chains.h): the cells' exact
// areas, region growing around a pocket of air, the insertion, deletion and join rules, still
// water, a dam break's area beside the marker particles', a drop joining its pool, the first
// sloshing mode against linear wave theory, the surface mesh, determinism and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bits.h"
#include "core/error.h"
#include "liquid/cell_labels.h"
#include "liquid/liquid_step.h"
#include "liquid/liquid_surface_mesh.h"
#include "liquid/surface_chains.h"
#include "liquid_test_support.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81;

// A tank of 1 m x 1 m (x, z), one cell thick in y, liquid in `boxes` tracked by chains.
LiquidDef chain_tank(int cells, std::vector<LiquidBoxDef> boxes) {
  LiquidDef def;
  def.domain = {Vec3(0, 0, 0), Vec3(1, 1.0 / cells, 1)};
  def.resolution = Eigen::Vector3i(cells, 1, cells);
  for (const LiquidBoxDef& box : boxes) def.fluid.push_back({box, Vec3::Zero()});
  def.surface = SurfaceMethod::chains;
  return def;
}

LiquidBoxDef box_xz(Real x0, Real z0, Real x1, Real z1) {
  return {Vec3(x0, -1, z0), Vec3(x1, 2, z1)};
}

struct Chains : test::LoneLiquid {
  using LoneLiquid::LoneLiquid;
  Real area() const { return chains_area(model, state.chain, state.chain_next); }
  Real max_link() const {
    Real worst = 0;
    for (std::size_t m = 0; m < state.chain.size(); ++m) {
      worst = std::max(
          worst,
          (state.chain[m] - state.chain[static_cast<std::size_t>(state.chain_next[m])]).norm());
    }
    return worst;
  }
  Real max_liquid_speed() {
    label_cells(model, state, ws.flags, ws.fill, ws.count);
    const MacGrid& g = model.grid;
    Real worst = 0;
    for (int a = 0; a < 3; ++a) {
      for (int c = g.stride(a); c + g.stride(a) < g.size; ++c) {
        if (!is_liquid(ws.flags[c]) && !is_liquid(ws.flags[c + g.stride(a)])) continue;
        worst = std::max(worst, std::abs(state.velocity.u[a][c]));
      }
    }
    return worst;
  }
};

// A closed polygon in the x-z plane at y = the slab's middle, as chain arrays.
void set_polygon(const LiquidModel& m, const std::vector<std::array<Real, 2>>& corners,
                 std::vector<Vec3>& points, std::vector<int>& next) {
  const int first = static_cast<int>(points.size());
  for (const auto& c : corners) {
    points.emplace_back(c[0], 0.5 * m.grid.h.y(), c[1]);
    next.push_back(static_cast<int>(points.size()));
  }
  next.back() = first;
}

Real overlap(Real a0, Real a1, Real b0, Real b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

TEST(LiquidChains, EachCellHoldsTheExactAreaTheChainsEnclose) {
  const LiquidModel m =
      build_liquid_model(chain_tank(20, {box_xz(0, 0, 1, 0.5)}), Vec3(0, 0, -kG), "test.json", 0);
  const MacGrid& g = m.grid;
  // A rectangle off the grid's lines: each cell's fraction is the product of the overlaps.
  {
    std::vector<Vec3> points;
    std::vector<int> next;
    set_polygon(m, {{{0.23, 0.17}, {0.71, 0.17}, {0.71, 0.58}, {0.23, 0.58}}}, points, next);
    std::vector<Real> fraction;
    chain_cell_fractions(m, points, next, fraction);
    Real worst = 0;
    for (int k = 1; k <= 20; ++k) {
      for (int i = 1; i <= 20; ++i) {
        const Real exact = overlap(0.23, 0.71, (i - 1) * 0.05, i * 0.05) *
                           overlap(0.17, 0.58, (k - 1) * 0.05, k * 0.05) / (0.05 * 0.05);
        worst = std::max(worst, std::abs(fraction[g.index(i, 1, k)] - exact));
      }
    }
    EXPECT_LT(worst, 1e-12);
  }
  // A circle of 200 markers: the cells' areas add up to the polygon's (shoelace) area.
  {
    std::vector<std::array<Real, 2>> corners;
    for (int k = 0; k < 200; ++k) {
      const Real t = 2 * M_PI * k / 200;
      corners.push_back({0.5 + 0.3 * std::cos(t), 0.45 + 0.3 * std::sin(t)});
    }
    std::vector<Vec3> points;
    std::vector<int> next;
    set_polygon(m, corners, points, next);
    std::vector<Real> fraction;
    chain_cell_fractions(m, points, next, fraction);
    Real sum = 0, low = 0, high = 0;
    for (Real f : fraction) {
      sum += f * 0.05 * 0.05;
      low = std::min(low, f);
      high = std::max(high, f);
    }
    const Real polygon = chains_area(m, points, next);
    EXPECT_NEAR(polygon, 0.5 * 200 * 0.09 * std::sin(2 * M_PI / 200), 1e-12);
    EXPECT_NEAR(sum, polygon, 1e-12);
    EXPECT_GT(low, -1e-12);
    EXPECT_LT(high, 1 + 1e-12);
  }
}

TEST(LiquidChains, RegionGrowingKeepsAPocketOfAirSealedInsideTheLiquid) {
  const LiquidModel m =
      build_liquid_model(chain_tank(20, {box_xz(0, 0, 1, 0.5)}), Vec3(0, 0, -kG), "test.json", 0);
  const MacGrid& g = m.grid;
  LiquidState s = initial_liquid_state(m, Vec3(0, 0, -kG));
  s.chain.clear();
  s.chain_next.clear();
  // A block of liquid (counter-clockwise) with a bubble in it (clockwise): the bubble's cells
  // touch no Empty cell outside, so the book's alternation would grow them Full.
  // Off the grid's lines (cells of 0.05 m).
  set_polygon(m, {{{0.12, 0.12}, {0.88, 0.12}, {0.88, 0.78}, {0.12, 0.78}}}, s.chain, s.chain_next);
  set_polygon(m, {{{0.32, 0.32}, {0.32, 0.58}, {0.68, 0.58}, {0.68, 0.32}}}, s.chain, s.chain_next);
  std::vector<CellFlag> flags(g.size);
  std::vector<Real> fill(g.size);
  std::vector<int> count(g.size);
  label_cells(m, s, flags, fill, count);
  auto at = [&](Real x, Real z) {
    const Eigen::Vector3i c = g.cell_of(Vec3(x, 0.5 * g.h.y(), z));
    return flags[g.index(c.x(), c.y(), c.z())];
  };
  EXPECT_EQ(at(0.5, 0.45), CellFlag::empty);  // the bubble
  EXPECT_EQ(at(0.22, 0.45), CellFlag::full);  // the liquid around it
  EXPECT_EQ(at(0.5, 0.7), CellFlag::full);
  EXPECT_EQ(at(0.5, 0.95), CellFlag::empty);  // the air above
  EXPECT_EQ(at(0.025, 0.025), CellFlag::empty);
  // The cells the bubble's chain crosses are Surface (an Empty neighbour inside), and the
  // liquid's area is the cells' sum: 0.76 x 0.66 - 0.36 x 0.26.
  EXPECT_EQ(at(0.33, 0.45), CellFlag::surface);
  EXPECT_NEAR(liquid_volume(m, flags, fill) / g.h.y(), 0.76 * 0.66 - 0.36 * 0.26, 1e-12);
}

TEST(LiquidChains, LongLinksAreSplitCloseMarkersDeletedAndFacingSurfacesJoined) {
  const LiquidModel m =
      build_liquid_model(chain_tank(20, {box_xz(0, 0, 1, 0.5)}), Vec3(0, 0, -kG), "test.json", 0);
  const Real s = chain_spacing(m);  // 0.025 m
  ChainScratch scratch;
  {
    // A square with one link four spacings long and one pair a tenth of a spacing apart.
    std::vector<Vec3> points;
    std::vector<int> next;
    set_polygon(m, {{{0.2, 0.2}, {0.3, 0.2}, {0.3, 0.3}, {0.3025, 0.3}, {0.32, 0.3}, {0.2, 0.3}}},
                points, next);
    const ChainRemeshStats stats = remesh_chains(m, points, next, scratch);
    EXPECT_EQ(stats.deleted, 2);  // (0.3, 0.3) and (0.3025, 0.3)
    EXPECT_EQ(stats.joined, 0);
    Real longest = 0;
    for (std::size_t k = 0; k < points.size(); ++k) {
      longest = std::max(longest, (points[k] - points[next[k]]).norm());
    }
    EXPECT_LE(longest, s + 1e-12);
    EXPECT_EQ(chain_loops(next), 1);
  }
  {
    // Two blocks a fifth of a spacing apart, their facing sides antiparallel: they join into one
    // loop enclosing both, counter-clockwise still.
    std::vector<Vec3> points;
    std::vector<int> next;
    std::vector<std::array<Real, 2>> lower{{0.2, 0.2}, {0.4, 0.2}};
    for (int k = 0; k <= 8; ++k) lower.push_back({0.4 - 0.025 * k, 0.3});  // top, leftwards
    std::vector<std::array<Real, 2>> upper;
    for (int k = 0; k <= 8; ++k) upper.push_back({0.2 + 0.025 * k, 0.305});  // bottom, rightwards
    upper.push_back({0.4, 0.4});
    upper.push_back({0.2, 0.4});
    set_polygon(m, lower, points, next);
    set_polygon(m, upper, points, next);
    const Real before = chains_area(m, points, next);
    const ChainRemeshStats stats = remesh_chains(m, points, next, scratch);
    EXPECT_GE(stats.joined, 1);
    EXPECT_EQ(chain_loops(next), 1);
    EXPECT_GT(chains_area(m, points, next), 0.9 * before);
  }
}

TEST(LiquidChains, StillWaterStaysStillWithHydrostaticPressure) {
  Chains liquid(chain_tank(12, {box_xz(0, 0, 1, 0.45)}));
  const Real a0 = liquid.area();
  LiquidStepStats stats;
  for (int step = 0; step < 1000; ++step) {
    liquid_substep(liquid.model, liquid.inputs, 0.01, liquid.state, liquid.ws, stats);
  }
  EXPECT_LT(liquid.max_liquid_speed(), 1e-6);
  EXPECT_NEAR(liquid.area(), a0, 1e-9);
  const MacGrid& g = liquid.model.grid;
  int checked = 0;
  for (int c = 0; c < g.size; ++c) {
    if (liquid.ws.flags[c] != CellFlag::full) continue;
    const Real depth = 0.45 - (c / g.sz - 0.5) * g.h.z();
    if (depth < 0) continue;
    EXPECT_NEAR(liquid.state.pressure[c], kG * depth, 0.01 * kG * depth);
    ++checked;
  }
  EXPECT_GT(checked, 30);
  for (const Vec3& x : liquid.state.chain) EXPECT_LE(x.z(), 0.45 + 1e-9);
}

TEST(LiquidChains, ADamBreakKeepsItsAreaAndRunsBesideTheMarkers) {
  LiquidDef def = chain_tank(32, {box_xz(0, 0, 0.25, 0.5)});
  Chains chains(def);
  def.surface = SurfaceMethod::markers;
  def.volume_correction = 0.2;
  test::LoneLiquid markers(def);
  const Real a0 = chains.area();
  Real worst_link = 0;
  for (int frame = 1; frame <= 6; ++frame) {
    chains.run(0.05);
    markers.run(0.05);
    worst_link = std::max(worst_link, chains.max_link());
  }
  // The front (the furthest liquid along x) at 0.3 s, both ways.
  Real front_chains = 0, front_markers = 0;
  for (const Vec3& x : chains.state.chain) front_chains = std::max(front_chains, x.x());
  for (const Vec3& x : markers.state.markers) front_markers = std::max(front_markers, x.x());
  std::printf(
      "dam break 0.3 s: area %.5f -> %.5f m^2, front chains %.3f m markers %.3f m, "
      "longest link %.4f m, %zu chain markers\n",
      a0, chains.area(), front_chains, front_markers, worst_link, chains.state.chain.size());
  EXPECT_NEAR(chains.area(), a0, 0.02 * a0);
  EXPECT_NEAR(front_chains, front_markers, 2.0 / 32);
  EXPECT_LE(worst_link, chain_spacing(chains.model) + 1e-12);
  // The cells agree with the chains' area.
  const Real cells = chains.volume() / chains.model.grid.h.y();
  EXPECT_NEAR(cells, chains.area(), 0.01 * a0);
}

// The closed-tank test for each surface method: 2000 steps of a dam break.
// The closed-tank test for each surface method: 2000 steps of a dam break, its splashes
// joining and dropping loops. The chains drift 3.5% in area without the correction (0.12500 ->
// 0.12940 m^2), none with it at 0.2.
TEST(LiquidChains, AClosedTankKeepsItsAreaOver2000Steps) {
  for (Real correction : {0.0, 0.2}) {
    LiquidDef def = chain_tank(32, {box_xz(0, 0, 0.25, 0.5)});
    def.volume_correction = correction;
    Chains liquid(def);
    const Real a0 = liquid.area(), v0 = liquid.volume();
    LiquidStepStats stats;
    for (int step = 0; step < 2000; ++step) {
      liquid_substep(liquid.model, liquid.inputs, 0.002, liquid.state, liquid.ws, stats);
    }
    std::printf(
        "dam break chains, 4 s, volume_correction %.1f: area %.5f -> %.5f m^2, cells %.6f -> "
        "%.6f m^3, %d joins, %d loops dropped\n",
        correction, a0, liquid.area(), v0, liquid.volume(), stats.chain_joins,
        stats.chain_loops_dropped);
    // The cells hold what the chains enclose.
    EXPECT_NEAR(liquid.volume() / liquid.model.grid.h.y(), liquid.area(), 1e-9);
    if (correction > 0) {
      EXPECT_NEAR(liquid.area(), a0, 0.01 * a0);
    }
  }
}

// The area of each loop [m^2], largest first.
std::vector<Real> loop_areas(const LiquidModel& m, const std::vector<Vec3>& points,
                             const std::vector<int>& next) {
  std::vector<Real> areas;
  std::vector<bool> seen(points.size(), false);
  for (std::size_t start = 0; start < points.size(); ++start) {
    if (seen[start]) continue;
    std::vector<Vec3> loop;
    std::vector<int> links;
    for (auto k = start; !seen[k]; k = static_cast<std::size_t>(next[k])) {
      seen[k] = true;
      loop.push_back(points[k]);
      links.push_back(static_cast<int>(loop.size()));
    }
    links.back() = 0;
    areas.push_back(chains_area(m, loop, links));
  }
  std::sort(areas.rbegin(), areas.rend());
  return areas;
}

TEST(LiquidChains, ADropJoinsItsPoolAndTheAreaHolds) {
  LiquidDef def = chain_tank(24, {box_xz(0, 0, 1, 0.3), box_xz(0.4, 0.6, 0.6, 0.8)});
  def.volume_correction = 0.2;
  Chains liquid(def);
  EXPECT_EQ(chain_loops(liquid.state.chain_next), 2);
  const Real a0 = liquid.area();
  // It falls 0.3 m (0.25 s), then splashes: the pool and the drop are one loop after it, the
  // splash's droplets and bubbles a few more.
  liquid.run(0.6);
  const std::vector<Real> areas =
      loop_areas(liquid.model, liquid.state.chain, liquid.state.chain_next);
  std::printf("drop: %zu loops, the largest %.5f of %.5f m^2 (start %.5f), %d joins\n",
              areas.size(), areas[0], liquid.area(), a0, liquid.stats.chain_joins);
  EXPECT_GE(liquid.stats.chain_joins, 1);
  EXPECT_GT(areas[0], 0.97 * a0);  // the drop (0.04 m^2, 12% of it) is in the pool's loop
  EXPECT_NEAR(liquid.area(), a0, 0.01 * a0);
}

// The first mode of a tank of length 1 and depth 0.5 (omega^2 = g k tanh(k D), k = pi), its
// amplitude as the liquid's area in the left half over the right half.
Real chain_sloshing_period(int cells) {
  // An amplitude of two thirds of the coarsest grid's cell (k a = 0.13: linear theory within
  // 0.3%); a tenth of that is lost in the coarse grid's Surface cells.
  constexpr Real kDepth = 0.5, kAmplitude = 0.04;
  Chains liquid(chain_tank(cells, {box_xz(0, 0, 1, kDepth)}));
  // The top side of the seeded loop bent to the mode's shape.
  for (Vec3& x : liquid.state.chain) {
    if (x.z() > kDepth - 1e-9) x.z() = kDepth + kAmplitude * std::cos(M_PI * x.x());
  }
  std::vector<Real> fraction;
  auto imbalance = [&] {
    chain_cell_fractions(liquid.model, liquid.state.chain, liquid.state.chain_next, fraction);
    const MacGrid& g = liquid.model.grid;
    Real left = 0, right = 0;
    for (int k = 1; k <= cells; ++k) {
      for (int i = 1; i <= cells; ++i)
        (i <= cells / 2 ? left : right) += fraction[g.index(i, 1, k)];
    }
    return (left - right) / cells;
  };
  constexpr Real kFrame = 1.0 / 240;
  std::vector<Real> crossings;
  Real previous = imbalance();
  for (int frame = 1; frame < 960; ++frame) {
    liquid.run(kFrame);
    const Real now = imbalance();
    if (previous < 0 && now >= 0) crossings.push_back(kFrame * (frame - now / (now - previous)));
    previous = now;
  }
  if (crossings.size() < 2) return 0;
  return (crossings.back() - crossings.front()) / (crossings.size() - 1);
}

// Within 1.7% of linear theory at 16, 32 and 64 cells (1.1954 s, 1.2022 s, 1.1924 s against
// 1.1818 s; the finite amplitude's own correction, Tadjbakhsh & Keller, is +0.3%), but not
// closer at each refinement: like the height field's, asserted within the tolerance only.
TEST(LiquidChains, SloshingPeriodIsLinearWaveTheorysAtThreeResolutions) {
  const Real expected = 2 * M_PI / std::sqrt(kG * M_PI * std::tanh(M_PI * 0.5));
  for (int cells : {16, 32, 64}) {
    const Real period = chain_sloshing_period(cells);
    std::printf("chains sloshing period: theory %.4f s, %d cells %.4f s\n", expected, cells,
                period);
    EXPECT_NEAR(period, expected, 0.03 * expected) << cells;
  }
}

TEST(LiquidChains, TheSurfaceMeshEnclosesTheChainsArea) {
  Chains liquid(chain_tank(20, {box_xz(0, 0, 0.4, 0.5)}));
  liquid.run(0.3);
  const LiquidSurfaceMesh mesh = liquid_surface_mesh(liquid.model, liquid.state, {});
  ASSERT_GT(mesh.triangles.size(), 100u);
  Real volume = 0;  // the divergence theorem over the closed mesh
  for (const auto& t : mesh.triangles) {
    volume += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]])) / 6;
  }
  const Real expected = liquid.area() * liquid.model.grid.h.y();
  std::printf("chains mesh: %.6f m^3 against %.6f (area x thickness)\n", volume, expected);
  EXPECT_NEAR(volume, expected, 0.12 * expected);
}

TEST(LiquidChains, SameStartSameBits) {
  auto run = [](Real seconds) {
    Chains liquid(chain_tank(24, {box_xz(0, 0, 0.25, 0.5)}));
    liquid.run(seconds);
    std::uint64_t h = kFnvOffset;
    hash_liquid_state(liquid.state, h);
    return h;
  };
  EXPECT_EQ(run(0.5), run(0.5));
  EXPECT_NE(run(0.5), run(0.0));
}

TEST(LiquidChains, WhatChainsCannotTrackIsRefusedByName) {
  auto refused = [](LiquidDef def, const std::string& path) {
    try {
      (void)build_liquid_model(def, Vec3(0, 0, -kG), "test.json", 0);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.path(), path) << e.what();
    }
  };
  LiquidDef def = chain_tank(16, {box_xz(0, 0, 0.5, 0.5)});
  LiquidDef three_d = def;
  three_d.resolution = Eigen::Vector3i(16, 16, 16);
  three_d.domain.max.y() = 1;
  refused(three_d, "liquids[0].surface");
  LiquidDef inflow = def;
  inflow.inflows.push_back({box_xz(0.9, 0.9, 1, 1), Vec3(0, 0, -1), 0});
  refused(inflow, "liquids[0].inflows");
  LiquidDef outflow = def;
  outflow.outflows.push_back(box_xz(0.9, 0, 1, 0.1));
  refused(outflow, "liquids[0].outflows");
  LiquidDef spray = def;
  spray.spray_speed = 1;
  refused(spray, "liquids[0].spray_speed");
  LiquidDef overlapping = def;
  overlapping.fluid.push_back({box_xz(0.4, 0, 0.8, 0.3), Vec3::Zero()});
  refused(overlapping, "liquids[0].fluid[1]");
}

}  // namespace
}  // namespace pbm
