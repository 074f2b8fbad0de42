#include "sim/stages_collisions.h"

namespace pbm::stages {

namespace {

BodySet bodies_of(const SubstepContext& c) {
  return {c.model.bodies, c.ws.bodies, c.state.q, c.state.v, c.state.time};
}

}  // namespace

bool body_collisions_present(const Model& model) {
  return model.body_collisions.options.enabled && model.bodies.size() >= 2;
}

bool self_collision_present(const Model& model) {
  const BodyCollisionOptions& options = model.body_collisions.options;
  if (!options.enabled || !options.self_collision) return false;
  for (const BodyModel& body : model.bodies) {
    if (body.has_local) return true;
  }
  return false;
}

void size_body_collisions(const Model& model, Workspace& ws) {
  (void)model;  // sized for the bodies on first use (collide/body_collisions.cpp)
  if (!ws.body_collisions) ws.body_collisions.emplace();
}

void record_self_collision_start(const SubstepContext& c) {
  // Self-collision follows each node from where it is now (collide/self_collision.h).
  record_step_start(c.model.bodies, c.state.q, c.state.v, c.state.time, c.dt,
                    c.model.body_collisions.options, c.ws.body_collisions->self);
}

void resolve_pairs_of_bodies(const SubstepContext& c) {
  c.ws.body_collision_stats =
      resolve_body_collisions(c.model.body_collisions, bodies_of(c), c.dt, *c.ws.body_collisions);
  c.ws.contacts += c.ws.body_collision_stats.contacts;  // the end of 5.2.2's step reduction
}

void resolve_bodies_with_themselves(const SubstepContext& c) {
  resolve_body_self_collisions(c.model.body_collisions.options, bodies_of(c), c.dt,
                               *c.ws.body_collisions, c.ws.body_collision_stats);
}

}  // namespace pbm::stages
