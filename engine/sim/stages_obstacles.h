// Rigid obstacles' part of the step (collide/rigid_contact.h, sec. 5.2.1): their push and
// friction among the rates, the projection out of them after the integrator, their contact
// energy and the bodies' distance to them, and the energy moving obstacles may give. Rows of the
// subsystem table (sim/subsystems.cpp).
#pragma once

#include <span>

#include "sim/subsystem.h"

namespace pbm::stages {

bool obstacles_present(const Model& model);
void obstacle_forces(const RateContext& c);         // contact_forces: (5.11), (5.12)
void obstacle_collisions(const SubstepContext& c);  // obstacle_collisions: projection, split
// The same for the bodies marked in `only` (all when it is empty): the constraint projection's
// second pass, so a substep still ends with every node outside every obstacle.
void resolve_obstacle_penetrations(const SubstepContext& c, std::span<const char> only);
void measure_obstacles(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                       FrameStats& stats);
Real obstacle_energy_allowance(const Model& model, const Inputs& inputs, const State& state,
                               Real t_end, Workspace& ws);
void add_obstacle_drawables(const Model& model, const Inputs& inputs, const State& state,
                            Workspace& ws, draw::Snapshot& snap);

}  // namespace pbm::stages
