// Constraints' part of the step (constrain/, ch. 7): the constraint forces (7.33) and the hinges'
// springs among the rates, after every body's unconstrained rates are known; the violations and
// the springs' energy; the kinetic energy Baumgarte's feedback may give assembling parts. Rows of
// the subsystem table (sim/subsystems.cpp).
#pragma once

#include "sim/subsystem.h"

namespace pbm::stages {

bool constraints_present(const Model& model);
void size_constraints(const Model& model, Workspace& ws);
void constraint_rates(const RateContext& c);  // constraints: (7.3), (7.4)
// Whether collisions can open the constraints (a collision stage is present) and the solver
// restores them (solver.constraint_projection).
bool constraint_projection_needed(const Model& model);
void record_constraints(const SubstepContext& c);   // renormalize, after the bodies'
void project_constraints(const SubstepContext& c);  // constraint_projection
void measure_constraints(const Model& model, const Inputs& inputs, const State& state,
                         Workspace& ws, FrameStats& stats);
Real constraint_allowance(const Model& model, const Inputs& inputs, const State& state, Real t_end,
                          Workspace& ws);
void add_constraint_drawables(const Model& model, const Inputs& inputs, const State& state,
                              Workspace& ws, draw::Snapshot& snap);

}  // namespace pbm::stages
