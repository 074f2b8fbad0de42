#include "figure/articulated_body.h"

#include <Eigen/Cholesky>

#include "figure/figure_kinematics.h"

namespace pbm {

void forward_dynamics(const FigureModel& figure, const Real* q, const Real* v, const Real* tau,
                      std::span<const ForceVector> f_ext, const Vec3& gravity, FigureWorkspace& ws,
                      Real* qdd, const Real* armature) {
  // Pass 1, outward: velocities and velocity products (figure_kinematics), then the rest.
  figure_kinematics(figure, q, v, ws);
  forward_dynamics_after_kinematics(figure, tau, f_ext, gravity, ws, qdd, armature);
}

void forward_dynamics_after_kinematics(const FigureModel& figure, const Real* tau,
                                       std::span<const ForceVector> f_ext, const Vec3& gravity,
                                       FigureWorkspace& ws, Real* qdd, const Real* armature) {
  const int n = figure.size();
  // The end of pass 1: each segment's own inertia and bias force p = v x* I v - f_ext as its
  // articulated ones to start from.
  for (int i = 0; i < n; ++i) {
    ws.IA[i] = ws.inertia[i];
    ws.f[i] = force_cross(ws.v[i], ws.inertia[i] * ws.v[i]);
    if (!f_ext.empty()) ws.f[i] -= to_vec6(f_ext[i]);
  }
  // Pass 2, inward: each segment's articulated inertia and bias force, with its joint's freedom
  // taken out, handed to its parent: I^a = I^A - U D^-1 U^T, p^a = p^A + I^a c + U D^-1 u.
  // I^A and p^A become I^a and p^a in place.
  for (int i = n - 1; i >= 0; --i) {
    const SegmentModel& segment = figure.segments[i];
    const MotionSubspace& S = ws.S[i];
    const int dof = static_cast<int>(S.cols());
    Mat6& Ia = ws.IA[i];
    Vec6& pa = ws.f[i];
    int zero_row = -1;
    if (dof == 1) {
      // A single axis s (revolute, prismatic): U = I^A s, D = s^T U a scalar. Along a coordinate
      // axis, s = +-e_k and U is a signed column of I^A.
      const Real sign = ws.axis_sign[i];
      const int k = ws.axis_column[i];
      Vec6 U;
      Real s_p;
      if (k >= 0) {
        U = sign * Ia.col(k);
        s_p = sign * pa[k];
      } else {
        U.noalias() = Ia * S.col(0);
        s_p = S.col(0).dot(pa);
      }
      const Real D =
          (k >= 0 ? sign * U[k] : S.col(0).dot(U)) + (armature ? armature[segment.v_offset] : 0);
      const Real D_inv = 1 / D;
      const Real u = tau[segment.v_offset] - s_p;
      ws.U[i].col(0) = U;
      ws.D_inv[i](0, 0) = D_inv;
      ws.u[i][0] = u;
      const Vec6 UD = D_inv * U;
      Ia.noalias() -= UD * U.transpose();
      pa += u * UD;
      if (k >= 0 && k < 3 && (!armature || armature[segment.v_offset] == 0)) {
        // I^a s = U - U D^-1 s^T U = 0 in exact arithmetic: row and column k vanish, and the
        // transform to the parent skips them (add_inertia_to_parent's zero_row). Not with an
        // armature a: D = s^T U + a and I^a s = U a / D.
        Ia.row(k).setZero();
        Ia.col(k).setZero();
        zero_row = k;
      }
    } else if (dof > 0) {
      ws.U[i].noalias() = Ia * S;
      JointMatrix D = S.transpose() * ws.U[i];
      if (armature) {
        for (int k = 0; k < dof; ++k) D(k, k) += armature[segment.v_offset + k];
      }
      // D = S^T I^A S is symmetric positive definite for a segment with mass and inertia
      // (finalize_figure_model); its inverse is at most 6 x 6.
      ws.D_inv[i] = D.llt().solve(JointMatrix::Identity(dof, dof));
      // tau - S^T p^A in two steps: the one-expression form makes a heap temporary of the Map's
      // dynamic type (tests/test_allocations.cpp).
      ws.u[i].noalias() = S.transpose() * pa;
      ws.u[i] = Eigen::Map<const VecX>(tau + segment.v_offset, dof) - ws.u[i];
      const MotionSubspace UD = ws.U[i] * ws.D_inv[i];
      Ia.noalias() -= UD * ws.U[i].transpose();
      pa.noalias() += UD * ws.u[i];
    }
    if (segment.parent < 0) continue;
    pa.noalias() += Ia * ws.c[i];
    add_inertia_to_parent(ws.X_up[i], Ia, ws.IA[segment.parent], zero_row);
    add_transform_to_parent(ws.X_up[i], pa, ws.f[segment.parent]);
  }
  // Pass 3, outward: accelerations, qddot = D^-1 (u - U^T a'), a = a' + S qddot.
  const Vec6 a0 = gravity_acceleration(gravity);
  for (int i = 0; i < n; ++i) {
    const SegmentModel& segment = figure.segments[i];
    const Vec6& a_parent = segment.parent >= 0 ? ws.a[segment.parent] : a0;
    ws.a[i] = transform_to_child(ws.X_up[i], a_parent, ws.c[i]);
    const int dof = static_cast<int>(ws.S[i].cols());
    if (dof == 0) continue;
    if (dof == 1) {
      // U . a on scalars: a was just written a double at a time (figure_kinematics.h).
      Real U_a = 0;
      for (int k = 0; k < 6; ++k) U_a += ws.U[i](k, 0) * ws.a[i][k];
      const Real qdd_i = ws.D_inv[i](0, 0) * (ws.u[i][0] - U_a);
      qdd[segment.v_offset] = qdd_i;
      const int k = ws.axis_column[i];
      if (k >= 0) {
        ws.a[i][k] += ws.axis_sign[i] * qdd_i;
      } else {
        ws.a[i] += qdd_i * ws.S[i].col(0);
      }
      continue;
    }
    Eigen::Map<VecX> qdd_i(qdd + segment.v_offset, dof);
    qdd_i = ws.D_inv[i] * (ws.u[i] - ws.U[i].transpose() * ws.a[i]);
    ws.a[i] += ws.S[i] * qdd_i;
  }
}

}  // namespace pbm
