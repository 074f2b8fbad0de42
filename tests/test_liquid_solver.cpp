// The liquid grid of ch. 16 on its own (engine/liquid/): still water, hydrostatic pressure, the
// divergence after each solve, volume, the first sloshing mode against linear wave theory, the
// three pressure solvers against each other, inflow volume and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bits.h"
#include "liquid/boundary_conditions.h"
#include "liquid/cell_labels.h"
#include "liquid/liquid_step.h"
#include "liquid_test_support.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81;

struct Liquid : test::LoneLiquid {
  using LoneLiquid::LoneLiquid;
  void label() { label_cells(model, state, ws.flags, ws.fill, ws.count); }
  // The largest speed on a face with liquid on a side [m/s].
  Real max_liquid_speed() {
    label();
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

// A tank of 1 m x 1 m (x, z), one cell thick in y (2D) or cubic (3D), water to `depth`.
LiquidDef tank(int cells, Real depth, bool three_d) {
  LiquidDef def;
  def.domain = {Vec3(0, 0, 0), Vec3(1, three_d ? 1.0 : 1.0 / cells, 1)};
  def.resolution = Eigen::Vector3i(cells, three_d ? cells : 1, cells);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(1, 1, depth)}, Vec3::Zero()});
  return def;
}

LiquidDef dam_break(int cells) {
  LiquidDef def = tank(cells, 0, false);
  def.fluid = {{{Vec3(0, 0, 0), Vec3(0.25, 1, 0.5)}, Vec3::Zero()}};
  return def;
}

TEST(LiquidSolver, StillWaterStaysStillUnderHydrostaticPressure) {
  for (PressureSolver solver :
       {PressureSolver::relaxation, PressureSolver::mic_pcg, PressureSolver::mgpcg}) {
    for (bool three_d : {false, true}) {
      LiquidDef def = tank(12, 0.5, three_d);
      def.solver = solver;
      def.advection = solver == PressureSolver::relaxation ? LiquidAdvection::book
                                                           : LiquidAdvection::semi_lagrangian;
      Liquid liquid(def);
      LiquidStepStats stats;
      for (int step = 0; step < 1000; ++step) {
        liquid_substep(liquid.model, liquid.inputs, 0.01, liquid.state, liquid.ws, stats);
      }
      EXPECT_LT(liquid.max_liquid_speed(), 1e-6) << static_cast<int>(solver) << three_d;
      // p = rho g depth at every Full cell's centre, within 1%.
      const MacGrid& g = liquid.model.grid;
      int checked = 0;
      for (int c = 0; c < g.size; ++c) {
        if (liquid.ws.flags[c] != CellFlag::full) continue;
        const int k = c / g.sz;
        const Real depth = 0.5 - (k - 0.5) * g.h.z();
        const Real p = def.density * liquid.state.pressure[c];
        EXPECT_NEAR(p, def.density * kG * depth, 0.01 * def.density * kG * depth);
        ++checked;
      }
      EXPECT_GT(checked, 0);
    }
  }
}

TEST(LiquidSolver, HeightFieldSurfaceInsideACellKeepsHydrostaticPressure) {
  LiquidDef def = tank(12, 0.45, false);  // the surface 0.4 of the way up its cell
  def.surface = SurfaceMethod::height_field;
  Liquid liquid(def);
  liquid.run(5.0);
  EXPECT_LT(liquid.max_liquid_speed(), 1e-6);
  const MacGrid& g = liquid.model.grid;
  for (int c = 0; c < g.size; ++c) {
    if (liquid.ws.flags[c] != CellFlag::full) continue;
    const Real depth = 0.45 - (c / g.sz - 0.5) * g.h.z();
    EXPECT_NEAR(liquid.state.pressure[c], kG * depth, 0.01 * kG * depth);
  }
  for (Real h : liquid.state.height) EXPECT_NEAR(h, 0.45, 1e-9);
}

