// Lagrangian dynamics of one hybrid deformable body (ch. 3) with lumped nodal masses (sec. 6.1).
//
// Kinematics (3.1)-(3.4), written in the body frame with P_i = [I, -p~_i, J_i] (3 x k, k = 6 +
// n_s):
//   x_i = c + R p_i,  p_i = s(u_i; q_s) + d_i                                           (3.3)
//   R^T x_i-dot = P_i nu_g + d_i-dot,  nu_g = (R^T c-dot, omega, q_s-dot)               (3.4)
//   R^T x_i-ddot = P_i alpha + d_i-ddot + a_i,                                           (3.17)
//   a_i = omega x (omega x p_i) + 2 omega x p_i-dot + J-dot_i q_s-dot                    (3.18)
// (3.18) as printed omits J-dot q_s-dot; without it a body whose q_s moves does not conserve
// momentum, so it is kept (computed by a second difference of s along q_s-dot).
//
// Mass matrix. With lumped masses at the nodes, M = sum m_i L_i^T L_i (3.14) is the arrowhead
//   [ A    C ]   A = sum m_i P_i^T P_i (k x k: M_cc, M_c theta, ..., M_ss of (3.16))
//   [ C^T  D ]   C_i = m_i P_i^T (coupling rows), D = diag(m_i I) (lumped M_dd)
// and its Schur complement A - C D^-1 C^T is exactly zero: nodal displacements can represent any
// rigid or global motion, so (c, theta, q_s, q_d) is redundant and M is singular. We remove the
// redundancy with the mean-axis (Tisserand) condition of floating-frame formulations,
//   sum_i m_i P_i^T d_i-dot = 0,
// i.e. q_d carries only the motion that c, theta and q_s cannot. Its constraint force acts on the
// d rows only, so the c and theta rows stay exact momentum balances. The solve is then O(nodes):
//   A alpha = r_g = sum P_i^T (f_i - m_i a_i) - K_ss (q_s - q_s0)                        (3.13)
//   d_i-ddot = r_i / m_i - P_i A^-1 sum_j P_j^T r_j,  r_i = f_i - m_i a_i - (K_dd q_d)_i
// with one k x k Cholesky factor (core/symmetric_solver.h). A's q_s block is singular too: scaling
// a0 by (1 + t) and a1..a3 by 1 / (1 + t) leaves s exactly unchanged (every taper, bend, shear and
// twist of (2.10)-(2.26) sees only e and the products a0 a_i), so along
// n = (a0, -a1, -a2, -a3, 0, ...) / |.| no force moves the shape but K_ss still pulls. That
// direction alone gets a fictitious inertia eta n n^T (BodyModel::parameter_inertia), sized when
// the Model is built so its oscillation under K_ss stays slow (omega dt <= 1/4); it is reported as
// kinetic energy 1/2 eta (n . q_s-dot)^2 and changes no shape. Likewise a bend's location and
// range weigh nothing while its amount is zero; every q_s entry therefore carries the inertia
// floor eta_i = k_s,i dt^2 (BodyModel::parameter_inertia_floor), so no mode of K_ss exceeds
// omega dt = 1; it is reported as kinetic energy too.
//
// Damping D = nu M (sec. 6.1) is the nodal force -nu m_i x_i-dot; first-order bodies (3.51) solve
// nu M q-dot = f_q - K q with the same machinery.
#pragma once

#include "core/types.h"
#include "deform/body_model.h"
#include "deform/body_workspace.h"

