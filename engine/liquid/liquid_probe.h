// The liquid as a body in it feels it (16.4): the pressure at any point, for the buoyancy of
// (16.13)-(16.15), and the velocity, for the drag the book folds into D (16.16). The pressure the
// solve leaves at the Full cells' centres is continued hydrostatically past them: into a Surface
// cell from where its fill puts the surface, into Empty cells above the liquid and into Solid
// cells, so that interpolated between centres it is linear in depth and crosses zero at the
// surface. A body's pressure integral then gives Archimedes' force for a surface anywhere inside
// a cell, not at its centre (tests/test_liquid_coupling.cpp).
//
// Under two-way coupling (liquid/moving_solids.h) the liquid's cells take the hydrostatic
// pressure below the free surface over them (waves included) instead of the solve's: beside a
// body that moves the liquid, the solve's pressure holds the body's own added mass (the liquid it
// must accelerate), and fed back one substep late it makes a body lighter than about half the
// liquid unstable (measured: a ball of 0.2 rho released under water was flung sideways at 68 N).
// The flow's push on such a body is its drag against the liquid's velocity.
#pragma once

#include "liquid/liquid_state.h"
#include "liquid/liquid_workspace.h"

namespace pbm {

// Rebuilds ws.probe_pressure and ws.probe_velocity from the state (labels it, into ws.flags,
// ws.fill and ws.count, with the cells ws.moving covers Solid); gravity as the liquid steps under
// it.
void build_liquid_probe(const LiquidModel& model, const LiquidState& state, const Vec3& gravity,
                        LiquidWorkspace& ws);

// Whether a point lies in the liquid's domain (a 2D grid counts as extruded along its thin
// axis: a slice of a flow that does not vary along it).
bool in_liquid_domain(const LiquidModel& model, const Vec3& x);

// The kinematic pressure p / rho at a point [m^2/s^2], >= 0 (0 above the surface and outside the
// domain), from the probe.
Real probe_pressure(const LiquidModel& model, const LiquidWorkspace& ws, const Vec3& x);

// The liquid's velocity at a point [m/s] (clamped into the domain), from the probe.
Vec3 probe_velocity(const LiquidModel& model, const LiquidWorkspace& ws, const Vec3& x);

}  // namespace pbm
