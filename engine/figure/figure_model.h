// An articulated figure (sec. 15.1.1): a tree of rigid segments, each joined to its parent (or to
// the inertial frame) by its parent joint. Segments are numbered so that a parent comes before
// its children (Featherstone's regular numbering, RBDA sec. 4.1.2), which every recursion here
// relies on: outward passes run 0..n-1, inward passes n-1..0.
//
// Frames: a segment's frame is its local frame, at its root site (sec. 15.1.1). X_tree places the
// joint's frame on the parent: joint_X_parent (the parent's site), and the joint moves the child
// from there, child_X_parent = X_J(q) X_tree (RBDA eq. 4.3).
#pragma once

#include <string>
#include <vector>

#include "core/spatial.h"
#include "figure/joint.h"

namespace pbm {

struct SegmentModel {
  std::string name;
  int parent = -1;  // -1: the inertial frame
  JointModel joint;
  SpatialTransform X_tree;  // joint_X_parent: the joint's frame (a parent site) from the parent's
  SpatialInertia inertia;   // about the segment's frame; m > 0, I_c symmetric positive definite
  Real damping = 0;         // joint damping: tau = -damping qdot [N m s/rad or N s/m]
  // The joint's spring (figure/figure_def.h, JointDef::stiffness): its stiffness and rest q
  // (revolute, prismatic: rest[0]; universal: rest[0], rest[1]; spherical: a unit quaternion).
  Real stiffness = 0;
  Vec4 rest = Vec4(1, 0, 0, 0);
  int q_offset = 0;  // first entry of the joint's q in the figure's q
  int v_offset = 0;  // first entry of the joint's v in the figure's v
};

struct FigureModel {
  std::string name;
  std::vector<SegmentModel> segments;
  int n_q = 0;  // position coordinates (a quaternion counts 4)
  int n_v = 0;  // velocity coordinates, the figure's DOF
  // Where the figure's q and v sit in a World's State::q and State::v (set by sim/model.cpp).
  int state_q_offset = 0, state_v_offset = 0;

  int size() const { return static_cast<int>(segments.size()); }
};

// Checks the tree and the inertias and lays out q and v (the offsets, n_q, n_v). Throws
// pbm::Error naming `file` and the segment's path (`path`[i]) on a parent that is not an earlier
// segment, a mass that is not positive, an inertia that is not symmetric positive definite, or an
// axis that is not unit length.
void finalize_figure_model(FigureModel& figure, const std::string& file = {},
                           const std::string& path = "segments");

// The figure's q at rest: every joint's joint_neutral.
void figure_neutral_q(const FigureModel& figure, Real* q);

// q-dot from v, joint by joint (joint_q_dot); q_dot has n_q entries.
void figure_q_dot(const FigureModel& figure, const Real* q, const Real* v, Real* q_dot);

// Unit quaternions again (sec. 6.1).
void figure_normalize(const FigureModel& figure, Real* q);

}  // namespace pbm
