#include "figure/joint_space_inertia.h"

#include "figure/figure_kinematics.h"

namespace pbm {

void joint_space_inertia(const FigureModel& figure, const Real* q, FigureWorkspace& ws, MatX& H) {
  H.resize(figure.n_v, figure.n_v);
  joint_space_inertia(figure, q, ws, Eigen::Ref<MatX>(H));
}

void joint_space_inertia(const FigureModel& figure, const Real* q, FigureWorkspace& ws,
                         Eigen::Ref<MatX> H) {
  const int n = figure.size();
  figure_kinematics(figure, q, nullptr, ws);
  H.setZero();
  // Inward: each segment's composite inertia, the subtree it carries, in its own coordinates.
  for (int i = 0; i < n; ++i) ws.IA[i] = ws.inertia[i];
  for (int i = n - 1; i >= 0; --i) {
    const int parent = figure.segments[i].parent;
    if (parent >= 0) {
      add_inertia_to_parent(ws.X_up[i], ws.IA[i], ws.IA[parent]);
    }
  }
  // H_ii = S_i^T I^c_i S_i, and H_ji = S_j^T (j_X*_i I^c_i S_i) for each ancestor j.
  for (int i = 0; i < n; ++i) {
    const SegmentModel& segment = figure.segments[i];
    const int dof_i = static_cast<int>(ws.S[i].cols());
    if (dof_i == 0) continue;
    MotionSubspace F = ws.IA[i] * ws.S[i];
    H.block(segment.v_offset, segment.v_offset, dof_i, dof_i) = ws.S[i].transpose() * F;
    for (int j = i; figure.segments[j].parent >= 0;) {
      for (int k = 0; k < F.cols(); ++k) F.col(k) = transform_to_parent(ws.X_up[j], F.col(k));
      j = figure.segments[j].parent;
      const int dof_j = static_cast<int>(ws.S[j].cols());
      if (dof_j == 0) continue;
      const int row = figure.segments[j].v_offset;
      H.block(row, segment.v_offset, dof_j, dof_i) = ws.S[j].transpose() * F;
      H.block(segment.v_offset, row, dof_i, dof_j) =
          H.block(row, segment.v_offset, dof_j, dof_i).transpose();
    }
  }
}

}  // namespace pbm
