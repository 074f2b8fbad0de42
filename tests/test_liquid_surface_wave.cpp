// The travelling wave a surface-pressure history forces (16.6.2, (16.17)-(16.19)): forced at the
// wave's own phase speed, the wave grows to the amplitude asked for, and once the forcing stops it
// runs on at the speed of linear wave theory, c = omega / k with omega^2 = g k tanh(k D).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "liquid/liquid_step.h"
#include "liquid_test_support.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81;
constexpr Real kLength = 6, kDepth = 0.25, kWavelength = 1, kAmplitude = 0.02;

Real omega() {
  const Real k = 2 * M_PI / kWavelength;
  return std::sqrt(kG * k * std::tanh(k * kDepth));
}

// Two periods of forcing.
Real duration() {
  return 2 * (2 * M_PI / omega());
}

// A wave's amplitude and phase.
struct Fit {
  Real amplitude = 0, phase = 0;
};

// The tank of kLength m at `cells` per metre, kDepth deep, forced by the wave of kWavelength.
LiquidDef wave_tank(SurfaceMethod surface, int cells) {
  LiquidDef def;
  const Real h = 1.0 / cells;
  def.domain = {Vec3(0, 0, 0), Vec3(kLength, h, 0.5)};
  def.resolution = Eigen::Vector3i(cells * static_cast<int>(kLength), 1, cells / 2);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(kLength, h, kDepth)}, Vec3::Zero()});
  def.surface = surface;
  def.markers_per_axis = 3;
  // depth 0: the liquid's at the start, kDepth.
  def.surface_waves.push_back({.amplitude = kAmplitude,
                               .wavelength = kWavelength,
                               .direction = Vec3::UnitX(),
                               .depth = 0,
                               .start = 0,
                               .duration = duration()});
  return def;
}

struct WaveTank : test::LoneLiquid {
  int cells_per_metre;
  int columns;

  WaveTank(SurfaceMethod surface, int cells)
      : LoneLiquid(wave_tank(surface, cells)),
        cells_per_metre(cells),
        columns(cells * static_cast<int>(kLength)) {}

  void run_to(Real t_end) { LoneLiquid::run_to(t_end, 60); }

  // The surface's height above the mean over each column [m].
  std::vector<Real> elevation() const {
    std::vector<Real> eta(static_cast<std::size_t>(columns), -kDepth);
    if (model.def.surface == SurfaceMethod::height_field) {
      for (int i = 0; i < columns; ++i) eta[i] = state.height[i] - kDepth;
      return eta;
    }
    // The highest marker of each column, plus the half spacing of liquid it stands for: where
    // the surface is (a count of markers would also read their bunching along the wave).
    const Real half_spacing = 0.5 * model.grid.h.z() / model.def.markers_per_axis;
    std::vector<Real> top(static_cast<std::size_t>(columns), -1e300);
    for (const Vec3& x : state.markers) {
      const int i = std::clamp(static_cast<int>(x.x() * cells_per_metre), 0, columns - 1);
      top[static_cast<std::size_t>(i)] = std::max(top[static_cast<std::size_t>(i)], x.z());
    }
    for (int i = 0; i < columns; ++i) eta[i] = top[i] + half_spacing - kDepth;
    return eta;
  }
  Fit fit() const;
};

// The wave's amplitude and phase over the middle two wavelengths, which what the end walls
// disturb (at the group velocity, about 0.76 m/s) does not reach by the time measured: the
// least-squares fit of eta = alpha cos(k x) + beta sin(k x).
Fit fit_wave(const std::vector<Real>& eta, int cells_per_metre) {
  const Real k = 2 * M_PI / kWavelength;
  Real cc = 0, cs = 0;
  int n = 0;
  for (std::size_t i = 0; i < eta.size(); ++i) {
    const Real x = (static_cast<Real>(i) + 0.5) / cells_per_metre;
    if (x < 2 || x > 4) continue;
    cc += eta[i] * std::cos(k * x);
    cs += eta[i] * std::sin(k * x);
    ++n;
  }
  // Over whole wavelengths cos and sin are orthogonal with mean square 1/2.
  const Real alpha = 2 * cc / n, beta = 2 * cs / n;
  return {std::hypot(alpha, beta), std::atan2(beta, alpha)};
}

struct WaveRun {
  Real amplitude = 0;  // at the forcing's end [m]
  Real later = 0;      // kLater after it [m]
  Real speed = 0;      // the crest's, over that time [m/s]
};
constexpr Real kLater = 0.3;

