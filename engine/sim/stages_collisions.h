// Collisions between bodies and of a body with itself (collide/body_collisions.h, sec. 5.2.2):
// the pairs of bodies after the integrator, before the obstacles (so no node is left inside an
// obstacle by another body); each local body with itself last, from the node positions recorded
// at the substep's start. Rows of the subsystem table (sim/subsystems.cpp).
#pragma once

#include "sim/subsystem.h"

namespace pbm::stages {

bool body_collisions_present(const Model& model);
bool self_collision_present(const Model& model);
void size_body_collisions(const Model& model, Workspace& ws);
void record_self_collision_start(const SubstepContext& c);     // step_start
void resolve_pairs_of_bodies(const SubstepContext& c);         // body_collisions
void resolve_bodies_with_themselves(const SubstepContext& c);  // self_collisions

}  // namespace pbm::stages
