#include "sim/stages_constraints.h"

#include <algorithm>

#include "constrain/constraint_forces.h"
#include "constrain/hinge_spring.h"
#include "constrain/point_constraint.h"
#include "sim/stages_collisions.h"
#include "sim/stages_obstacles.h"

namespace pbm::stages {

namespace {

constexpr float kConstraintRedViolation = 0.01f;  // [m]: |C| drawn fully red
constexpr float kConstraintEndSize = 5;           // [pixels], smaller than a spring's ends

// Green while held, turning red as |C| reaches kConstraintRedViolation.
draw::Vec3f constraint_color(float violation) {
  const float t = std::clamp(violation / kConstraintRedViolation, 0.0f, 1.0f);
  return {0.25f + 0.7f * t, 0.9f - 0.7f * t, 0.35f - 0.15f * t};
}

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
  if (constraint_projection_needed(model)) {
    ws.constraint_projection.emplace();
    init_constraint_projection(system_of(model), *ws.constraint_projection);
  }
}

bool constraint_projection_needed(const Model& model) {
  return model.solver.constraint_projection && !model.constraints.points.empty() &&
         (obstacles_present(model) || body_collisions_present(model) ||
          self_collision_present(model));
}

void record_constraints(const SubstepContext& c) {
  // The state the integrator left, before any collision stage moves a body on its own.
  record_constraints_before_collisions(system_of(c.model), c.state.q, c.state.v, c.ws.bodies,
                                       *c.ws.constraint_projection);
}

void project_constraints(const SubstepContext& c) {
  // The projection moves the constrained parts by what the collisions opened (1e-4 m at a
  // landing), which may put a node back inside an obstacle, and no substep ends with one there
  // (collide/rigid_contact.h). So the two alternate, the obstacles last: each round's opening is
  // a fraction of the last one's. Measured on the snowman's landings, largest |C| from 1.5 s on:
  // 1 round 1.9 mm, 2 rounds 0.41 mm, 4 rounds 0.043 mm, 8 rounds the same.
  constexpr int kRounds = 4;
  ConstraintProjectionWorkspace& pw = *c.ws.constraint_projection;
  for (int round = 0; round < kRounds; ++round) {
    const ConstraintProjection done = project_constraints_after_collisions(
        system_of(c.model), c.state.q, c.state.v, c.ws.bodies, *c.ws.constraints, pw, c.dt);
    if (!done.ran || !obstacles_present(c.model)) return;
    resolve_obstacle_penetrations(c, pw.constrained);
  }
}

void constraint_rates(const RateContext& c) {
  // (7.3), (7.4): every body's unconstrained rates are known; the constraint forces couple them.
  add_constraint_rates(system_of(c.model), c.q, c.v, c.ws.bodies, *c.ws.constraints, c.v_dot);
}

void measure_constraints(const Model& model, const Inputs& /*inputs*/, const State& state,
                         Workspace& ws, FrameStats& stats) {
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

void add_constraint_drawables(const Model& model, const Inputs& inputs, const State& state,
                              Workspace& ws, draw::Snapshot& snap) {
  (void)inputs;
  // Where each end of a point constraint is now (the bodies' kinematics are current): a node, a
  // point fixed in the body frame, or a world anchor. Drawn over the parts they join.
  const ConstrainedSystem system = system_of(model);
  draw::Lines lines{
      .end_points = true, .end_point_size = kConstraintEndSize, .layer = draw::Layer::overlay};
  for (const PointConstraintModel& c : model.constraints.points) {
    const Vec3 a = constraint_end_position(c.ends[0], ws.bodies, system, state.q);
    const Vec3 b = constraint_end_position(c.ends[1], ws.bodies, system, state.q);
    lines.points.push_back(a.cast<float>());
    lines.points.push_back(b.cast<float>());
    lines.colors.push_back(constraint_color(static_cast<float>((a - b).norm())));
  }
  if (!lines.points.empty()) snap.lines.push_back(std::move(lines));
}

}  // namespace pbm::stages
