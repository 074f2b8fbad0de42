// PIC/FLIP (advection flip, liquid_def.h): the markers carry the liquid's velocity between
// substeps, and the grid only adds what acts on it in one (gravity, viscosity, the pressure that
// keeps it divergence-free). Zhu & Bridson 2005, "Animating sand as a fluid": the markers'
// velocities spread to the faces by the same trilinear weights the grid is read with, and back as
// a blend of the grid's new velocity (PIC) and the marker's own plus the grid's change (FLIP).
#pragma once

#include "liquid/liquid_state.h"
#include "liquid/liquid_workspace.h"

namespace pbm {

// Each face any marker weighs on takes the weighted mean of their velocities' component along
// its axis; faces no marker reaches keep theirs (the extrapolation of the substep sets those
// beside the liquid).
void markers_to_grid(const LiquidModel& model, const std::vector<Vec3>& markers,
                     const std::vector<Vec3>& velocities, LiquidWorkspace& ws, MacField& field);

// Each marker's velocity from the substep's start (`before`, what markers_to_grid gave with its
// boundaries) to its end (`after`): flip_ratio (v + after - before) + (1 - flip_ratio) after, all
// read at the marker.
void grid_to_markers(const LiquidModel& model, const MacField& before, const MacField& after,
                     const std::vector<Vec3>& markers, std::vector<Vec3>& velocities);

}  // namespace pbm