TEST(LiquidSolver, EverySolveLeavesFullCellsDivergenceFreeWithinCfl) {
  for (PressureSolver solver :
       {PressureSolver::relaxation, PressureSolver::mic_pcg, PressureSolver::mgpcg}) {
    LiquidDef def = dam_break(32);
    def.solver = solver;
    Liquid liquid(def);
    const LiquidStepStats stats = liquid.run(1.0);
    std::printf(
        "dam break 32, solver %d: %d substeps, %d iterations (max %d), max divergence "
        "%.2e 1/s, max CFL %.3f\n",
        static_cast<int>(solver), stats.substeps, stats.iterations, stats.max_iterations,
        stats.divergence, stats.cfl);
    EXPECT_EQ(stats.unconverged, 0);
    EXPECT_LT(stats.divergence, def.tolerance);
    EXPECT_LE(stats.cfl, 1.0);
    EXPECT_GT(stats.substeps, 20);
  }
}

TEST(LiquidSolver, VolumeInAClosedTankIsConserved) {
  {
    // Markers through a discrete field drift together (21% of the volume lost in 4 s at 2 x 2 a
    // cell without it): the knob that pushes packed markers apart holds the volume.
    LiquidDef def = dam_break(32);
    def.volume_correction = 0.2;
    Liquid liquid(def);
    const Real v0 = liquid.volume();
    LiquidStepStats stats;
    for (int step = 0; step < 2000; ++step) {
      liquid_substep(liquid.model, liquid.inputs, 0.002, liquid.state, liquid.ws, stats);
    }
    std::printf("dam break markers: volume %.5f -> %.5f m^3\n", v0, liquid.volume());
    EXPECT_NEAR(liquid.volume(), v0, 0.01 * v0);
  }
  {
    LiquidDef def = tank(32, 0.5, false);
    def.surface = SurfaceMethod::height_field;
    Liquid liquid(def);
    const Real v0 = liquid.volume();
    for (std::size_t i = 0; i < liquid.state.height.size(); ++i) {
      liquid.state.height[i] = 0.5 + 0.05 * std::cos(M_PI * (i + 0.5) / 32);
    }
    EXPECT_NEAR(liquid.volume(), v0, 1e-3 * v0);
    LiquidStepStats stats;
    for (int step = 0; step < 2000; ++step) {
      liquid_substep(liquid.model, liquid.inputs, 0.002, liquid.state, liquid.ws, stats);
    }
    std::printf("sloshing height field: volume %.5f -> %.5f m^3\n", v0, liquid.volume());
    EXPECT_NEAR(liquid.volume(), v0, 0.01 * v0);
  }
}

// The first mode of a tank of length L and depth D: omega^2 = g k tanh(k D), k = pi / L.
Real sloshing_period(int cells, SurfaceMethod surface) {
  // An amplitude of a few marker spacings (k a = 0.13: linear theory within 1%).
  constexpr Real kDepth = 0.5, kAmplitude = 0.04;
  LiquidDef def = tank(cells, kDepth, false);
  def.surface = surface;
  def.markers_per_axis = 3;

  Liquid liquid(def);
  auto surface_at = [&](Real x) { return kDepth + kAmplitude * std::cos(M_PI * x); };
  if (surface == SurfaceMethod::height_field) {
    for (int i = 0; i < cells; ++i) liquid.state.height[i] = surface_at((i + 0.5) / cells);
  } else {
    LiquidDef full = tank(cells, 1.0, false);
    full.surface = surface;
    full.markers_per_axis = 3;
    liquid.state.markers =
        initial_liquid_state(build_liquid_model(full, liquid.inputs.gravity, "test.json", 0),
                             liquid.inputs.gravity)
            .markers;
    std::erase_if(liquid.state.markers, [&](const Vec3& x) { return x.z() > surface_at(x.x()); });
  }
  // The first mode's amplitude, as the liquid's excess in the left half over the right half
  // (an integral, which the markers' quantization of the surface averages out).
  auto left_height = [&] {
    Real left = 0, right = 0;
    if (surface == SurfaceMethod::height_field) {
      for (int i = 0; i < cells; ++i) (i < cells / 2 ? left : right) += liquid.state.height[i];
      return kDepth + (left - right) / cells;
    }
    for (const Vec3& x : liquid.state.markers) (x.x() < 0.5 ? left : right) += 1;
    return kDepth + (left - right) / (left + right);
  };
  // The signal at 240 Hz for 4 s (almost four periods), averaged over 0.1 s (the markers' count
  // moves in steps and flickers about zero), then its upward crossings of zero, linearly
  // interpolated in time.
  constexpr Real kFrame = 1.0 / 240;
  constexpr int kFrames = 960, kWindow = 12;
  std::vector<Real> signal{left_height() - kDepth};
  for (int frame = 1; frame < kFrames; ++frame) {
    liquid.run(kFrame);
    signal.push_back(left_height() - kDepth);
  }
  std::vector<Real> crossings;
  Real previous = 0;
  for (int f = kWindow; f + kWindow < kFrames; ++f) {
    Real now = 0;
    for (int w = -kWindow; w <= kWindow; ++w) now += signal[f + w] / (2 * kWindow + 1);
    if (f > kWindow && previous < 0 && now >= 0) {
      crossings.push_back(kFrame * (f - now / (now - previous)));
    }
    previous = now;
  }
  if (crossings.size() < 2) return 0;
  return (crossings.back() - crossings.front()) / (crossings.size() - 1);
}

