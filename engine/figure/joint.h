// Joints of an articulated figure (sec. 15.1.1: up to six DOF, three translational and three
// rotational) in Featherstone's form (sec. 15.2.2; RBDA ch. 4): a joint transform X_J(q) from the
// joint's frame on the parent to the child's frame, a motion subspace S (6 x n_v, child
// coordinates) with the joint velocity v_J = S qdot, and the bias c_J = S-dot qdot.
//
// The book represents a multi-DOF joint as a chain of single-DOF ones; a spherical joint here is
// one 3-DOF joint on a unit quaternion instead (no gimbal lock, no massless links in the chain),
// and a universal joint one 2-DOF joint with its own bias.
#pragma once

#include <Eigen/Core>

#include "core/spatial.h"
#include "core/types.h"

namespace pbm {

enum class JointKind {
  revolute,   // 1 DOF: rotation by q [rad] about axis
  prismatic,  // 1 DOF: translation by q [m] along axis
  spherical,  // 3 DOF: q a unit quaternion (w, x, y, z) of child -> parent; v = omega (child)
  universal,  // 2 DOF: q0 about axis (parent), then q1 about axis2 (child) [rad]
  fixed,      // 0 DOF: the child welded to the parent
  free,       // 6 DOF: q = (position in the parent [m], unit quaternion); v = (omega, v_O) child
};

struct JointModel {
  JointKind kind = JointKind::revolute;
  Vec3 axis = Vec3::UnitZ();   // unit; revolute, prismatic, universal's first axis
  Vec3 axis2 = Vec3::UnitY();  // unit; universal's second axis
};

// Position and velocity sizes of a joint: its q (a quaternion takes 4) and its v (= DOF).
int joint_q_size(JointKind kind);
int joint_v_size(JointKind kind);

// The motion subspace S: 6 x n_v with n_v <= 6, stored inline (no allocation).
using MotionSubspace = Eigen::Matrix<Real, 6, Eigen::Dynamic, 0, 6, 6>;
// Joint-space vectors and blocks of one joint, n_v <= 6, inline.
using JointVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, 6, 1>;
using JointMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

// X_J(q) = child_X_joint (RBDA Table 4.1), q the joint's position coordinates.
SpatialTransform joint_transform(const JointModel& joint, const Real* q);

// S(q) in child coordinates (RBDA Table 4.1).
void joint_motion_subspace(const JointModel& joint, const Real* q, MotionSubspace& S);

// c_J = S-dot qdot (RBDA eq. 4.39 with a constant joint frame): zero but for the universal joint,
// whose first axis turns with the second angle.
MotionVector joint_bias(const JointModel& joint, const Real* q, const Real* qd);

// q-dot from the joint's velocity v: quaternion rates 1/2 q (x) (0, omega) (A.2) and, for the
// free joint, the position's rate R v_O (v_O is in child coordinates).
void joint_q_dot(const JointModel& joint, const Real* q, const Real* v, Real* q_dot);

// The joint's q at rest: zero angles and offsets, identity quaternions.
void joint_neutral(const JointModel& joint, Real* q);

// Unit quaternions again after a step (sec. 6.1 renormalization); other coordinates unchanged.
void joint_normalize(const JointModel& joint, Real* q);

}  // namespace pbm
