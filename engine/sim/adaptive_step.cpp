#include "sim/adaptive_step.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pbm {

namespace {

// Calm: a step whose estimate is this share of the tolerance or less; two in a row lengthen
// the step (see the header).
constexpr Real kCalmError = 0.125;
constexpr int kCalmSteps = 2;

// h |v+ - v| / 2 over every velocity coordinate, divided by the tolerance.
Real step_error(const VecX& v0, const VecX& v1, Real h, Real tolerance) {
  const Real largest = v0.size() ? (v1 - v0).cwiseAbs().maxCoeff() : 0.0;
  return 0.5 * h * largest / tolerance;
}

}  // namespace

bool adaptive_steps(const Model& model) {
  return model.solver.adaptive && model.solver.integrator == IntegratorKind::implicit;
}

AdaptiveResult advance_adaptive(const World& world, const Inputs& inputs, State& state, Real h,
                                bool ends_frame, Workspace& ws, int& evaluations) {
  const Model& model = *world.model;
  AdaptiveResult result;
  // Positions within the frame substep in ticks of the shortest step.
  constexpr long kTicks = 1L << kAdaptiveLevels;
  long tick = 0;
  while (tick < kTicks) {
    int level = std::clamp(state.adaptive_level, 0, kAdaptiveLevels);
    auto length = [](int l) { return 1L << (kAdaptiveLevels - l); };
    // A step starts on a multiple of its own length and ends within the frame substep.
    while (level < kAdaptiveLevels && (tick % length(level) != 0 || tick + length(level) > kTicks))
      ++level;
    const Real step = h * static_cast<Real>(length(level)) / static_cast<Real>(kTicks);
    ws.adaptive_save = state;
    ws.substep_ends_frame = ends_frame && tick + length(level) == kTicks;
    const bool ok = advance_substep(world, inputs, state, step, ws, evaluations);
    const Real error =
        ok ? step_error(ws.adaptive_save.v, state.v, step, model.solver.adaptive_tolerance)
           : std::numeric_limits<Real>::infinity();
    if (!(error <= 1) && level < kAdaptiveLevels) {
      state = ws.adaptive_save;
      state.adaptive_level = level + 1;
      state.adaptive_calm = 0;
      ++result.rejected;
      continue;
    }
    if (!ok) {
      result.ok = false;
      return result;
    }
    tick += length(level);
    ++result.accepted;
    // state.adaptive_level stays the length asked for: a step shortened only to stay aligned
    // (or within the frame substep) does not lower it.
    if (error <= kCalmError) {
      if (++state.adaptive_calm >= kCalmSteps && state.adaptive_level > 0) {
        --state.adaptive_level;
        state.adaptive_calm = 0;
      }
    } else {
      state.adaptive_calm = 0;
    }
  }
  return result;
}

}  // namespace pbm
