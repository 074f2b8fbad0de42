#include "figure/figure_kinematics.h"

#include <cmath>

namespace pbm {

namespace {

// E^T M E for a symmetric M: T = M E, then the upper triangle of E^T T (its (r, c) entry is
// E.col(r) . T.col(c)), mirrored: 45 multiplications instead of 54. E may be N x 3 (N = 2: only
// the rows of E where M has non-zero rows and columns, add_inertia_to_parent's zero_row).
template <int N>
Mat3 rotate_symmetric(const Eigen::Matrix<Real, N, 3>& E, const Eigen::Matrix<Real, N, N>& M) {
  Eigen::Matrix<Real, N, 3> T;
  T.noalias() = M.lazyProduct(E);
  Mat3 out;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r <= c; ++r) out(r, c) = out(c, r) = E.col(r).dot(T.col(c));
  }
  return out;
}

// Rows of M crossed with r: (M r~)'s row j is m_j^T r~ = (m_j x r)^T.
inline Mat3 rows_cross(const Mat3& M, const Vec3& r) {
  Mat3 out;
  for (int j = 0; j < 3; ++j) out.row(j) = Vec3(M.row(j).transpose()).cross(r).transpose();
  return out;
}

// out += xlt(r)^T [A B; B^T C] xlt(r) = [A - B R + R B^T - R C R, B + R C; (B + R C)^T, C] with
// R = r~, the blocks already rotated to the parent's orientation. Since R^T = -R,
// R B^T = -(B R)^T, and R C R is symmetric: row and column cross products instead of 3 x 3
// products.
inline void add_translated(const Vec3& r, const Mat3& A, const Mat3& B, const Mat3& C, Mat6& out) {
  const Mat3 BR = rows_cross(B, r);
  Mat3 RC;  // column k is r x c_k
  for (int k = 0; k < 3; ++k) RC.col(k) = r.cross(Vec3(C.col(k)));
  const Mat3 RCR = rows_cross(RC, r);
  const Mat3 top_left = A - BR - BR.transpose() - RCR;
  const Mat3 top_right = B + RC;
  // Column by column in aligned pairs of rows (0, 1), (2, 3), (4, 5): the parent reads its
  // columns as SSE pairs right after (a chain's next segment), and a pair written as one store
  // forwards, where two halves from different blocks stall.
  using Pair = Eigen::Matrix<Real, 2, 1>;
  for (int c = 0; c < 3; ++c) {
    out.col(c).segment<2>(0) += Pair(top_left(0, c), top_left(1, c));
    out.col(c).segment<2>(2) += Pair(top_left(2, c), top_right(c, 0));
    out.col(c).segment<2>(4) += Pair(top_right(c, 1), top_right(c, 2));
    out.col(3 + c).segment<2>(0) += Pair(top_right(0, c), top_right(1, c));
    out.col(3 + c).segment<2>(2) += Pair(top_right(2, c), C(0, c));
    out.col(3 + c).segment<2>(4) += Pair(C(1, c), C(2, c));
  }
}

using Mat23 = Eigen::Matrix<Real, 2, 3>;

}  // namespace

// out += X^T I X for X = child_X_parent = rot(E) xlt(r) (core/spatial.h), without the 6 x 6
// products (432 multiplications): the blocks of I = [A B; B^T C] rotated by E (E^T A E,
// E^T B E, E^T C E), then translated.
void add_inertia_to_parent(const SpatialTransform& X, const Mat6& I, Mat6& out, int zero_row) {
  const Mat3& E = X.E;
  const Mat3 C = rotate_symmetric<3>(E, I.bottomRightCorner<3, 3>());
  if (zero_row < 0) {
    Mat3 T;
    T.noalias() = I.topRightCorner<3, 3>().lazyProduct(E);
    Mat3 B;
    B.noalias() = E.transpose().lazyProduct(T);
    add_translated(X.r, rotate_symmetric<3>(E, I.topLeftCorner<3, 3>()), B, C, out);
    return;
  }
  // Row and column k of A and row k of B are zero: only E's rows i, j take part, E^T A E =
  // E2^T A2 E2 and E^T B E = E2^T (B2 E) with E2, B2 those rows and A2 the 2 x 2 block that
  // remains (24 and 36 multiplications instead of 45 and 54).
  const int i = (zero_row + 1) % 3, j = (zero_row + 2) % 3;
  Mat23 E2;
  E2.row(0) = E.row(i);
  E2.row(1) = E.row(j);
  Eigen::Matrix<Real, 2, 2> A2;
  A2 << I(i, i), I(i, j), I(j, i), I(j, j);
  const Mat3 A = rotate_symmetric<2>(E2, A2);
  Mat23 B2;
  B2.row(0) = I.block<1, 3>(i, 3);
  B2.row(1) = I.block<1, 3>(j, 3);
  Mat23 T;
  T.noalias() = B2.lazyProduct(E);
  Mat3 B;
  B.noalias() = E2.transpose().lazyProduct(T);
  add_translated(X.r, A, B, C, out);
}

