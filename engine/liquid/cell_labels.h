// Step 3 of the algorithm of 16.5: what each cell holds this substep, from the markers (16.3.1:
// no marker Empty, a marker next to an Empty cell Surface, else Full), from the height field
// (16.3.3: crossed by it Surface, above it Empty, below it Full) or from the chains (16.3.2,
// region growing: liquid/surface_chains.h). Solid, Inflow and Outflow
// cells are the scene's. Also how much of each Surface cell the liquid fills, for the
// ghost-fluid pressure boundary and the volume.
#pragma once

#include <vector>

#include "liquid/liquid_state.h"

namespace pbm {

struct MovingSolids;

// Cells moving solids cover (liquid/moving_solids.h) are Solid, whatever markers they hold.
void label_cells(const LiquidModel& model, const LiquidState& state, std::vector<CellFlag>& flags,
                 std::vector<Real>& fill, std::vector<int>& count,
                 const MovingSolids* moving = nullptr);

// The liquid's volume [m^3]: every liquid cell by its fill (a Full cell's is 1 but for chains,
// whose cells crossed by a link keep the exact part the liquid fills).
Real liquid_volume(const LiquidModel& model, const std::vector<CellFlag>& flags,
                   const std::vector<Real>& fill);

// The height field's column of horizontal cell (i0, i1) (0-based) and its two axes.
struct ColumnAxes {
  int h0 = 0, h1 = 1, v = 2;
};
ColumnAxes column_axes(const LiquidModel& model);
int column_count(const LiquidModel& model);

}  // namespace pbm