namespace pbm {

void resize_workspace(const BodyModel& body, BodyWorkspace& ws);

// Superquadric bodies: each node's basis at q_s from the powers of its latitude and longitude,
// computed once per distinct value (SignedPowers), into ws.basis.
void compute_node_bases(const BodyModel& body, const VecX& q_s, BodyWorkspace& ws);

// The superquadric's six parameters (the only shape every shipped scene uses): its blocks are
// fixed-size products Eigen keeps in registers, where the run-time loops below cost several times
// their arithmetic in the node loops of every step (issue 12, "A faster step").
inline constexpr Eigen::Index kSuperquadricParameters = 6;
using SuperquadricJt = Eigen::Matrix<Real, kSuperquadricParameters, 3>;

// out(0..n_s-1) += w J_i^T y. For other n_s, written out: n_s is small and known only at run time,
// where Eigen's dynamic products cost more than the arithmetic.
// Always inlined: called per node and per contact point in the hottest loops, where a call
// costs as much as the 18 products.
[[gnu::always_inline]] inline void add_Jt_y(const BodyWorkspace& ws, int i, const Vec3& y, Real w,
                                            Real* out) {
  const Eigen::Index ns = ws.Jt.rows();
  const Real* b = ws.Jt.data() + 3 * i * ns;
  const Vec3 wy = w * y;
  if (ns == kSuperquadricParameters) {
    Eigen::Map<Eigen::Matrix<Real, kSuperquadricParameters, 1>>(out).noalias() +=
        Eigen::Map<const SuperquadricJt>(b) * wy;
    return;
  }
  for (Eigen::Index k = 0; k < ns; ++k)
    out[k] += b[k] * wy[0] + b[ns + k] * wy[1] + b[2 * ns + k] * wy[2];
}

// J_i g for g of n_s entries.
[[gnu::always_inline]] inline Vec3 J_times(const BodyWorkspace& ws, int i, const Real* g) {
  const Eigen::Index ns = ws.Jt.rows();
  const Real* b = ws.Jt.data() + 3 * i * ns;
  if (ns == kSuperquadricParameters) {
    return Eigen::Map<const SuperquadricJt>(b).transpose() *
           Eigen::Map<const Eigen::Matrix<Real, kSuperquadricParameters, 1>>(g);
  }
  Real x = 0, y = 0, z = 0;
  for (Eigen::Index k = 0; k < ns; ++k) {
    x += b[k] * g[k];
    y += b[ns + k] * g[k];
    z += b[2 * ns + k] * g[k];
  }
  return Vec3(x, y, z);
}

// Fills R, q_s, s, p, p_dot, x, x_dot, J (and a_vp for second-order bodies) from the body's slices
// of q and v. q_s_rest must already hold the rest values in force.
// with_accelerations = false skips a_vp (and its second difference of s) where only velocities
// are needed.
void compute_body_kinematics(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                             const Eigen::Ref<const VecX>& v, BodyWorkspace& ws,
                             bool with_accelerations = true);

// Reference shape s at every node into ws.s (no Jacobian), reusing the cache when q_s is unchanged.
void compute_reference_positions(const BodyModel& body, const VecX& q_s, BodyWorkspace& ws);

// K_dd q_d into ws.K_q (zero for bodies without local DOFs).
void compute_elastic_forces(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                            BodyWorkspace& ws);

// Assembles and factors A (the k x k block) from the current kinematics, which must be those of
// q (the body's slice). A depends on q alone, so a factorization at bitwise the same q is reused
// (the contact pass factors the state the next step starts from).
void factor_generalized_mass(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                             BodyWorkspace& ws);

// g^T A^+ g for each column g of G (k x m) into out(0..m-1): the inverse of the effective mass a
// generalized force direction meets, e.g. g = P_i^T n for a push along n at node i. One matrix
// triangular solve for all columns. Needs the factored A; uses ws.contact_rotated.
void inverse_effective_masses(BodyWorkspace& ws, const Eigen::Ref<const MatX>& G,
                              Eigen::Ref<VecX> out);

// Given ws.force (external, world), returns the body's velocity derivative (second order:
// (c-ddot world, omega-dot body, q_s-ddot, d-ddot)) or, for first-order bodies, the velocity
// itself (3.51). Needs kinematics, elastic forces and the factored A.
void solve_body_dynamics(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                         const Eigen::Ref<const VecX>& v, BodyWorkspace& ws, Eigen::Ref<VecX> out);

// Moves the rigid/global part of d-dot into nu_g (sum m_i P_i^T d_i-dot = 0 again) without
// changing any node velocity x_i-dot. Needs kinematics and the factored A at this state.
void resplit_velocities(const BodyModel& body, const Eigen::Ref<const VecX>& q, Eigen::Ref<VecX> v,
                        BodyWorkspace& ws);

// After a substep: the mean-axis split's velocity form drifts between steps, so local bodies
// restore it (kinematics of (q, v), the mass block at q, resplit_velocities); the stage with
// obstacles does the same in resolve_penetrations (collide/rigid_contact.h), after its
// projection. Other bodies have no split to restore.
void restore_velocity_split(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                            Eigen::Ref<VecX> v, BodyWorkspace& ws);

// The position counterpart of resplit_velocities for translation: moves the mass-weighted mean
// of d into c (x_i unchanged exactly). The velocity condition alone is not integrable, so without
// this, projections at contacts accumulate a translation in q_d and c leaves the body.
// c-dot gains omega x (the shift), in the world frame, so no node's velocity changes either: the
// frame origin moved to another material point. Returns the shift (body frame).
Vec3 recenter_displacements(const BodyModel& body, Eigen::Ref<VecX> q, Eigen::Ref<VecX> v);

// P_i g = g_c + g_omega x p_i + J_i g_s: body-frame velocity of node i for a k-vector g.
Vec3 node_from_generalized(const BodyModel& body, const BodyWorkspace& ws, int i, const VecX& g);
// P_i^T y = (y, p_i x y, J_i^T y): the generalized force of a body-frame nodal force y.
VecX generalized_from_node(const BodyModel& body, const BodyWorkspace& ws, int i, const Vec3& y);

// Unit direction of q_s along which the reference shape does not change (see above).
VecX gauge_direction(const VecX& q_s);
void gauge_direction(const VecX& q_s, VecX& n);  // into n, allocation-free once n is sized

// x = A^+ y (pseudo-inverse on A's range), after factor_generalized_mass.
void solve_generalized_mass(BodyWorkspace& ws, const VecX& y, VecX& x);

// Energies and momenta from the current kinematics.
struct BodyEnergy {
  Real kinetic = 0;    // 1/2 sum m |x-dot|^2 + 1/2 eta |q_s-dot|^2
  Real elastic = 0;    // 1/2 (q_s - q_s0)^T K_ss (q_s - q_s0) + 1/2 q_d^T K_dd q_d   (3.31, 3.43)
  Real potential = 0;  // gravity: -sum m_i g . x_i
  Vec3 linear_momentum = Vec3::Zero();   // sum m x-dot
  Vec3 angular_momentum = Vec3::Zero();  // sum m x x x-dot (about the world origin)
};
BodyEnergy compute_body_energy(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                               const Eigen::Ref<const VecX>& v, const Vec3& gravity,
                               BodyWorkspace& ws);

}  // namespace pbm
