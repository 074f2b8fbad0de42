// A liquid's push on a figure's segments (16.4), one way, as on bodies (sim/liquid_body_loads.h):
// buoyancy as the pressure integrated over each segment's surface, -oint p n dA (the book's
// f = -grad p dV (16.13) summed over the segment's volume (16.15), by the divergence theorem),
// here over the exact shape's patches (figure/segment_surface.h), so that a segment the surface
// cuts through gets Archimedes' force of its submerged part; drag, the damping of (16.16), as
// -1/2 rho C_d A |v_rel| v_rel over each wet patch facing the flow, v_rel the segment's material
// velocity there less the liquid's.
#pragma once

#include <span>
#include <vector>

#include "core/spatial.h"
#include "figure/segment_surface.h"
#include "liquid/liquid_probe.h"

namespace pbm {

struct LiquidSegmentTotals {
  Vec3 force = Vec3::Zero();  // in world coordinates [N]
  Real wetted_area = 0;       // [m^2]
  Real power = 0;             // of the forces at the segments' velocities [W]
};

// The divisions of the segments' surface patches the liquid loads integrate over
// (figure/segment_surface.h): a sphere's 256 points give Archimedes' force within 0.15% of its
// full buoyancy at any water line (tests/test_liquid_figure.cpp).
inline constexpr int kSegmentSurfaceDivisions = 4;

// Adds the liquid's force on each segment to forces[i] (spatial, in segment i's own frame, about
// its origin, as figure/articulated_body.h takes external forces), with the segments at `world`
// (inertial -> segment) moving at `v` (spatial, own frames). The liquid's probe must be built
// (liquid/liquid_probe.h).
LiquidSegmentTotals add_liquid_segment_loads(const LiquidModel& liquid, const LiquidWorkspace& lw,
                                             const std::vector<std::vector<SurfacePatch>>& patches,
                                             const std::vector<SpatialTransform>& world,
                                             std::span<const Vec6> v,
                                             std::span<ForceVector> forces);

}  // namespace pbm