// The refinement: 16, 32 and 64 cells across. Markers: 1.2223, 1.2007, 1.1910 s against
// 1.1818 s (+3.4%, +1.6%, +0.8%: first order, halving at each refinement). The height field:
// 1.1859, 1.2003, 1.1951 s (+0.3%, +1.6%, +1.1%), not closer at the finer grids but changing
// less at each refinement (0.014 s, then 0.005 s). Its coarse grids are sensitive to where the
// surface sits in its cells: a wave of less than a cell (a = 0.01 m) runs -10%, -2.4%, 0.0% at
// 16, 32, 64 cells (the book's Surface cells hold the atmosphere's pressure at their centres, so
// the liquid in a Surface cell's lower half feels no horizontal pressure gradient).
TEST(LiquidSolver, SloshingPeriodApproachesLinearWaveTheoryUnderRefinement) {
  const Real k = M_PI, depth = 0.5;
  const Real expected = 2 * M_PI / std::sqrt(kG * k * std::tanh(k * depth));
  const int cells[3] = {16, 32, 64};
  Real markers[3], height[3];
  for (int r = 0; r < 3; ++r) {
    markers[r] = sloshing_period(cells[r], SurfaceMethod::markers);
    height[r] = sloshing_period(cells[r], SurfaceMethod::height_field);
    std::printf("sloshing period: theory %.4f s, %d cells: markers %.4f s, height field %.4f s\n",
                expected, cells[r], markers[r], height[r]);
    EXPECT_NEAR(markers[r], expected, 0.05 * expected) << cells[r];
    EXPECT_NEAR(height[r], expected, 0.02 * expected) << cells[r];
  }
  for (int r = 1; r < 3; ++r) {
    EXPECT_LT(std::abs(markers[r] - expected), std::abs(markers[r - 1] - expected)) << cells[r];
  }
  EXPECT_LT(std::abs(markers[2] - markers[1]), std::abs(markers[1] - markers[0]));
  EXPECT_LT(std::abs(height[2] - height[1]), std::abs(height[1] - height[0]));
}

// 16.3's CFL condition is checked after each pressure solve, not only estimated before it: the
// limit (the fastest face plus the speed gravity gives in one substep) misses the pressure's
// acceleration at a dam break's foot, where the first substep reached 0.569 at CFL 0.5 before
// the check; the substep is redone shorter instead.
TEST(LiquidSolver, NoSubstepExceedsTheCflFraction) {
  LiquidDef def;
  def.domain = {Vec3(0, 0, 0), Vec3(1, 0.1, 0.6)};
  def.resolution = Eigen::Vector3i(20, 1, 12);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(0.3, 0.1, 0.5)}, Vec3::Zero()});
  Liquid liquid(def);
  LiquidStepStats first;
  const Real planned = liquid_substep_limit(liquid.model, liquid.inputs, liquid.state);
  const Real taken =
      liquid_substep(liquid.model, liquid.inputs, planned, liquid.state, liquid.ws, first);
  std::printf("first substep: planned %.5f s, taken %.5f s, CFL %.4f, %d retries\n", planned, taken,
              first.cfl, first.cfl_retries);
  EXPECT_GE(first.cfl_retries, 1);
  EXPECT_LT(taken, planned);
  EXPECT_NEAR(liquid.state.time, taken, 1e-15);
  EXPECT_LE(first.cfl, def.cfl * (1 + 1e-9));
  EXPECT_GT(first.cfl, 0.75 * def.cfl);  // shortened to near the fraction, not far below it
  // 1.5 s of the collapse, the front across the tank and up its far wall: every substep within.
  const LiquidStepStats& run = liquid.run_to(1.5);
  std::printf("1.5 s: %d substeps, %d retried, largest CFL %.4f\n", run.substeps, run.cfl_retries,
              run.cfl);
  EXPECT_LE(run.cfl, def.cfl * (1 + 1e-9));
  EXPECT_NEAR(liquid.state.time, 1.5, 1e-12);
}

