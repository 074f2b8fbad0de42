// The implicit integrator's adaptive step (issue 12, docs/architecture.md "Knobs that converge"):
// solver.adaptive chooses each substep's length from a local error estimate instead of taking the
// frame's substeps at solver.dt.
//
// Estimate. The implicit step is Euler's update with the stiff forces at the step's end
// (deform/implicit_membrane.h, collide/implicit_contact.h): q+ = q + h v+. The trapezoid rule,
// second order, would take q + h (v + v+) / 2; their difference h |v+ - v| / 2 is the local
// position error of the first-order step, and it counts what the collision stages did to v in
// the step (an impact's stop is where a large step errs most). A step is accepted when the
// largest entry over every body's velocity coordinates stays within solver.adaptive_tolerance
// [m, or rad for rotations], and rejected (the state restored, the step halved) otherwise.
//
// Lengths. A substep is the frame's substep h / 2^level, level 0..kAdaptiveLevels, so that the
// steps tile the frame exactly and the implicit membrane's factor (one per length) is reused
// while the level stays. After two calm steps in a row (an error under 1/8: the step twice as
// long would stay within about 1/2, the local error growing as h^2) the level goes back one,
// where the step's start is aligned to the longer length. At the finest level a step is taken
// whatever its estimate, and the stability guard judges the frame as ever (docs/architecture.md,
// "Stability guard"). The level and the count of calm steps live in State: a frame stepped after
// a seek takes the same substeps.
#pragma once

#include "sim/state.h"
#include "sim/workspace.h"
#include "sim/world.h"

namespace pbm {

inline constexpr int kAdaptiveLevels = 10;  // the shortest substep is h / 1024

// Whether the scene takes adaptive steps (solver.adaptive with the implicit integrator).
bool adaptive_steps(const Model& model);

struct AdaptiveResult {
  bool ok = true;
  int accepted = 0, rejected = 0;
};

// Advances the state over one frame substep of length h (ending the frame when ends_frame) in
// accepted adaptive substeps. Not ok when a substep at the finest level failed (a NaN): the
// caller's guard retries the frame.
AdaptiveResult advance_adaptive(const World& world, const Inputs& inputs, State& state, Real h,
                                bool ends_frame, Workspace& ws, int& evaluations);

}  // namespace pbm
