// Kinematics of one end of a point-to-point constraint (7.21): its position x, velocity
// x-dot = L q-dot, the acceleration (or, for first-order bodies, the velocity) the body's
// unconstrained motion gives it, and the transpose of its point Jacobian on the body's rigid and
// global coordinates, G = L^T = P^T R^T (k x 3, k = 6 + n_s; P = [I, -p~, J] of (3.4)).
//
// Constraint forces act on the rigid and global rows only, as obstacle forces do
// (collide/rigid_contact.h): with lumped masses a force on the q_d rows would move its node alone
// (its mobility is 1/m_i, no other node feels it), pulling a single node out of an assembling
// part. C itself is measured on the deformed surface, x = c + R (s + d), so Baumgarte's feedback
// also corrects what the node's displacement adds.
//
// All take the body workspaces after compute_body_kinematics of the same state.
#pragma once

#include <vector>

#include "constrain/constraint_model.h"
#include "deform/body_dynamics.h"

namespace pbm {

// x of the end [m], world frame.
Vec3 constraint_end_position(const ConstraintPoint& end, const std::vector<BodyWorkspace>& bodies,
                             const ConstrainedSystem& system, const VecX& q);

// x-dot of the end [m/s], world frame; v is the whole State::v.
Vec3 constraint_end_velocity(const ConstraintPoint& end, const std::vector<BodyWorkspace>& bodies,
                             const ConstrainedSystem& system, const VecX& v);

// The end's unconstrained rate, from the body's solved rates `rates` (the whole v-dot vector of
// this evaluation): second order, x-ddot = c-ddot + R (omega-dot x p + J q_s-ddot + d-ddot + a)
// with a the velocity-product term (3.18), i.e. L q-ddot + L-dot q-dot of (7.21); first order,
// x-dot = c-dot + R (omega x p + J q_s-dot + d-dot) from the velocities (3.51) solved.
Vec3 constraint_end_rate(const ConstraintPoint& end, const std::vector<BodyWorkspace>& bodies,
                         const ConstrainedSystem& system, const VecX& rates);

// G = P^T R^T (k x 3) into G, sized k x 3 by the caller.
void constraint_end_jacobian_transpose(const ConstraintPoint& end, const BodyModel& body,
                                       const BodyWorkspace& bw, MatX& G);

// rates(body slice) += the rate a generalized rigid+global increment `delta` (k, body frame
// c, omega, q_s) stands for: c's row to the world frame (as solve_body_dynamics returns it).
void add_generalized_rate(const BodyModel& body, const BodyWorkspace& bw, const VecX& delta,
                          VecX& rates);

}  // namespace pbm
