// BodyWorkspace: the scratch of one body's dynamics and contacts (deform/body_dynamics.h,
// collide/rigid_contact.h), sized once for its BodyModel (no allocation inside a step) and
// rebuildable at any time without changing a result (docs/architecture.md: determinism).
#pragma once

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>

#include "core/symmetric_solver.h"
#include "core/types.h"
#include "deform/body_model.h"
#include "deform/superquadric.h"

namespace pbm {

// The implicit membrane's scratch (deform/implicit_membrane.h), sized only when the scene's
// integrator is "implicit": the scalar K_dd, the factor of H = a M + b K (one per substep length,
// reused while it stays) and the dense columns of the k x k correction.
struct ImplicitMembraneWorkspace {
  // Eigen's factor cannot be copied; a copied workspace starts without one and factors on first
  // use, which gives the same numbers.
  struct Factor {
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt;
    bool analyzed = false;  // symbolic analysis of H's pattern done
    Real a = -1, b = -1;    // coefficients of the factored H (-1: none)
    Factor() = default;
    Factor(const Factor&) {}
    Factor& operator=(const Factor&) {
      analyzed = false;
      a = b = -1;
      return *this;
    }
  };
  Eigen::SparseMatrix<double> K;  // scalar K_dd (n x n); K_dd = K (x) I_3
  Eigen::SparseMatrix<double> H;  // a M + b K, same pattern as K plus the diagonal
  Factor factor;
  int factorizations = 0;  // numeric factorizations so far
  MatX columns;            // n x (4 + 3 n_s + 3): the distinct scalar fields of M P, then M g
  MatX solved;             // H^-1 of columns: Y and y0
  MatX scratch;            // columns' shape: the permuted right-hand sides
  MatX P;                  // 3 n x k: the rows P_i stacked (body frame)
  MatX Z;                  // 3 n x (k + 1): M (P - Y) and M (g - y0)
  MatX PtZ;                // k x (k + 1)
  MatX A_pinv;             // k x k: A^+
  MatX S;                  // k x k: I - A^+ P^T B Y
  Eigen::PartialPivLU<MatX> lu;
  VecX g, z, t3n;    // 3 n
  VecX mu, rhs, tk;  // k
  // The compliant contact (implicit_node_correction, collide/rigid_contact.cpp): the listed
  // nodes, their normals and amounts, and dense scratch for up to `capacity` of them, grown by
  // doubling so that a steady contact allocates nothing.
  std::vector<int> nodes, active, touching;
  std::vector<Vec3> normals, touching_normal;
  std::vector<Real> amounts;
  int capacity = 0;
  MatX unit, node_columns, scratch_columns;  // n x capacity: e_i, H_s^-1 e_i, permuted
  MatX system, global;                       // capacity x capacity
  MatX G, AG;                                // k x capacity: P_i^T n_i and A^+ of them
  VecX lambda, rhs_m;                        // capacity
  VecX change;                               // 3 n: the local change
  VecX dnu;                                  // k: the generalized change
};

// The implicit integrator's contact (collide/implicit_contact.h), sized only under "implicit": per
// candidate point of the global surface, its direction g_p in the rigid + global rows, e_p and
// beta_p of its end force f_p = e_p - beta_p g_p^T x, and whether it is in the active set.
struct ImplicitContactWorkspace {
  bool on = false;
  int candidates = 0;              // points of this evaluation
  int rounds = 0;                  // active-set rounds of the last solve
  MatX G;                          // k x samples
  VecX excess, weight, end_force;  // e_p, beta_p, f_p
  std::vector<char> active;
  MatX system, scratch;  // k x k; k x samples
  Eigen::LDLT<MatX> factor;
  VecX rhs, fallback;  // k
};

// Per-body scratch, sized once (no allocation inside a step). Rebuildable at any time.
struct BodyWorkspace {
  Mat3 R = Mat3::Identity();  // body -> world rotation (3.7)
  VecX q_s;                   // current global parameters (n_shape)
  VecX q_s_rest;              // rest values after tracks (n_shape)
  std::vector<Vec3> s;        // reference shape at each node, body frame
  std::vector<Vec3> p;        // s + d, body frame
  std::vector<Vec3> p_dot;    // J q_s-dot + d-dot, body frame
  std::vector<Vec3> a_vp;     // velocity-product acceleration a_i (3.18), body frame
  std::vector<Vec3> x;        // world positions
  std::vector<Vec3> x_dot;    // world velocities
  std::vector<Vec3> force;    // external nodal forces, world frame [N]
  // Collision forces (5.11, 5.12) on the rigid + global rows (c in the body frame, theta, q_s),
  // k entries (see collide/rigid_contact.h).
  VecX contact_generalized;
  // Contact scratch: P^T y of each pressing point's direction (k x points, grown on demand),
  // V^T times it, and per point a force and an inverse effective mass.
  MatX contact_directions, contact_rotated;
  VecX contact_magnitude, contact_mobility;
  // Contact scratch (collide/rigid_contact.cpp): per node, the signed distance of c + R s_i;
  // the samples of the global surface inside an obstacle.
  std::vector<Real> surface_distance;
  struct PressingPoint {
    int sample = 0, obstacle = 0;
    Real phi = 0;
    Vec3 s = Vec3::Zero(), n = Vec3::Zero();  // body frame point, world normal
  };
  std::vector<PressingPoint> pressing;
  struct SlipPoint {
    int sample = 0;
    Real speed = 0, share = 0, limit = 0;     // slip speed, stiffness share, beta_f |f_n|
    Vec3 s = Vec3::Zero(), t = Vec3::Zero();  // body frame point and slip direction
  };
  std::vector<SlipPoint> slipping;
  std::vector<int> penetrating;  // nodes inside an obstacle after a step
  std::vector<int> contact;      // per node: index of the obstacle touched, or -1
  // J_i^T of (2.6) for every node, n_s x 3 n_nodes: node i's block is columns 3i..3i+2, one
  // contiguous n_s x 3 run (see add_Jt_y and J_times).
  MatX Jt;
  Mat3X J_node;                                  // 3 x n_shape scratch
  std::vector<SuperquadricBasis> basis;          // superquadric bodies: per node, with s and J
  std::vector<SignedPowers> u_powers, v_powers;  // per BodyModel::grid_u / grid_v entry
  // The same for the contact samples' grid, filled on demand: an entry is current when its stamp
  // equals sample_stamp (advanced whenever q_s may have changed).
  std::vector<SignedPowers> sample_u_powers, sample_v_powers;
  std::vector<unsigned> sample_u_stamp, sample_v_stamp;
  unsigned sample_stamp = 0;
  VecX K_q;                       // K_dd q_d, body frame (3 n_nodes)
  MatX A;                         // k x k mass block of the generalized rigid+global coordinates
  SymmetricSolver A_solver;       // A^+ (Cholesky, or the pseudo-inverse where A is singular)
  VecX r_g, b, gamma, alpha;      // k-vectors
  MatX mass_J, mass_pJ;           // sum m J_i, sum m p~_i J_i (3 x n_s)
  MatX mass_JtJ;                  // sum m J_i^T J_i (n_s x n_s)
  VecX node_mass_3;               // node masses repeated per coordinate (3 n_nodes)
  MatX mass_Jt;                   // Jt diag(node_mass_3), n_s x 3 n_nodes
  VecX mass_pJ_a, mass_pJ_b;      // n_s: the two products of a row of mass_pJ
  VecX q_s_dot, q_plus, q_minus;  // n_s: q_s-dot and q_s +- h q_s-dot (kinematics)
  VecX gauge, gauge_scaled;       // n_s: the gauge direction n and eta n
  VecX shape_scratch;             // n_s
  bool kinematics_valid = false;
  // s and J depend on q_s alone: they are reused while q_s is bitwise unchanged (the contact
  // pass and the next step's first evaluation see the q_s the integrator produced).
  VecX shape_key;  // q_s at which s (and J if shape_has_J) were evaluated
  VecX mass_key;   // body q at which A was last factored (empty = none)
  bool shape_has_J = false;
  std::vector<Vec3> d_dot_body;  // d-dot per node, body frame (zero without q_d)
  Vec3 omega = Vec3::Zero();     // angular velocity, body frame
  Real dt = 0;                   // substep in progress (rate-based contact damping, implicit)
  // A body of level "auto" with its displacements off this frame: a copy of State::dormant,
  // set at each frame's start (sim/level_of_detail.h). Its q_d and d-dot are zero and stay so.
  bool dormant = false;
  ImplicitMembraneWorkspace implicit;         // empty unless the integrator is "implicit"
  ImplicitContactWorkspace implicit_contact;  // the same
  const Vec3& d_dot(const BodyModel&, int i) const { return d_dot_body[i]; }
};

}  // namespace pbm
