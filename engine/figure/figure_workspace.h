// Scratch of the figure's recursions, one entry per segment, sized once by size_figure_workspace
// (docs/architecture.md, "Allocation": a step allocates nothing). Nothing here outlives a call:
// every entry is recomputed from (q, v) by figure_kinematics.
#pragma once

#include <vector>

#include "core/spatial.h"
#include "figure/figure_model.h"
#include "figure/joint.h"

namespace pbm {

struct FigureWorkspace {
  // Forward kinematics (figure_kinematics).
  std::vector<SpatialTransform> X_up;  // child_X_parent = X_J X_tree (RBDA eq. 4.3)
  std::vector<MotionSubspace> S;       // motion subspace, child coordinates
  std::vector<Vec6> v;                 // segment velocity, segment coordinates
  std::vector<Vec6> c;                 // velocity-product acceleration c_J + v x v_J
  std::vector<Mat6> inertia;           // the segments' 6 x 6 spatial inertias (2.63), constant
  // A single-DOF joint's axis as a column of S (joint_axis_column): 0..5, or -1 off the
  // coordinate axes or for other joints; with its sign.
  std::vector<int> axis_column;
  std::vector<Real> axis_sign;
  // Recursions.
  std::vector<Vec6> a;             // segment acceleration
  std::vector<Vec6> f;             // RNEA's force; ABA's bias force p^A
  std::vector<Mat6> IA;            // articulated-body (ABA) or composite (CRBA) inertia
  std::vector<MotionSubspace> U;   // IA S
  std::vector<JointMatrix> D_inv;  // (S^T IA S)^-1
  std::vector<JointVector> u;      // tau - S^T p^A
};

void size_figure_workspace(const FigureModel& figure, FigureWorkspace& ws);

}  // namespace pbm
