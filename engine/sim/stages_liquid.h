// Liquids' part of the step (liquid/, ch. 16): each liquid advances on its own CFL clock at the
// liquid stage, after the bodies' corrections; its volume, energy and cost are measured, a NaN
// in its grid fails the frame, and its markers, height field and solid cells are drawn. Rows of
// the subsystem table (sim/subsystems.cpp).
#pragma once

#include "sim/subsystem.h"

namespace pbm::stages {

bool liquids_present(const Model& model);
void size_liquids(const Model& model, Workspace& ws);
// A liquid advances to the substep's end when the frame ends there, or when one more substep of
// the bodies would take it past its own next substep's length (LiquidState::next_step): shorter
// substeps of the bodies do not cut its substeps shorter, and a frame's end finds it there.
void advance_liquids(const SubstepContext& c);  // liquid
void measure_liquids(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                     FrameStats& stats);
// Bodies in a liquid (sim/liquid_body_loads.h): the probe built from the liquids' state at
// each substep's start, their buoyancy and drag added to the bodies' nodal forces, and the work
// those forces did (State::liquid_work) after each substep.
bool liquid_bodies_present(const Model& model);
void size_liquid_bodies(const Model& model, Workspace& ws);
void liquid_probe_start(const SubstepContext& c);  // step_start
void liquid_body_forces(const RateContext& c);     // contact_forces
void liquid_body_work(const SubstepContext& c);    // coupling
// Two-way liquids start without the markers their scene puts inside bodies, obstacles and
// figures' segments (the solid occupies that space); ws.drive as measure_state leaves it at the
// state's time.
void remove_covered_liquid(const Model& model, State& state, Workspace& ws);
std::string describe_liquid_failure(const Model& model, const State& state);
void add_liquid_drawables(const Model& model, const Inputs& inputs, const State& state,
                          Workspace& ws, draw::Snapshot& snap);

}  // namespace pbm::stages
