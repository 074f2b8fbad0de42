#include "figure/figure_kinematics.h"

namespace pbm {

// out += X^T I X for X = child_X_parent = rot(E) xlt(r) (core/spatial.h), without the 6 x 6
// products (432 multiplications): rotating the blocks of I = [A B; B^T C] by E, then the
// translation, xlt(r)^T I xlt(r) = [A - B R + R B^T - R C R, B + R C; (B + R C)^T, C] with
// R = r~ (R^T = -R).
void add_inertia_to_parent(const SpatialTransform& X, const Mat6& I, Mat6& out) {
  const Mat3& E = X.E;
  const Mat3 A = E.transpose() * I.topLeftCorner<3, 3>() * E;
  const Mat3 B = E.transpose() * I.topRightCorner<3, 3>() * E;
  const Mat3 C = E.transpose() * I.bottomRightCorner<3, 3>() * E;
  const Mat3 R = skew(X.r);
  const Mat3 RC = R * C;
  const Mat3 top_right = B + RC;
  out.topLeftCorner<3, 3>() += A - B * R + R * B.transpose() - RC * R;
  out.topRightCorner<3, 3>() += top_right;
  out.bottomLeftCorner<3, 3>() += top_right.transpose();
  out.bottomRightCorner<3, 3>() += C;
}

void size_figure_workspace(const FigureModel& figure, FigureWorkspace& ws) {
  const std::size_t n = figure.segments.size();
  ws.X_up.assign(n, SpatialTransform{});
  ws.S.assign(n, MotionSubspace());
  ws.v.assign(n, Vec6::Zero());
  ws.c.assign(n, Vec6::Zero());
  ws.inertia.resize(n);
  for (std::size_t i = 0; i < n; ++i) ws.inertia[i] = inertia_matrix(figure.segments[i].inertia);
  ws.a.assign(n, Vec6::Zero());
  ws.f.assign(n, Vec6::Zero());
  ws.IA.assign(n, Mat6::Zero());
  ws.U.assign(n, MotionSubspace());
  ws.D_inv.assign(n, JointMatrix());
  ws.u.assign(n, JointVector());
}

void figure_kinematics(const FigureModel& figure, const Real* q, const Real* v,
                       FigureWorkspace& ws) {
  for (int i = 0; i < figure.size(); ++i) {
    const SegmentModel& segment = figure.segments[i];
    const Real* q_i = q + segment.q_offset;
    ws.X_up[i] = joint_transform(segment.joint, q_i) * segment.X_tree;
    joint_motion_subspace(segment.joint, q_i, ws.S[i]);
    if (v == nullptr) {
      ws.v[i].setZero();
      ws.c[i].setZero();
      continue;
    }
    const int n_v = joint_v_size(segment.joint.kind);
    const Eigen::Map<const VecX> qd(v + segment.v_offset, n_v);
    const Vec6 v_J = ws.S[i] * qd;
    const Vec6 v_parent = segment.parent >= 0 ? ws.v[segment.parent] : Vec6::Zero();
    ws.v[i] = transform_to_child(ws.X_up[i], v_parent) + v_J;
    ws.c[i] =
        to_vec6(joint_bias(segment.joint, q_i, v + segment.v_offset)) + motion_cross(ws.v[i], v_J);
  }
}

}  // namespace pbm
