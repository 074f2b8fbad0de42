// The algorithm of 16.5 over one liquid: substeps of its own length, each the CFL condition
// (16.3) at the chosen fraction, until the liquid reaches a time.
#pragma once

#include "liquid/liquid_state.h"
#include "liquid/liquid_workspace.h"
#include "liquid/moving_solids.h"
#include "liquid/pressure_system.h"

namespace pbm {

// What the liquid's substeps cost and measured since the stats were last reset.
struct LiquidStepStats {
  int substeps = 0;
  int iterations = 0;           // of every pressure solve
  int max_iterations = 0;       // of the worst one
  int unconverged = 0;          // solves that stopped at max_iterations
  Real divergence = 0;          // the largest |div u| of a Full cell after a solve [1/s]
  Real cfl = 0;                 // the largest max_a |u_a| dt / h_a taken (16.3)
  Real dt_min = 0, dt_max = 0;  // the substeps' lengths [s]
  int removed = 0;              // markers that left by an outflow
  int dropped = 0;              // markers an inflow could not release (the capacity)
  int solid_cells = 0;          // cells moving solids covered at the last substep
  int pushed = 0;               // markers pushed out of them (liquid/moving_solids.h)
  int spray_emitted = 0;        // spray particles released (liquid/spray.h)
  int foam_landed = 0;          // spray fallen back onto the liquid as foam
  // Chains (liquid/surface_chains.h): markers inserted on long links, deleted as too close,
  // joins of surfaces meeting, loops dropped below three markers, substeps whose insertion
  // stopped at the capacity.
  int chain_inserted = 0, chain_deleted = 0, chain_joins = 0, chain_loops_dropped = 0;
  int chain_full = 0;
  // Substeps redone shorter because the velocities they made would cross more of a cell than the
  // CFL fraction (the limit's estimate misses the pressure's acceleration, e.g. at a dam break's
  // foot: 0.57 in its first substep at CFL 0.5 before the check).
  int cfl_retries = 0;
  double solve_seconds = 0;  // wall time in the pressure solves (a cost, never a result)
};

struct LiquidInputs {
  Vec3 gravity{0, 0, -9.81};
  // Applied on the Surface cells beyond the liquid's own surface_pressure [Pa] (16.6.2), at
  // `time`, changing at surface_pressure_rate [Pa/s].
  Real surface_pressure = 0;
  Real surface_pressure_rate = 0;
  // Every inflow's velocity while a track drives it (16.6.1), at `time`, with its rate; else
  // (inflows_driven false) each inflow keeps the scene's.
  bool inflows_driven = false;
  Vec3 inflow_velocity = Vec3::Zero();
  Vec3 inflow_rate = Vec3::Zero();
  // When the values above hold [s]: a substep takes them at its own start.
  Real time = 0;
  // Two-way coupling (liquid/moving_solids.h): the cells the scene's obstacles cover, and the
  // bodies' surfaces as they are at surfaces_time; each substep voxelizes them at its own start.
  std::span<const SolidCell> obstacle_cells = {};
  std::span<const SolidSurface> surfaces = {};
  Real surfaces_time = 0;
};

// The length of the next substep: the CFL fraction of the time to cross a cell at the fastest
// face's speed plus the speed gravity gives in that time, and the explicit viscous limit.
Real liquid_substep_limit(const LiquidModel& model, const LiquidInputs& inputs,
                          const LiquidState& state);

// One substep of 16.5 (steps 3-8) of length dt, or shorter: when the velocities after the
// pressure solve would carry the liquid across more than the CFL fraction of a cell in dt, steps
// 5-7 are redone from the substep's start with dt shortened to keep it (up to 4 times; the
// surface has not moved yet). Returns the length taken.
Real liquid_substep(const LiquidModel& model, const LiquidInputs& inputs, Real dt,
                    LiquidState& state, LiquidWorkspace& ws, LiquidStepStats& stats);

// Substeps until state.time reaches t_end (equal lengths within the limit); then the limit of the
// next one in state.next_step. At most def.max_substeps: false (and state.overrun = 1) when they
// did not reach t_end.
bool advance_liquid(const LiquidModel& model, const LiquidInputs& inputs, Real t_end,
                    LiquidState& state, LiquidWorkspace& ws, LiquidStepStats& stats);

}  // namespace pbm
