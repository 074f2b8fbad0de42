// Constraints kept through collisions (issue 12; docs/architecture.md, "Constraints through
// collisions").
//
// Baumgarte's feedback (7.14) closes a violation at the rates alpha and beta, but the collision
// stages after the integrator (sec. 5.2: the projection of nodes out of obstacles and the
// inelastic impact on their velocities, the impulses between bodies) move each body on its own.
// A landing part is stopped while the part constrained to it keeps falling, so every substep of
// an impact opens C-dot by up to 0.14 m/s and C by 1e-4 m (the snowman, measured at dt 1 ms), and
// the feedback, at alpha = 30/s, lets C reach 1.2 cm before it closes it again.
//
// So the constraints are recorded as the integrator left them and, after the collision stages,
// restored: C and C-dot of every point constraint are brought back to their values before the
// collisions. The collisions' change to the constraints is undone and nothing else is: a part
// still assembling (7.16) keeps its exponential decay, and a substep without a collision is left
// bit for bit. Both levels use the constraint solve's own matrix N (7.36)-(7.41), with the mass
// metric of the bodies (the smallest change in kinetic energy's norm that does it):
//   position:  N lambda = C_before - C,        q_k += s M_k^-1 L^T lambda  (a few chord steps)
//   velocity:  N mu = C-dot_before - C-dot,    v_k += s M_k^-1 L^T mu
// on the rigid and global coordinates, as the constraint forces act (constrain/point_constraint.h).
// A velocity correction keeps the mean-axis split (it changes no d-dot). First-order bodies
// (3.51) have no velocity state: their positions alone are restored.
#pragma once

#include <vector>

#include "constrain/constraint_forces.h"

namespace pbm {

struct ConstraintProjectionWorkspace {
  VecX C_before, C_dot_before;    // 3 k-bar, as the integrator left them
  VecX C, C_dot, rhs, lambda;     // 3 k-bar
  std::vector<Mat3> R;            // per body: the rotation of its current quaternion
  std::vector<char> node_ends;    // per body: has an end on a node (needs its kinematics)
  std::vector<char> constrained;  // per body: has any end
};

void init_constraint_projection(const ConstrainedSystem& system, ConstraintProjectionWorkspace& pw);

// Records C and C-dot of every point constraint at (q, v): the state the integrator left.
void record_constraints_before_collisions(const ConstrainedSystem& system, const VecX& q,
                                          const VecX& v, std::vector<BodyWorkspace>& bodies,
                                          ConstraintProjectionWorkspace& pw);

struct ConstraintProjection {
  bool ran = false;        // whether the collisions opened any constraint (and it was undone)
  Real opened = 0;         // largest |C - C_before| the collisions made [m]
  Real opened_rate = 0;    // largest |C-dot - C-dot_before| [m/s]
  Real residual = 0;       // largest |C - C_before| after the projection [m]
  Real residual_rate = 0;  // the same for C-dot [m/s]
};

// An opening |C - C_before| + dt |C-dot - C-dot_before| up to this is left to Baumgarte's
// feedback [m].
inline constexpr Real kNegligibleOpening = 1e-7;

// Restores C and C-dot to the recorded values by changing q and v in place (see above), unless
// the collisions of this substep of length dt opened them negligibly. Needs every constrained
// body's factored mass block (the substep's last, or the collision stage's).
ConstraintProjection project_constraints_after_collisions(
    const ConstrainedSystem& system, VecX& q, VecX& v, std::vector<BodyWorkspace>& bodies,
    ConstraintWorkspace& cw, ConstraintProjectionWorkspace& pw, Real dt);

}  // namespace pbm
