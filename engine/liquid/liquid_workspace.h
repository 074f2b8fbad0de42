// A liquid's scratch (docs/architecture.md, "Workspace"): the cell labels of the substep, the
// tentative velocities, the pressure system and its solvers' vectors. Nothing here changes a
// later frame: every array is rebuilt from the state in each substep.
#pragma once

#include <vector>

#include "liquid/boundary_conditions.h"
#include "liquid/liquid_model.h"
#include "liquid/moving_solids.h"
#include "liquid/pressure_multigrid.h"
#include "liquid/surface_chains.h"

namespace pbm {

struct LiquidWorkspace {
  std::vector<CellFlag> flags;       // this substep's labels (16.3)
  std::vector<Real> fill;            // fraction of a Surface cell the liquid fills, 1 in Full cells
  std::vector<int> count;            // markers per cell
  MacField previous;                 // the velocities at the substep's start (advection reads them)
  std::vector<Real> pressure_start;  // the pressure at the substep's start (a CFL retry's)
  // Advection flip: the markers' weights on each face as their velocities are spread to the grid.
  std::vector<Real> transfer_weight[3];
  ExtrapolationWork extrapolation;  // faces whose velocity the extrapolation may read
  // The pressure system A dp = D on the Full cells (liquid/pressure_system.h), per cell.
  std::vector<int> cell_of_row;              // the Full cells, in index order
  std::vector<Real> diag;                    // A's diagonal
  std::vector<Real> target;                  // the divergence each Full cell is solved to [1/s]
  std::vector<Real> face_scale[3];           // s_f of each cell's + face along each axis
  std::vector<Real> dp, r, z, s, q, precon;  // conjugate gradients' vectors, MIC(0)'s factor
  std::vector<Real> height_next;             // the height field's update (16.12)
  ChainScratch chains;                       // the chains' remeshing (liquid/surface_chains.h)
  // With chains and volume_correction: the divergence every Full cell is solved to this substep
  // [1/s], the share of the area's drift from LiquidState::chain_area the knob restores.
  Real chain_divergence = 0;
  std::vector<Vec3> inflow_velocity;  // each inflow's this substep (LiquidInputs)
  MultigridHierarchy multigrid;
  // The cells bodies and obstacles cover (two-way coupling), set before each substep and each
  // probe from where they are then.
  MovingSolids moving;
  // What bodies in the liquid read (liquid/liquid_probe.h), rebuilt from the state before each
  // of their substeps: the pressure continued past the liquid, the velocities.
  std::vector<Real> probe_pressure;
  std::vector<std::uint8_t> probe_known;
  std::vector<int> probe_order;
  std::vector<Real> probe_eta, probe_next_eta;  // the free surface over each liquid cell [m]
  MacField probe_velocity;
};

void size_liquid_workspace(const LiquidModel& model, LiquidWorkspace& ws);

}  // namespace pbm
