// The membrane's stiffness taken implicitly over a substep: the "implicit" integrator
// (docs/architecture.md, "Knobs that converge"), a linearized backward Euler for the local
// displacements of sec. 6.1.
//
// The explicit dynamics (deform/body_dynamics.h) give the local accelerations as
//   d-ddot = T r,   T = M^-1 - P A^+ P^T,   r_i = f_i - m_i a_i - (K_dd q_d)_i - nu m_i x_i-dot
// (the mean-axis split: T removes what c, theta and q_s carry). Euler (6.1) is stable only while
// the fastest membrane mode keeps omega dt < 2 (deform/stability_limit.h). Backward Euler takes
// the stiff terms at the step's end instead, d -> d + h d-dot+ and d-dot -> d-dot+ in K_dd q_d and
// in the damping's d part, which makes the increment z = d-dot+ - d-dot solve
//   (I + T B) z = g,   B = h nu M + h^2 K_dd,   g = h d-ddot - h^2 T K_dd d-dot.
// First-order bodies (3.51) give the velocity d-dot = T r / nu; the same substitution gives
//   (I + T B) d-dot+ = d-dot,   B = (h / nu) K_dd.
// With H = M + B (sparse, symmetric positive definite, one Cholesky factor per substep length:
// K_dd is constant, so the factor is reused while h stays), multiplying by M gives
//   H z = M g + M P mu,   mu = A^+ P^T B z,
// and since B = H - M, P^T B z needs no product with K:
//   z = y0 + Y mu,  Y = H^-1 M P,  y0 = H^-1 M g,
//   (I - A^+ P^T M (P - Y)) mu = A^+ P^T M (g - y0)             (k x k, k = 6 + n_s).
// K_dd = K (x) I_3 (the three coordinates share one scalar matrix, membrane_stiffness.h), so
// every solve is the scalar n x n factor applied to the distinct scalar fields of M P and M g
// (4 + 3 n_s + 3 of them: implicit_membrane.cpp). Each mode of K_dd in the
// mean-axis subspace then follows backward Euler, stable and damped at any h; the rigid, global
// and contact rows stay explicit (their limits are the parameter inertia floor's and the contact's
// mobility sizing, both set so they hold at any step).
#pragma once

#include <span>

#include "core/types.h"
#include "deform/body_model.h"
#include "deform/body_workspace.h"

namespace pbm {

// Assembles the scalar K_dd and analyzes its pattern (local bodies; no-op otherwise).
void prepare_implicit_membrane(const BodyModel& body, BodyWorkspace& ws);

// Replaces the d part of `rates` (the explicit solve_body_dynamics output for the body's slice v)
// by the backward-Euler rate over a substep h: z / h for second-order bodies, d-dot+ for
// first-order ones. Needs the kinematics, the factored mass block and the explicit rates of the
// same state. Allocates only when h changes (a new factor).
void implicit_membrane_rates(const BodyModel& body, const Eigen::Ref<const VecX>& v,
                             BodyWorkspace& ws, Real h, Eigen::Ref<VecX> rates);

// The damping of the rigid and global rows taken at the step's end: a second-order body's
// -nu m_i x_i-dot (sec. 6.1) acts on c, theta and q_s as -nu A q-dot, so backward Euler over h
// gives q-dot+ = (q-dot + h a) / (1 + h nu), i.e. their explicit rates divided by 1 + h nu. Without
// it the damper alone limits the step to 2 / nu (the interactive scene's nu = 4000 to 0.5 ms);
// with it only the global block's 1 / tau does (deform/stability_limit.h). The d rows are
// implicit_membrane_rates' (h nu M in B); first-order bodies have no such rows to damp.
void implicit_row_damping(const BodyModel& body, Real h, Eigen::Ref<VecX> rates);

// The smallest change of the node positions (or velocities) that moves each listed node
// (ws.implicit.nodes) by its amount along its normal while pushing, never pulling (multipliers
// >= 0, by an active set). A node moves through the body's local displacements, in the metric of
// the substep's H = a M + b K, and through its rigid and global coordinates, whose compliance the
// caller gives in ws.implicit.global (m x m: n_i^T P_i A^+ P_j^T n_j, or n_i . n_j / mass for a
// translation):
//   (N^T H^-1 N + global) lambda = amounts,   local change dx = H^-1 N lambda.
// A projection made node by node dents a stiff membrane by the step's whole penetration, an
// energy 1/2 K_ii depth^2 that grows with the step; here a stiff body moves as a whole and a soft
// one dents, as backward Euler over the step would have it. H is isotropic per node
// (K_dd = K (x) I_3), so dx is in the normals' frame. Writes dx into ws.implicit.change (3 n) and
// the multipliers into ws.implicit.lambda (0 for nodes dropped). Needs the factor of the substep
// (implicit_membrane_rates) and reserve_contact_nodes for the list's size.
void implicit_node_correction(const BodyModel& body, BodyWorkspace& ws);

// Room for m listed nodes in the contact scratch (grown by doubling; no allocation below).
void reserve_contact_nodes(const BodyModel& body, BodyWorkspace& ws, int m);

}  // namespace pbm
