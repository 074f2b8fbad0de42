// One liquid on its own, as the World holds it (liquid/liquid_step.h): its model, state,
// workspace and inputs under gravity -9.81 z, advanced in frames as the World advances it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "liquid/cell_labels.h"
#include "liquid/liquid_step.h"

namespace pbm::test {

struct LoneLiquid {
  LiquidModel model;
  LiquidState state;
  LiquidWorkspace ws;
  LiquidInputs inputs;
  LiquidStepStats stats;  // every run's, added up

  explicit LoneLiquid(const LiquidDef& def) {
    inputs.gravity = Vec3(0, 0, -9.81);
    model = build_liquid_model(def, inputs.gravity, "test.json", 0);
    state = initial_liquid_state(model, inputs.gravity);
    size_liquid_workspace(model, ws);
  }

  // Advances `seconds` in frames of 1/fps, each of which must reach its end; the frames' ends
  // counted from the run's start, as the World snaps its targets to frame times (a remainder
  // advance_liquid leaves as negligible must not become a frame of its own). Returns `stats`.
  const LiquidStepStats& run(Real seconds, Real fps = 30) {
    const Real t0 = state.time;
    const int frames = static_cast<int>(std::ceil(seconds * fps - 1e-9));
    for (int k = 1; k <= frames; ++k) {
      EXPECT_TRUE(advance_liquid(model, inputs, t0 + std::min(seconds, k / fps), state, ws, stats))
          << "frame " << k << " of the run from " << t0 << " s";
    }
    return stats;
  }
  const LiquidStepStats& run_to(Real t, Real fps = 30) { return run(t - state.time, fps); }

  // Labels the cells (liquid/cell_labels.h) and sums the liquid in them [m^3].
  Real volume() {
    label_cells(model, state, ws.flags, ws.fill, ws.count);
    return liquid_volume(model, ws.flags, ws.fill);
  }
};

// The mean height of a liquid's top over its columns along z [m]: each column's highest liquid
// cell's floor plus its fill (a Full one's whole height), from the labels in ws.
inline Real mean_surface_height(const LiquidModel& m, const LiquidWorkspace& w) {
  const MacGrid& g = m.grid;
  Real sum = 0;
  for (int j = 1; j <= g.n.y(); ++j) {
    for (int i = 1; i <= g.n.x(); ++i) {
      Real top = g.origin.z();
      for (int k = g.n.z(); k >= 1; --k) {
        const auto c = static_cast<std::size_t>(g.index(i, j, k));
        if (!is_liquid(w.flags[c])) continue;
        top = g.origin.z() + (k - 1 + w.fill[c]) * g.h.z();
        break;
      }
      sum += top;
    }
  }
  return sum / (g.n.x() * g.n.y());
}

}  // namespace pbm::test