void size_figure_workspace(const FigureModel& figure, FigureWorkspace& ws) {
  const std::size_t n = figure.segments.size();
  ws.X_up.assign(n, SpatialTransform{});
  ws.S.assign(n, MotionSubspace());
  ws.axis_column.assign(n, -1);
  ws.axis_sign.assign(n, 1);
  ws.v.assign(n, Vec6::Zero());
  ws.c.assign(n, Vec6::Zero());
  ws.inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) ws.inertia[i] = inertia_matrix(figure.segments[i].inertia);
  ws.a.assign(n, Vec6::Zero());
  ws.f.assign(n, Vec6::Zero());
  ws.IA.assign(n, Mat6::Zero());
  // Sized per joint once, so ABA writes their entries without resizing.
  ws.U.resize(n);
  ws.D_inv.resize(n);
  ws.u.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const JointModel& joint = figure.segments[i].joint;
    const int dof = joint_v_size(joint.kind);
    ws.U[i].setZero(6, dof);
    ws.D_inv[i].setZero(dof, dof);
    ws.u[i].setZero(dof);
    // Only a universal joint's S depends on q (figure/joint.h); the others' are set here once,
    // with the axis a single-DOF joint moves along, and figure_kinematics leaves them.
    Real sign = 1;
    ws.axis_column[i] = joint_axis_column(joint, sign);
    ws.axis_sign[i] = sign;
    const Real rest[7] = {1, 0, 0, 0, 0, 0, 0};
    joint_motion_subspace(joint, rest, ws.S[i]);
  }
}

namespace {

// child_X_parent = X_J(q) X_tree. A revolute joint's X_J is the pure rotation rot(E_J), so the
// product is (E_J E_tree, r_tree); about a coordinate axis k, E_J (Table 2.2's rx, ry, rz) mixes
// only rows k + 1 and k + 2 of E_tree: 12 multiplications instead of 27 and a general rotation.
SpatialTransform up_transform(const SegmentModel& segment, const Real* q, int k, Real sign) {
  const JointModel& joint = segment.joint;
  if (joint.kind != JointKind::revolute) return joint_transform(joint, q) * segment.X_tree;
  if (k < 0) return {joint_transform(joint, q).E * segment.X_tree.E, segment.X_tree.r};
  const Real c = std::cos(q[0]), s = sign * std::sin(q[0]);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  SpatialTransform X = segment.X_tree;
  X.E.row(i) = c * segment.X_tree.E.row(i) + s * segment.X_tree.E.row(j);
  X.E.row(j) = c * segment.X_tree.E.row(j) - s * segment.X_tree.E.row(i);
  return X;
}

// v x (rate e_column) (motion_cross with a single nonzero entry): a revolute axis e_k (column
// k) gives [w x e_k; v_O x e_k] rate, a prismatic one (3 + k) [0; w x e_k] rate.
Vec6 axis_cross(const Vec6& v, int column, Real rate) {
  const int k = column % 3, i = (k + 1) % 3, j = (k + 2) % 3;
  // a x e_k = a_j e_i - a_i e_j.
  Vec6 out = Vec6::Zero();
  const int first = column < 3 ? 0 : 3;  // where w x e_k goes
  out[first + i] = v[j] * rate;
  out[first + j] = -v[i] * rate;
  if (column < 3) {
    out[3 + i] = v[3 + j] * rate;
    out[3 + j] = -v[3 + i] * rate;
  }
  return out;
}

}  // namespace

void figure_kinematics(const FigureModel& figure, const Real* q, const Real* v,
                       FigureWorkspace& ws) {
  for (int i = 0; i < figure.size(); ++i) {
    const SegmentModel& segment = figure.segments[i];
    const Real* q_i = q + segment.q_offset;
    const int column = ws.axis_column[i];
    ws.X_up[i] = up_transform(segment, q_i, column, ws.axis_sign[i]);
    if (segment.joint.kind == JointKind::universal) {
      joint_motion_subspace(segment.joint, q_i, ws.S[i]);
    }
    if (v == nullptr) {
      ws.v[i].setZero();
      ws.c[i].setZero();
      continue;
    }
    const Vec6 v_parent = segment.parent >= 0 ? ws.v[segment.parent] : Vec6::Zero();
    const Real* v_i = v + segment.v_offset;
    const int n_v = static_cast<int>(ws.S[i].cols());
    if (n_v == 0) {
      ws.v[i] = transform_to_child(ws.X_up[i], v_parent);
      ws.c[i].setZero();
      continue;
    }
    if (column >= 0) {
      // Along a coordinate axis, v_J = rate e_column and c = v x v_J has four terms.
      const Real rate = ws.axis_sign[i] * v_i[0];
      Vec6 v_J = Vec6::Zero();
      v_J[column] = rate;
      ws.v[i] = transform_to_child(ws.X_up[i], v_parent, v_J);
      ws.c[i] = axis_cross(ws.v[i], column, rate);
      continue;
    }
    // v_J = S qdot; a single column as a fixed-size vector (no dynamic-size product).
    Vec6 v_J = ws.S[i].col(0) * v_i[0];
    for (int k = 1; k < n_v; ++k) v_J += ws.S[i].col(k) * v_i[k];
    ws.v[i] = transform_to_child(ws.X_up[i], v_parent, v_J);
    ws.c[i] = motion_cross(ws.v[i], v_J);
    if (segment.joint.kind == JointKind::universal) {
      ws.c[i] += to_vec6(joint_bias(segment.joint, q_i, v_i));
    }
  }
}

}  // namespace pbm