// The wave's amplitude when the forcing ends and its crest's speed after (the phase's least-
// squares slope over seven samples, which averages the markers' flicker).
WaveRun forced_wave(SurfaceMethod surface, int cells_per_metre) {
  WaveTank tank(surface, cells_per_metre);
  const Real k = 2 * M_PI / kWavelength;
  tank.run_to(duration());
  const Fit start = tank.fit();
  WaveRun run{.amplitude = start.amplitude};
  Real st = 0, sp = 0, stt = 0, stp = 0, previous = start.phase, unwrapped = 0;
  constexpr int kSamples = 6;
  for (int q = 0; q <= kSamples; ++q) {
    if (q > 0) tank.run_to(duration() + q * kLater / kSamples);
    const Fit now = tank.fit();
    // eta ~ cos(k x - phi): phi grows by omega t; each step moves it less than pi.
    Real step = now.phase - previous;
    while (step < -M_PI) step += 2 * M_PI;
    while (step > M_PI) step -= 2 * M_PI;
    unwrapped += q > 0 ? step : 0;
    previous = now.phase;
    const Real t = q * kLater / kSamples;
    st += t, sp += unwrapped, stt += t * t, stp += t * unwrapped;
    run.later = now.amplitude;
  }
  const int n = kSamples + 1;
  run.speed = (n * stp - st * sp) / (n * stt - st * st) / k;
  return run;
}

Fit WaveTank::fit() const {
  return fit_wave(elevation(), cells_per_metre);
}

void print(const char* name, int cells, const WaveRun& r) {
  std::printf(
      "%s, %d cells a metre: amplitude %.4f m at the forcing's end (asked %.4f), %.4f m "
      "%.2f s later; speed %.4f m/s (theory %.4f)\n",
      name, cells, r.amplitude, kAmplitude, r.later, kLater, r.speed,
      omega() * kWavelength / (2 * M_PI));
}

// Linear theory's growth, less the standing part a start from rest leaves (1 / (2 omega T) of it,
// 4%), the grid's damping and its dispersion; the height field converges to it.
TEST(LiquidSurfaceWave, HeightFieldWaveGrowsToItsAmplitudeAndRunsAtThePhaseSpeed) {
  const Real c = omega() * kWavelength / (2 * M_PI);
  const WaveRun coarse = forced_wave(SurfaceMethod::height_field, 32);
  const WaveRun fine = forced_wave(SurfaceMethod::height_field, 64);
  print("height field", 32, coarse);
  print("height field", 64, fine);
  EXPECT_NEAR(fine.amplitude, kAmplitude, 0.05 * kAmplitude);
  EXPECT_NEAR(fine.later, fine.amplitude, 0.05 * kAmplitude);  // a free wave keeps its height
  EXPECT_NEAR(fine.speed, c, 0.02 * c);
  EXPECT_LT(std::abs(fine.amplitude - kAmplitude), std::abs(coarse.amplitude - kAmplitude));
  EXPECT_LT(std::abs(fine.speed - c), std::abs(coarse.speed - c));
}

TEST(LiquidSurfaceWave, MarkerWaveGrowsToItsAmplitudeAndRunsAtThePhaseSpeed) {
  const Real c = omega() * kWavelength / (2 * M_PI);
  const WaveRun run = forced_wave(SurfaceMethod::markers, 64);
  print("markers", 64, run);
  EXPECT_NEAR(run.amplitude, kAmplitude, 0.15 * kAmplitude);
  EXPECT_NEAR(run.later, run.amplitude, 0.1 * kAmplitude);
  EXPECT_NEAR(run.speed, c, 0.05 * c);
}

TEST(LiquidSurfaceWave, ForcingFollowsTheBookAndStopsAfterItsDuration) {
  WaveTank tank(SurfaceMethod::height_field, 32);
  const SurfaceWaveModel& wave = tank.model.surface_waves.at(0);
  // C = pi / L for a wavelength 2L (16.19); omega from the dispersion at the liquid's depth.
  EXPECT_NEAR(wave.wave_vector.x(), M_PI / (kWavelength / 2), 1e-12);
  EXPECT_NEAR(wave.omega, omega(), 1e-12);
  EXPECT_NEAR(wave.pressure, 2 * kG * kAmplitude / (omega() * duration()), 1e-12);
  const Vec3 x(0.3, 0, kDepth);
  EXPECT_NEAR(surface_wave_pressure(tank.model, x, 0.1),
              wave.pressure * std::cos(wave.wave_vector.x() * 0.3 - wave.omega * 0.1), 1e-12);
  EXPECT_EQ(surface_wave_pressure(tank.model, x, duration()), 0.0);
  // Untouched still water outside the forcing's time stays still.
  LiquidDef def = tank.model.def;
  def.surface_waves[0].start = 100;
  WaveTank later(SurfaceMethod::height_field, 32);
  later.model = build_liquid_model(def, later.inputs.gravity, "test.json", 0);
  later.run_to(0.5);
  for (const Real eta : later.elevation()) EXPECT_LT(std::abs(eta), 1e-9);
}

TEST(LiquidSurfaceWave, DirectionAlongGravityIsRefused) {
  LiquidDef def;
  def.domain = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  def.resolution = Eigen::Vector3i(8, 8, 8);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(1, 1, 0.5)}, Vec3::Zero()});
  def.surface_waves.push_back({.direction = Vec3::UnitZ()});
  try {
    build_liquid_model(def, Vec3(0, 0, -kG), "w.json", 0);
    FAIL() << "accepted a wave travelling along gravity";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("liquids[0].surface_waves[0].direction"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace pbm
