// The outward pass every recursion starts with (RBDA Tables 5.1, 6.2, 7.1, first loop): for each
// segment, in parent-first order, X_up = X_J(q) X_tree, S(q), its velocity
// v_i = X_up v_parent + S qdot (the book's v_l = v_p + qdot_l s_l, sec. 15.2.2, in the child's
// coordinates) and its velocity-product acceleration c_i = c_J + v_i x v_J.
#pragma once

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// The inner loops' small kernels below are written on scalars: built from Vec3 expressions,
// GCC stores 3-vectors one double at a time and reloads them as SSE pairs, a store-forwarding
// stall per call that cost the recursions about a third of their time (pbm bench figures).

// The 6-D cross products on packed [angular; linear] vectors (core/spatial.h, RBDA 2.31-2.33):
// v x m = [w x m_w; w x m_v + v_O x m_w] and v x* f = [w x n + v_O x f; w x f].
inline Vec6 motion_cross(const Vec6& v, const Vec6& m) {
  const Real w0 = v[0], w1 = v[1], w2 = v[2], o0 = v[3], o1 = v[4], o2 = v[5];
  Vec6 out;
  out << w1 * m[2] - w2 * m[1], w2 * m[0] - w0 * m[2], w0 * m[1] - w1 * m[0],
      w1 * m[5] - w2 * m[4] + o1 * m[2] - o2 * m[1], w2 * m[3] - w0 * m[5] + o2 * m[0] - o0 * m[2],
      w0 * m[4] - w1 * m[3] + o0 * m[1] - o1 * m[0];
  return out;
}
inline Vec6 force_cross(const Vec6& v, const Vec6& f) {
  const Real w0 = v[0], w1 = v[1], w2 = v[2], o0 = v[3], o1 = v[4], o2 = v[5];
  Vec6 out;
  out << w1 * f[2] - w2 * f[1] + o1 * f[5] - o2 * f[4],
      w2 * f[0] - w0 * f[2] + o2 * f[3] - o0 * f[5], w0 * f[1] - w1 * f[0] + o0 * f[4] - o1 * f[3],
      w1 * f[5] - w2 * f[4], w2 * f[3] - w0 * f[5], w0 * f[4] - w1 * f[3];
  return out;
}

// X m and X^T f for X = child_X_parent = rot(E) xlt(r) on packed vectors: a motion (velocity,
// acceleration) of the parent in the child's coordinates, [E w; E (v - r x w)], and a force on
// the child in the parent's, [E^T n + r x E^T f; E^T f] (Table 2.2).
inline Vec6 transform_to_child(const SpatialTransform& X, const Vec6& m,
                               const Vec6& plus = Vec6::Zero()) {
  const Mat3& E = X.E;
  const Vec3& r = X.r;
  const Real w0 = m[0], w1 = m[1], w2 = m[2];
  const Real t0 = m[3] - (r[1] * w2 - r[2] * w1), t1 = m[4] - (r[2] * w0 - r[0] * w2),
             t2 = m[5] - (r[0] * w1 - r[1] * w0);
  Vec6 out;
  for (int i = 0; i < 3; ++i) {
    out[i] = E(i, 0) * w0 + E(i, 1) * w1 + E(i, 2) * w2 + plus[i];
    out[3 + i] = E(i, 0) * t0 + E(i, 1) * t1 + E(i, 2) * t2 + plus[3 + i];
  }
  return out;
}
inline void add_transform_to_parent(const SpatialTransform& X, const Vec6& f, Vec6& out) {
  const Mat3& E = X.E;
  const Vec3& r = X.r;
  Real g[3], n[3];
  for (int i = 0; i < 3; ++i) {
    g[i] = E(0, i) * f[3] + E(1, i) * f[4] + E(2, i) * f[5];
    n[i] = E(0, i) * f[0] + E(1, i) * f[1] + E(2, i) * f[2];
  }
  out[0] += n[0] + r[1] * g[2] - r[2] * g[1];
  out[1] += n[1] + r[2] * g[0] - r[0] * g[2];
  out[2] += n[2] + r[0] * g[1] - r[1] * g[0];
  out[3] += g[0];
  out[4] += g[1];
  out[5] += g[2];
}
inline Vec6 transform_to_parent(const SpatialTransform& X, const Vec6& f) {
  Vec6 out = Vec6::Zero();
  add_transform_to_parent(X, f, out);
  return out;
}

// The coordinate axis a single-DOF joint moves along, as a column of its 6 x 1 motion subspace:
// k (revolute about +-e_k) or 3 + k (prismatic along +-e_k), with the sign; -1 for an axis off
// the coordinate axes or a joint of another kind. ABA then reads U = I^A s as a column of I^A.
inline int joint_axis_column(const JointModel& joint, Real& sign) {
  if (joint.kind != JointKind::revolute && joint.kind != JointKind::prismatic) return -1;
  const Vec3& a = joint.axis;
  for (int k = 0; k < 3; ++k) {
    if (a[(k + 1) % 3] == 0 && a[(k + 2) % 3] == 0) {
      sign = a[k] > 0 ? 1 : -1;
      return joint.kind == JointKind::revolute ? k : 3 + k;
    }
  }
  return -1;
}

// out += X^T I X: a child's (articulated or composite) inertia I added to its parent's, X =
// child_X_parent. zero_row = k in 0..2 declares row and column k of I zero (the articulated
// inertia of a revolute joint about e_k once ABA has taken its freedom out, I^a s = 0), so they
// are skipped.
void add_inertia_to_parent(const SpatialTransform& X, const Mat6& I, Mat6& out, int zero_row = -1);

// q: n_q position coordinates; v: n_v velocities (nullptr: at rest, v and c zero).
void figure_kinematics(const FigureModel& figure, const Real* q, const Real* v,
                       FigureWorkspace& ws);

// The base's spatial acceleration that stands for gravity g (inertial frame): a_0 = -a_g
// = [0; -g] (RBDA sec. 5.3), so gravity costs nothing per segment.
inline Vec6 gravity_acceleration(const Vec3& gravity) {
  Vec6 a0;
  a0 << Vec3::Zero(), -gravity;
  return a0;
}

}  // namespace pbm
