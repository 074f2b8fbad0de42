// What of a liquid changes a later frame (docs/architecture.md, "Determinism"): its velocities
// and pressure (the pressure warm-starts the next solve and enters the next momentum update,
// (16.2)), its markers or height field, and what its inflows have released.
#pragma once

#include <cstdint>
#include <vector>

#include "liquid/liquid_model.h"

namespace pbm {

struct LiquidState {
  Real time = 0;      // how far the liquid has advanced [s] (it steps on its own CFL clock)
  MacField velocity;  // u, v, w on the faces [m/s]
  std::vector<Real> pressure;  // kinematic pressure p / rho at the centres [m^2/s^2] (16.1)
  std::vector<Vec3> markers;   // marker particles (16.3.1) [m]
  // Free-surface marker chains (16.3.2, liquid/surface_chains.h): the markers [m] and each one's
  // next on its loop.
  std::vector<Vec3> chain;
  std::vector<int> chain_next;
  Real chain_area =
      0;  // the area the chains enclosed at the start, which volume_correction keeps [m^2]
  // Each marker's velocity with advection flip (empty otherwise) [m/s].
  std::vector<Vec3> marker_velocity;
  // Spray in the air and foam on the surface (liquid/spray.h) [m], [m/s], [s].
  std::vector<Vec3> spray, spray_velocity;
  std::vector<Vec3> foam;
  std::vector<Real> foam_age;
  std::uint64_t spray_total = 0;     // spray ever emitted: seeds where the next one goes
  Real spray_owed = 0;               // a fraction of a particle owed to the next substep
  std::vector<Real> height;          // surface height per column (16.3.3) [m], height field only
  std::vector<Real> released;        // per inflow: markers owed but not yet released (a fraction)
  std::uint64_t released_total = 0;  // markers ever released: seeds where the next one goes
  // The length the next substep may take (liquid_substep_limit after the last advance; 0 before
  // the first) [s]: a caller stepping other systems in shorter steps advances the liquid once
  // this much time has passed (sim/stages_liquid.h).
  Real next_step = 0;
  // 1 once an advance stopped at max_substeps short of its time (the run fails there).
  int overrun = 0;
};

LiquidState initial_liquid_state(const LiquidModel& model, const Vec3& gravity);

// Adds the bytes of every field to an FNV-1a hash.
void hash_liquid_state(const LiquidState& state, std::uint64_t& h);

// Bytes the state holds (the timeline's memory budget).
std::size_t liquid_state_bytes(const LiquidState& state);

}  // namespace pbm
