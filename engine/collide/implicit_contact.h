// The obstacles' push taken at the step's end: the implicit integrator's contact on the rigid +
// global rows (docs/architecture.md, "Knobs that converge").
//
// Explicitly, the pressing points' springs a K (-phi) and dashpots (collide/rigid_contact.h) are
// stable only while each keeps omega dt <= 1 on the mass the point moves with, so
// add_contact_forces clamps a spring stiffer than the step resolves, and a point feels the ground
// only after a step has carried it in. At a large step both fail: a ball arriving at 4 m/s with
// h = 0.06 s is 0.26 m inside before its first push, the contact's potential 0.5 a K phi^2
// (measured with the unclamped stiffness) dwarfs the fall's energy, and the guard stops the run.
//
// Under "implicit" the clamp is lifted and each point's normal force is taken where the step
// ends, linearized in the rows it acts on (c in the body frame, theta, q_s). With g_p = P_p^T R^T
// n_p (the point's direction in the rows), u = g_p^T nu its normal velocity relative to the
// obstacle, k_p and c_p its spring and dashpot, and semi-implicit Euler (nu+ = nu + h alpha,
// phi_end = phi + h u+):
//   f_p = -k_p phi_end - c_p u+ = e_p - beta_p g_p^T x,
//   second order (x = alpha):  e_p = -k_p phi - (c_p + h k_p) u,  beta_p = h (c_p + h k_p),
//   first order (3.51, x = nu+): e_p = -k_p phi + (c_p + h k_p) w_p,  beta_p = c_p + h k_p,
// (w_p the obstacle's normal velocity there), and the rows solve
//   (A' + sum_active beta_p g_p g_p^T) x = r_g + sum_active g_p e_p,   A' = A or nu_d A.
// A point is active while its end force pushes (f_p >= 0): points leave and join the set until
// it is consistent (a few k x k solves). The candidates include the points of the global surface
// that the step may carry in (phi < h times the fastest approach), so a landing point is stopped
// at the surface in the step it arrives. beta_p >= 0 makes the system A' plus a positive
// semi-definite part: backward Euler damps the stiff contact modes at any h. The local
// displacements keep their own implicit membrane (deform/implicit_membrane.h); friction stays
// explicit with its per-step cap, and the projection after the step (resolve_penetrations) is
// unchanged.
#pragma once

#include "core/types.h"
#include "deform/body_model.h"
#include "deform/body_workspace.h"

namespace pbm {

// Sizes the scratch and turns the implicit contact on for the body (local bodies).
void prepare_implicit_contact(const BodyModel& body, BodyWorkspace& ws);

// Replaces the rigid + global part of `rates` (the explicit solve_body_dynamics output for the
// body's slice of v, whose r_g holds every force but the points' normal push) by the solve above.
// Needs the candidates of the same evaluation (add_contact_forces) and the mass block; leaves the
// rates as they are where no point is a candidate.
void implicit_contact_rates(const BodyModel& body, BodyWorkspace& ws, Eigen::Ref<VecX> rates);

}  // namespace pbm
