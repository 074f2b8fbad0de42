// Spray and foam (beyond the book's 16.3; Houdini's whitewater, Blender's FLIP spray and foam):
// where a marker liquid's surface rises fast, spray particles leave it and fly under gravity and
// air drag; spray falling back onto the liquid becomes foam, which rides the surface with the
// liquid's velocity and fades after its lifetime. Secondary and massless: they draw the splash,
// they carry none of the liquid's volume or momentum. They live in the State (they change later
// frames) and are seeded deterministically, so reruns give the same bits.
#pragma once

#include "liquid/liquid_state.h"
#include "liquid/liquid_workspace.h"

namespace pbm {

struct SprayStats {
  int emitted = 0;  // spray particles released this advance
  int landed = 0;   // of them turned to foam
  int faded = 0;    // foam particles past their lifetime
};

// One substep of dt of the spray and foam of a liquid whose cells ws.flags labels and whose
// velocities `field` holds (the substep's end): spray from every Surface cell with open air
// above whose liquid rises faster than spray_speed, at spray_rate per cell per second; then
// a' = g - k |v| v for spray (k = spray_drag, terminal speed sqrt(g / k)), advection with the
// liquid for foam.
void advance_spray(const LiquidModel& model, const MacField& field, const Vec3& gravity, Real dt,
                   const LiquidWorkspace& ws, LiquidState& state, SprayStats& stats);

// The spray's motion in air alone, one step of dt (the semi-implicit drag keeps it stable at
// any dt: the speed relaxes toward the terminal one rather than overshooting it).
void fly_spray(const Vec3& gravity, Real drag, Real dt, Vec3& x, Vec3& v);

}  // namespace pbm