TEST(LiquidSolver, ThreeSolversReachTheSamePressure) {
  LiquidDef def = dam_break(24);
  Liquid base(def);
  base.run(0.3);  // a moving, splashing state
  std::vector<std::vector<Real>> pressures;
  for (PressureSolver solver :
       {PressureSolver::relaxation, PressureSolver::mic_pcg, PressureSolver::mgpcg}) {
    LiquidDef d = def;
    d.solver = solver;
    d.tolerance = 1e-8;
    d.max_iterations = 20000;
    Liquid liquid(d);
    liquid.state = base.state;
    LiquidStepStats stats;
    liquid_substep(liquid.model, liquid.inputs, 0.005, liquid.state, liquid.ws, stats);
    EXPECT_EQ(stats.unconverged, 0);
    EXPECT_LT(stats.divergence, 1e-8);
    pressures.push_back(liquid.state.pressure);
    std::printf("solver %d: %d iterations\n", static_cast<int>(solver), stats.iterations);
  }
  Real scale = 0;
  for (Real p : pressures[1]) scale = std::max(scale, std::abs(p));
  for (std::size_t c = 0; c < pressures[0].size(); ++c) {
    EXPECT_NEAR(pressures[0][c], pressures[1][c], 1e-6 * scale);
    EXPECT_NEAR(pressures[2][c], pressures[1][c], 1e-6 * scale);
  }
}

// The inflow releases u A t of markers exactly; the cells they fill (the volume the pressure
// solve sees) within 10% with volume_correction, which spreads the markers the falling jet packs
// tighter than the marker density into the pool (0.00182 m^3, -6.7%; without it 0.00169 m^3,
// -13%, once the CFL check redid one substep: the labels' volume moves with how markers pack).
TEST(LiquidSolver, InflowAddsItsVolumeFlux) {
  LiquidDef def = tank(32, 0.25, false);
  InflowDef inflow;
  inflow.box = {Vec3(0, 0, 0.5), Vec3(1.0 / 32, 1, 0.5 + 4.0 / 32)};  // 4 cells of the left wall
  inflow.velocity = Vec3(0.5, 0, 0);
  def.inflows.push_back(inflow);
  def.volume_correction = 0.2;
  Liquid liquid(def);
  const Real v0 = liquid.volume();
  const std::size_t m0 = liquid.state.markers.size();
  liquid.run(1.0);
  const Real added = 0.5 * (4.0 / 32) * (1.0 / 32) * 1.0;  // u A t, A per unit thickness
  const Real cell = std::pow(1.0 / 32, 3);
  const Real released =
      static_cast<Real>(liquid.state.markers.size() - m0) / liquid.model.markers_per_cell * cell;
  const Real measured = liquid.volume() - v0;
  std::printf("inflow: expected %.5f m^3, released %.5f m^3, in the cells %.5f m^3\n", added,
              released, measured);
  EXPECT_NEAR(released, added, 0.5 * cell / liquid.model.markers_per_cell);  // one marker
  EXPECT_NEAR(measured, added, 0.1 * added);
}

TEST(LiquidSolver, SameStartSameBits) {
  auto run = [](Real seconds) {
    Liquid liquid(dam_break(24));
    liquid.run(seconds);
    std::uint64_t h = kFnvOffset;
    hash_liquid_state(liquid.state, h);
    return h;
  };
  EXPECT_EQ(run(0.5), run(0.5));
  EXPECT_NE(run(0.5), run(0.0));  // the hash sees the state move
}

}  // namespace
}  // namespace pbm
