// A liquid's push on the bodies in it (16.4), one way: the liquid moves them, they do not move
// it (the book's assumption of small bodies). Buoyancy: the book's f_i = -grad p_i dV_i (16.13)
// summed over a body (16.15) is, by the divergence theorem, the pressure integrated over its
// surface, -oint p n dA; we integrate that form over the body's surface triangles, which needs
// no volume per node and gives Archimedes' force (and its torque) also for a body the surface
// cuts through (the book's nodes on the surface would count a half-submerged box's submerged
// sides and bottom as more than half its volume). Drag: the damping D of (16.16) "proportional
// to the relative velocity between a node and the local fluid", i.e. quadratic, -1/2 rho C_d A
// |v_rel| v_rel over each wet triangle facing the flow, whose projected areas sum to a body's
// frontal area (liquid "drag" is C_d).
#pragma once

#include <vector>

#include "deform/body_model.h"
#include "deform/body_workspace.h"
#include "liquid/liquid_probe.h"

namespace pbm {

struct LiquidLoadTotals {
  Vec3 force = Vec3::Zero();  // on the body [N]
  Real wetted_area = 0;       // [m^2]
};

// Adds the liquid's nodal forces on the body, at the body's kinematics in bw (x, x_dot), to
// `force` (one entry per node) [N]. The liquid's probe must be built (liquid/liquid_probe.h).
LiquidLoadTotals add_liquid_loads(const LiquidModel& liquid, const LiquidWorkspace& lw,
                                  const BodyModel& body, const BodyWorkspace& bw,
                                  std::vector<Vec3>& force);

}  // namespace pbm
