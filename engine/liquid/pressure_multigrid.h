// The multigrid preconditioner of MGPCG (McAdams, Sifakis and Teran 2010) for the pressure
// system of liquid/pressure_system.h: one V-cycle on a hierarchy of coarsened grids approximates
// L^-1 r, where L is the grid Laplacian on the Full cells,
//   (L x)_c = sum over the faces f of c not shared with a Solid or Inflow cell of
//             (x_c - x_nb) / h_a^2,   x_nb = 0 when nb is Surface, Empty or Outflow (Dirichlet),
// (h_a the cell size along the face's axis). The pressure system is dt L with the ghost-fluid
// scale on faces to Surface cells; the V-cycle is symmetric and positive definite, as conjugate
// gradients need of a preconditioner.
#pragma once

#include <cstdint>
#include <vector>

#include "liquid/mac_grid.h"

namespace pbm {

struct MultigridLevel {
  MacGrid grid;                    // this level's cells (with a ghost layer)
  std::vector<std::uint8_t> type;  // per cell: 0 unknown, 1 Dirichlet, 2 Neumann (no cell)
  std::vector<Real> x, b, r;       // per cell
  // From the types, for the smoother: each unknown cell's diagonal (sum of 1/h_a^2 over its
  // faces not shared with a Neumann cell), and the unknown cells of each colour ((i + j + k) mod
  // 2), all of them and those beside a Dirichlet or Neumann cell, in index order.
  std::vector<Real> diag;
  std::vector<int> unknown[2], boundary[2];
};

struct MultigridHierarchy {
  std::vector<MultigridLevel> levels;  // levels[0]: the liquid's grid
};

// Sizes every level for `grid` (allocates; once per workspace). An axis of one cell (a 2D grid)
// is never coarsened.
void size_multigrid(const MacGrid& grid, MultigridHierarchy& mg);
// The levels' cell types from this substep's labels (no allocation).
void build_multigrid(const std::vector<CellFlag>& flags, MultigridHierarchy& mg);
// z = (one V-cycle) ~ L^-1 r on the unknown cells; r and z are per cell of the fine grid, z is 0
// elsewhere (no allocation).
void apply_multigrid(MultigridHierarchy& mg, const std::vector<Real>& r, std::vector<Real>& z);

}  // namespace pbm
