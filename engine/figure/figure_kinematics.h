// The outward pass every recursion starts with (RBDA Tables 5.1, 6.2, 7.1, first loop): for each
// segment, in parent-first order, X_up = X_J(q) X_tree, S(q), its velocity
// v_i = X_up v_parent + S qdot (the book's v_l = v_p + qdot_l s_l, sec. 15.2.2, in the child's
// coordinates) and its velocity-product acceleration c_i = c_J + v_i x v_J.
#pragma once

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// The 6-D cross products on packed [angular; linear] vectors (core/spatial.h, RBDA 2.31-2.33).
inline Vec6 motion_cross(const Vec6& v, const Vec6& m) {
  return to_vec6(cross(motion_from_vec6(v), motion_from_vec6(m)));
}
inline Vec6 force_cross(const Vec6& v, const Vec6& f) {
  return to_vec6(cross(motion_from_vec6(v), force_from_vec6(f)));
}

// X m and X^T f for X = child_X_parent on packed vectors: a motion (velocity, acceleration) of
// the parent in the child's coordinates, and a force on the child in the parent's.
inline Vec6 transform_to_child(const SpatialTransform& X, const Vec6& m) {
  return to_vec6(transform_motion(X, motion_from_vec6(m)));
}
inline Vec6 transform_to_parent(const SpatialTransform& X, const Vec6& f) {
  return to_vec6(transform_force(inverse(X), force_from_vec6(f)));
}

// out += X^T I X: a child's (articulated or composite) inertia I added to its parent's, X =
// child_X_parent.
void add_inertia_to_parent(const SpatialTransform& X, const Mat6& I, Mat6& out);

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
