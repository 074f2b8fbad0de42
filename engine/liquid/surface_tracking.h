// Step 8 of 16.5: the liquid's position moved by its new velocities. Markers (16.3.1) are
// carried with the velocity interpolated by area (volume) weighting (fig. 16.3), released at
// inflows and removed at outflows; the height field (16.3.3) follows (16.12).
#pragma once

#include "liquid/liquid_state.h"
#include "liquid/liquid_workspace.h"
#include "liquid/moving_solids.h"

namespace pbm {

// Moves every marker through the field by the midpoint rule; a marker that would enter a Solid
// cell (the scene's, or one a moving solid covers) or leave the domain stays where it was; one
// that enters an Outflow cell is removed, with its velocity when `velocities` holds one per
// marker (advection flip; empty otherwise). Returns how many were removed.
int advect_markers(const LiquidModel& model, const MacField& field, Real dt,
                   std::vector<Vec3>& markers, std::vector<Vec3>& velocities,
                   const MovingSolids* moving = nullptr);

// Each inflow's markers for dt at its rate (or, at rate 0, at the marker density times its
// volume flux), placed by a low-discrepancy sequence over its cells. A rate given scales with the
// inflow's velocity now (inflow_velocity, one per inflow) over the scene's along its main axis;
// an inflow sucking liquid out releases none. Never grows the markers past their capacity;
// returns how many it could not release.
int release_markers(const LiquidModel& model, const std::vector<Vec3>& inflow_velocity, Real dt,
                    LiquidState& state);

// (16.12): h += dt (w + (h_{i-1} - h_{i+1}) / (4 dx) (u_{i+1/2} + u_{i-1/2}) + the same along y),
// with the velocities of the cell the surface crosses, held inside the domain.
void advance_height_field(const LiquidModel& model, const MacField& field, Real dt,
                          LiquidState& state, LiquidWorkspace& ws);

}  // namespace pbm
