// State: minimal restartable plain data (docs/architecture.md, "Determinism"). Each body owns the
// slices at BodyModel::q_offset / v_offset, its blocks named in deform/body_layout.h.
#pragma once

#include <cstdint>

#include "core/quaternion.h"
#include "core/types.h"
#include "liquid/liquid_state.h"
#include "sim/model.h"

namespace pbm {

// Everything that changes a later frame, and nothing else: restoring a State (a seek, the
// timeline cache) and stepping on gives bit-identical results with any workspace.
struct State {
  Real time = 0;  // [s]
  VecX q;         // generalized coordinates of every body, n_q
  VecX v;         // generalized velocities of every body, n_v
  // rk45's step size to try first in the next substep [s] (0: the whole substep): the adaptive
  // integrator's memory of the last accepted step.
  Real rk45_step = 0;
  // The adaptive implicit step (sim/adaptive_step.h): the level of the next substep to try (its
  // length is the frame's substep / 2^level) and how many calm steps in a row it has taken.
  int adaptive_level = 0;
  int adaptive_calm = 0;
  // Nodes touching an obstacle or another body after the last substep: with
  // solver.contact_step_reduction it decides whether the next substep is divided (end of 5.2.2).
  int contact_nodes = 0;
  // The run-level stability guard (docs/architecture.md, "Stability guard"), kept here because
  // it decides whether a later frame is accepted. energy_surplus: the largest growth of the
  // total energy over the frames ending now beyond the work the inputs did, max(0, surplus +
  // frame's growth) [J]. energy_scale: the most kinetic + elastic energy any frame started with
  // [J], what the surplus is judged against.
  Real energy_surplus = 0;
  Real energy_scale = 0;
  // Work the liquids' forces did on the bodies since the frame attempt's start [J]
  // (sim/liquid_body_loads.h): the run-level guard counts it as work of an input. In the State
  // so a step the adaptive integrator rejects takes its share back with it.
  Real liquid_work = 0;
  // Per body: 1 while a body of level "auto" runs without its displacements (q_d = d-dot = 0;
  // sim/level_of_detail.h), decided at a frame's start; 0 for every other body.
  std::vector<std::uint8_t> dormant;
  // Per figure: how many of its impulse events (CompiledFigure::impulses, in time order) have
  // been applied. A count rather than a test of the event's time against the substep's interval:
  // a frame's end is snapped to its exact time, so consecutive intervals may overlap by a
  // rounding error, and an event there would be applied twice.
  std::vector<int> impulses_applied;
  // Per liquid: its grid's velocities, pressure and surface (liquid/liquid_state.h), at its own
  // time (LiquidState::time, which trails `time` between its CFL substeps).
  std::vector<LiquidState> liquids;
};

State initial_state(const Model& model);

// FNV-1a over the bytes of every field: equal hashes <=> bit-identical states.
std::uint64_t hash_state(const State& state);

}  // namespace pbm
