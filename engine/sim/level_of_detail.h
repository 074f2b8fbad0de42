// Levels of detail chosen automatically (issue 12; docs/architecture.md, "Levels of detail"): a
// body of level "auto" has the state of a local body, but while it is far from every obstacle and
// every other body and no spring pulls it, its displacements are off: q_d and d-dot are held at
// zero (State::dormant) and it runs as a global body (the membrane, the local solve and the
// implicit solve skipped, deform/body_dynamics.h), whose explicit limit is the global block's
// alone, so the frame may take longer substeps (frame_substep).
//
// Decided once per frame, at its start, so every substep of a frame (and every retry of it) runs
// one set of levels:
//   - wake (displacements on) when, looking two frames ahead at the body's current speed, its
//     spin, gravity and the obstacles' speed, a node could reach an obstacle, or its bounding
//     sphere another body's; when a spring acts on it in that time (the mouse drag); or when
//     something dented it anyway (q_d or d-dot not zero). Switching on keeps the state as it is:
//     q_d = 0 is a local body without dents, so position and energy are continuous exactly.
//   - sleep (displacements off) when none of that holds and its dents have died down: every
//     |d_i| and |d-dot_i| T under kSleepDisplacement of its radius. Switching off zeroes them; the
//     energy they held and the largest |d_i| are the jump, reported in the frame's stats.
#pragma once

#include "sim/frame_stats.h"
#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/workspace.h"

namespace pbm {

// Largest |d_i| (and |d-dot_i| times the frame) a body may have to go dormant, relative to its
// bounding radius: under a pixel on a body drawn under 1000 pixels across. Not zero: at rest a
// membrane keeps a static dent whose force the global block balances (2e-4 of the radius after
// two balls' head-on collision), which would keep the body awake forever.
inline constexpr Real kSleepDisplacement = 1e-3;

bool auto_levels_present(const Model& model);

// At a frame's start (ws.drive at state.time, the bodies' kinematics of `state` in ws): wakes and
// puts to sleep the "auto" bodies (see above), changing state.dormant and, for a body put to
// sleep, its q_d and d-dot; copies the flags into ws.bodies and adds the switches to stats.
// Returns whether a body went to sleep (the state changed and must be measured again).
bool choose_levels(const Model& model, State& state, Workspace& ws, LevelStats& stats);

// The substep of a frame with the levels of `state`: Model::substep without "auto" bodies, else
// shortened below the limit of each body at its current level (the global block's for a
// dormant one).
Real frame_substep(const Model& model, const State& state);

}  // namespace pbm
