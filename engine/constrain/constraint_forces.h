// The fast constraint-force computation of sec. 7.3: for k-bar point constraints among the parts,
// the 3 k-bar constraint forces f_c solve
//   N f_c + r = 0                                                                  (7.33)
// with N assembled block by block by the algorithm of sec. 7.3.2 (7.36)-(7.41):
//   N_lm = sum over the bodies i that constraints l and m share of s_l s_m L_l M_i^-1 L_m^T,
// s = +1 where the body is end a ("one") of the constraint and -1 where it is end b ("two"), and
//   r_l = (x-ddot_a - x-ddot_b)_free + 2 alpha C-dot_l + beta^2 C_l                 (7.24), (7.35)
// from Baumgarte's C-ddot + 2 alpha C-dot + beta^2 C = 0 (7.14), where "free" is the motion
// without constraint forces (L-dot q-dot + L M^-1 V of (7.24)). Each body then receives
// f_gc = sum s L^T f_c (7.9), (7.20), added to its rates as M^-1 f_gc.
//
// First-order bodies (3.51), (7.4): the same with velocities: N_lm from (nu M)^-1 and
//   r_l = (x-dot_a - x-dot_b)_free + alpha C_l,
// so C-dot = -alpha C and C = C(0) e^(-alpha t) (7.16) exactly. A constraint joins bodies of one
// order (checked in build_constraints), so one N serves both.
//
// N is symmetric positive semidefinite. It is solved by dense LU (Eigen PartialPivLU, as in the
// book) or, for loop-free systems, by a sparse LDL^T (Eigen SimplicialLDLT with AMD ordering,
// pattern analysed once): a tree's N has no fill-in beyond its blocks, so the cost is linear in
// k-bar. N gets eps I, eps = 1e-9 max N_ii: a hinge's two points (or any redundant set) make N
// singular, and the regularization picks a bounded force in its null space, which does no work.
#pragma once

#include <array>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "constrain/constraint_model.h"
#include "constrain/sparse_ldlt.h"
#include "deform/body_dynamics.h"

namespace pbm {

// Scratch of the constraint solve, sized once for the model (no allocation in a step besides the
// sparse factorization's own). Rebuildable at any time.
struct ConstraintWorkspace {
  int n_constraints = 0;  // k-bar
  bool sparse = false;    // which solver runs
  // Per constraint and end (a, b): G = L^T (k x 3, body frame rows, constraint_end_jacobian_
  // transpose) and Y = M^-1 G (second order) or (nu M)^-1 G (first order), k x 3.
  std::vector<std::array<MatX, 2>> G, Y;
  // Per body: the (constraint, end) pairs on it, end 0 = "one", 1 = "two" (7.36).
  std::vector<std::vector<std::array<int, 2>>> body_ends;
  VecX C;      // x_a - x_b per constraint [m] (3 k-bar)
  VecX C_dot;  // its rate [m/s]
  VecX r;      // (7.35) (3 k-bar)
  VecX f_c;    // constraint forces [N] (3 k-bar), on end a; end b gets -f_c
  MatX N;      // dense (3 k-bar)^2
  Eigen::PartialPivLU<MatX> lu;
  Eigen::SparseMatrix<Real> N_sparse;  // its pattern: the blocks of constraints sharing a body
  SparseLDLT ldlt;
  std::vector<VecX> column, response;          // per body, k: one column of G and of Y
  std::vector<VecX> hinge_force, hinge_delta;  // per body, k: hinge spring scratch
  VecX delta;                                  // k of the largest body
  Real regularization = 0;                     // eps of the last solve
};

void init_constraint_workspace(const ConstrainedSystem& system, ConstraintWorkspace& cw);

// Adds the hinge springs' and the constraint forces' response to `rates` (the whole v-dot of
// this evaluation: accelerations of second-order bodies, velocities of first-order ones, as
// solve_body_dynamics returned them). Needs every body's kinematics and factored A at (q, v).
void add_constraint_rates(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                          std::vector<BodyWorkspace>& bodies, ConstraintWorkspace& cw, VecX& rates);

// The parts of the solve that the projection after collisions (constrain/constraint_projection.h)
// shares with the forces: Y = M^-1 G ((nu M)^-1 G for first-order bodies) of every end from
// cw.G and the bodies' factored mass blocks; N assembled from G and Y by (7.37)-(7.41),
// regularized and factored; out = -N^-1 rhs with that factor (allocation-free).
void fill_end_responses(const ConstrainedSystem& system, std::vector<BodyWorkspace>& bodies,
                        ConstraintWorkspace& cw);
void factor_constraint_matrix(ConstraintWorkspace& cw);
void solve_constraint_matrix_negated(ConstraintWorkspace& cw, const VecX& rhs, VecX& out);

// |C_l| of every point constraint l [m] into violations (resized to their count) at the
// kinematics in `bodies`; returns max_l |C_l| (0 without constraints).
Real measure_constraint_violations(const ConstrainedSystem& system, const VecX& q,
                                   const std::vector<BodyWorkspace>& bodies, VecX& violations);

// Kinetic energy Baumgarte's feedback may legitimately add while parts assemble (for the
// stability guard): sum over constraints of (m_a + m_b) (alpha |C| + |C-dot|)^2, a bound on what
// pulling the violation shut at the rates of (7.14) gives the two bodies [J].
Real constraint_energy_allowance(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                                 const std::vector<BodyWorkspace>& bodies);

}  // namespace pbm
