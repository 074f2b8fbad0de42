#include "liquid/liquid_step.h"

#include <algorithm>
#include <cmath>

#include "core/wall_clock.h"
#include "liquid/boundary_conditions.h"
#include "liquid/cell_labels.h"
#include "liquid/momentum.h"
#include "liquid/particle_transfer.h"
#include "liquid/spray.h"
#include "liquid/surface_chains.h"
#include "liquid/surface_tracking.h"

namespace pbm {

namespace {

// How far outside the liquid the velocities are continued: a marker or a backtrace moves less
// than a cell in a substep (16.3), so two layers hold everything either reads.
constexpr int kExtrapolationLayers = 2;

// The largest |u_a| / h_a over faces with liquid on a side [1/s].
Real fastest_rate(const LiquidModel& model, const std::vector<CellFlag>* flags,
                  const MacField& field) {
  const MacGrid& g = model.grid;
  Real rate = 0;
  for (int a = 0; a < 3; ++a) {
    const int e = g.stride(a);
    const std::vector<Real>& u = field.u[a];
    for (int c = e; c + e < g.size; ++c) {
      if (flags && !is_liquid((*flags)[static_cast<std::size_t>(c)]) &&
          !is_liquid((*flags)[static_cast<std::size_t>(c + e)])) {
        continue;
      }
      rate = std::max(rate, std::abs(u[static_cast<std::size_t>(c)]) / g.h[a]);
    }
  }
  return rate;
}

// Pressure where no solve sets it: the applied one in Surface and Empty cells (16.2.2), with the
// surface waves' at time t (16.17); an Outflow cell's follows the liquid beside it (the last
// substep's), so the liquid leaves at the rate its own pressure drives.
void set_boundary_pressure(const LiquidModel& model, const std::vector<CellFlag>& flags,
                           Real applied, Real t, std::vector<Real>& p) {
  const MacGrid& g = model.grid;
  const bool waves = !model.surface_waves.empty();
  for (int c = 0; c < g.size; ++c) {
    const CellFlag f = flags[static_cast<std::size_t>(c)];
    if (f == CellFlag::surface || f == CellFlag::empty) {
      p[static_cast<std::size_t>(c)] =
          applied + (waves ? surface_wave_pressure(model, g.centre(c), t) : 0.0);
    } else if (f == CellFlag::outflow) {
      Real sum = 0;
      int n = 0;
      for (int a = 0; a < 3; ++a) {
        for (int side = -1; side <= 1; side += 2) {
          const int nb = c + side * g.stride(a);
          if (nb < 0 || nb >= g.size || !is_liquid(flags[static_cast<std::size_t>(nb)])) continue;
          sum += p[static_cast<std::size_t>(nb)];
          ++n;
        }
      }
      p[static_cast<std::size_t>(c)] = n > 0 ? sum / n : applied;
    }
  }
}

}  // namespace

Real liquid_substep_limit(const LiquidModel& model, const LiquidInputs& inputs,
                          const LiquidState& state) {
  const MacGrid& g = model.grid;
  Real h_min = 1e300, inv_h2 = 0;
  for (int a = 0; a < 3; ++a) {
    if (a == model.thin_axis) continue;
    h_min = std::min(h_min, g.h[a]);
    inv_h2 += 1 / (g.h[a] * g.h[a]);
  }
  // The whole field, liquid or not: its labels are the next substep's to make.
  const Real rate =
      fastest_rate(model, nullptr, state.velocity) + std::sqrt(inputs.gravity.norm() / h_min);
  Real dt = model.def.cfl / std::max(rate, 1e-12);
  // Explicit diffusion is stable for nu dt sum_a 2 / h_a^2 <= 1.
  if (model.def.viscosity > 0) dt = std::min(dt, 1 / (2 * model.def.viscosity * inv_h2));
  return dt;
}

Real liquid_substep(const LiquidModel& model, const LiquidInputs& inputs, Real dt,
                    LiquidState& state, LiquidWorkspace& ws, LiquidStepStats& stats) {
  // The driven values at the substep's start (16.6).
  const Real since = state.time - inputs.time;
  const Real applied =
      (inputs.surface_pressure + inputs.surface_pressure_rate * since) / model.def.density +
      model.def.surface_pressure / model.def.density;
  ws.inflow_velocity.resize(model.inflows.size());
  for (std::size_t s = 0; s < model.inflows.size(); ++s) {
    ws.inflow_velocity[s] = inputs.inflows_driven
                                ? Vec3(inputs.inflow_velocity + inputs.inflow_rate * since)
                                : model.inflows[s].velocity;
  }
  // The solids where they are now, and the liquid they swept pushed ahead of them.
  clear_moving_solids(ws.moving);
  for (const SolidCell& cell : inputs.obstacle_cells) {
    mark_solid_cell(model, cell.cell, cell.velocity, ws.moving);
  }
  for (const SolidSurface& surface : inputs.surfaces) {
    voxelize_surface(model, surface, state.time - inputs.surfaces_time, ws.moving);
  }
  if (model.def.surface == SurfaceMethod::markers) {
    stats.pushed += push_markers_out(model, ws.moving, state.markers);
  }
  stats.solid_cells = static_cast<int>(ws.moving.cells.size());
  // 3-4: labels, boundary pressures and velocities.
  label_cells(model, state, ws.flags, ws.fill, ws.count, &ws.moving);
  set_boundary_pressure(model, ws.flags, applied, state.time, state.pressure);
  MacField& field = state.velocity;
  const bool carried = model.def.advection == LiquidAdvection::flip;
  // PIC/FLIP: the markers' velocities are the substep's starting field where they reach.
  if (carried) markers_to_grid(model, state.markers, state.marker_velocity, ws, field);
  set_wall_velocities(model, ws.flags, ws.inflow_velocity, ws.moving, field);
  set_surface_velocities(model, ws.flags, field);
  extrapolate_velocities(model, ws.flags, kExtrapolationLayers, ws.extrapolation, field);
  for (int a = 0; a < 3; ++a) ws.previous.u[a] = field.u[a];
  // Steps 5-7 from the substep's start; redone shorter while the field they make would exceed
  // the CFL fraction (a 2% margin under it, so a retry is not followed by another at the edge).
  ws.pressure_start = state.pressure;
  constexpr int kCflRetries = 4;
  PressureSolveStats solve;
  Real rate = 0;  // the fastest face's |u| / h after step 7 [1/s]
  for (int attempt = 0;; ++attempt) {
    if (attempt > 0) {
      for (int a = 0; a < 3; ++a) field.u[a] = ws.previous.u[a];
      state.pressure = ws.pressure_start;
    }
    // Chains drift in area through the interpolated field (3.5% in 4 s of a dam break,
    // tests/test_liquid_chains.cpp): the liquid expands or contracts uniformly by the knob's share
    // of the drift each substep, a divergence of (A0 - A) / (A dt) restoring all of it.
    ws.chain_divergence = 0;
    if (model.def.surface == SurfaceMethod::chains && model.def.volume_correction > 0) {
      const Real area = chains_area(model, state.chain, state.chain_next);
      if (area > 0) {
        ws.chain_divergence = model.def.volume_correction *
                              std::clamp((state.chain_area - area) / area, -1.0, 1.0) / dt;
      }
    }
    // The system of this substep's labels; its ghost-fluid scales also enter the momentum's
    // pressure gradient.
    const bool dirichlet = build_pressure_system(model, dt, ws);
    // 5: the tentative velocities.
    update_momentum(model,
                    MomentumInput{.flags = ws.flags,
                                  .face_scale = ws.face_scale,
                                  .previous = ws.previous,
                                  .pressure = state.pressure,
                                  .gravity = inputs.gravity,
                                  .dt = dt},
                    field);
    set_wall_velocities(model, ws.flags, ws.inflow_velocity, ws.moving, field);
    // 6: the pressure iteration.
    const PressureSolveOptions options{.tolerance = model.def.tolerance,
                                       .relative = model.def.relative_tolerance,
                                       .max_iterations = model.def.max_iterations};
    const WallClock::time_point solve_start = WallClock::now();
    solve =
        solve_pressure(model, model.def.solver, dt, dirichlet, options, ws, field, state.pressure);
    stats.solve_seconds += seconds_since(solve_start);
    // 7: the Surface cells' velocities again, and what lies beyond them.
    set_surface_velocities(model, ws.flags, field);
    set_wall_velocities(model, ws.flags, ws.inflow_velocity, ws.moving, field);
    extrapolate_velocities(model, ws.flags, kExtrapolationLayers, ws.extrapolation, field);
    rate = fastest_rate(model, &ws.flags, field);
    if (attempt == kCflRetries || dt * rate <= model.def.cfl * (1 + 1e-9)) break;
    dt = 0.98 * model.def.cfl / rate;
    stats.cfl_retries += 1;
  }
  // 8: the surface.
  if (model.def.surface == SurfaceMethod::height_field) {
    advance_height_field(model, field, dt, state, ws);
  } else if (model.def.surface == SurfaceMethod::chains) {
    advect_chains(model, field, dt, state.chain);
    const ChainRemeshStats remesh = remesh_chains(model, state.chain, state.chain_next, ws.chains);
    stats.chain_inserted += remesh.inserted;
    stats.chain_deleted += remesh.deleted;
    stats.chain_joins += remesh.joined;
    stats.chain_loops_dropped += remesh.loops_dropped;
    stats.chain_full += remesh.full ? 1 : 0;
  } else {
    // The markers' velocities take the substep's change before they move with it.
    if (carried) grid_to_markers(model, ws.previous, field, state.markers, state.marker_velocity);
    stats.removed +=
        advect_markers(model, field, dt, state.markers, state.marker_velocity, &ws.moving);
    stats.dropped += release_markers(model, ws.inflow_velocity, dt, state);
    if (model.def.spray_speed > 0) {
      SprayStats spray;
      advance_spray(model, field, inputs.gravity, dt, ws, state, spray);
      stats.spray_emitted += spray.emitted;
      stats.foam_landed += spray.landed;
    }
  }
  state.time += dt;
  stats.substeps += 1;
  stats.iterations += solve.iterations;
  stats.max_iterations = std::max(stats.max_iterations, solve.iterations);
  stats.unconverged += solve.converged ? 0 : 1;
  stats.divergence = std::max(stats.divergence, solve.divergence);
  stats.cfl = std::max(stats.cfl, dt * rate);
  stats.dt_min = stats.substeps == 1 ? dt : std::min(stats.dt_min, dt);
  stats.dt_max = std::max(stats.dt_max, dt);
  return dt;
}

bool advance_liquid(const LiquidModel& model, const LiquidInputs& inputs, Real t_end,
                    LiquidState& state, LiquidWorkspace& ws, LiquidStepStats& stats) {
  // A remainder below this fraction of a substep is left to the next call.
  constexpr Real kNegligible = 1e-9;
  int taken = 0;
  while (t_end - state.time > kNegligible * (1 + std::abs(t_end))) {
    if (taken++ == model.def.max_substeps) {
      state.overrun = 1;
      state.next_step = liquid_substep_limit(model, inputs, state);
      return false;
    }
    const Real limit = liquid_substep_limit(model, inputs, state);
    const Real remaining = t_end - state.time;
    const Real n = std::ceil(remaining / limit - 1e-9);
    const Real dt = n <= 1 ? remaining : remaining / n;
    const Real length = liquid_substep(model, inputs, dt, state, ws, stats);
    // Exactly, whatever the rounding of the sum (unless the CFL check shortened the substep).
    if (n <= 1 && length == dt) state.time = t_end;
  }
  state.next_step = liquid_substep_limit(model, inputs, state);
  return true;
}

}  // namespace pbm
