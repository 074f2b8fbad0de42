#include "sim/stages_constraints.h"

#include "constrain/constraint_forces.h"
#include "constrain/hinge_spring.h"

namespace pbm::stages {

namespace {

ConstrainedSystem system_of(const Model& model) {
  return {model.constraints, model.bodies};
}

}  // namespace

bool constraints_present(const Model& model) {
  return !model.constraints.empty();
}

void size_constraints(const Model& model, Workspace& ws) {
  ws.constraints.emplace();
  init_constraint_workspace(system_of(model), *ws.constraints);
}

void constraint_rates(const RateContext& c) {
  // (7.3), (7.4): every body's unconstrained rates are known; the constraint forces couple them.
  add_constraint_rates(system_of(c.model), c.q, c.v, c.ws.bodies, *c.ws.constraints, c.v_dot);
}

void measure_constraints(const Model& model, const State& state, Workspace& ws, FrameStats& stats) {
  const ConstrainedSystem system = system_of(model);
  stats.hinge_energy = hinge_spring_energy(system, ws.bodies);
  stats.constraint_violation =
      measure_constraint_violations(system, state.q, ws.bodies, stats.constraint_violations);
}

Real constraint_allowance(const Model& model, const Inputs& inputs, const State& state, Real t_end,
                          Workspace& ws) {
  (void)inputs;
  (void)t_end;
  // Assembling parts (7.16) gain the kinetic energy Baumgarte's feedback gives them.
  return constraint_energy_allowance(system_of(model), state.q, state.v, ws.bodies);
}

}  // namespace pbm::stages
