#include "figure/joint.h"

#include <Eigen/Geometry>

#include "core/quaternion.h"

namespace pbm {
namespace {

// The active rotation by angle about a unit axis: child vectors to joint-frame vectors.
Mat3 axis_rotation(const Vec3& axis, Real angle) {
  return Eigen::AngleAxis<Real>(angle, axis).toRotationMatrix();
}

Vec4 quaternion_at(const Real* q) {
  return Vec4(q[0], q[1], q[2], q[3]);
}

}  // namespace

int joint_q_size(JointKind kind) {
  switch (kind) {
    case JointKind::revolute:
    case JointKind::prismatic:
      return 1;
    case JointKind::spherical:
      return 4;
    case JointKind::universal:
      return 2;
    case JointKind::fixed:
      return 0;
    case JointKind::free:
      return 7;
  }
  return 0;
}

int joint_v_size(JointKind kind) {
  switch (kind) {
    case JointKind::revolute:
    case JointKind::prismatic:
      return 1;
    case JointKind::spherical:
      return 3;
    case JointKind::universal:
      return 2;
    case JointKind::fixed:
      return 0;
    case JointKind::free:
      return 6;
  }
  return 0;
}

// The child's frame is the joint frame moved by the active rotation R (and translation r): a
// vector's coordinates go from the joint frame to the child's by E = R^T (core/spatial.h).
SpatialTransform joint_transform(const JointModel& joint, const Real* q) {
  switch (joint.kind) {
    case JointKind::revolute:
      return rotation(axis_rotation(joint.axis, q[0]).transpose());
    case JointKind::prismatic:
      return translation(joint.axis * q[0]);
    case JointKind::spherical:
      return rotation(rotation_from_quaternion(quaternion_at(q)).transpose());
    case JointKind::universal:
      return rotation(
          (axis_rotation(joint.axis, q[0]) * axis_rotation(joint.axis2, q[1])).transpose());
    case JointKind::fixed:
      return SpatialTransform{};
    case JointKind::free:
      return SpatialTransform{rotation_from_quaternion(quaternion_at(q + 3)).transpose(),
                              Vec3(q[0], q[1], q[2])};
  }
  return SpatialTransform{};
}

void joint_motion_subspace(const JointModel& joint, const Real* q, MotionSubspace& S) {
  S.setZero(6, joint_v_size(joint.kind));
  switch (joint.kind) {
    case JointKind::revolute:
      S.col(0).head<3>() = joint.axis;
      break;
    case JointKind::prismatic:
      S.col(0).tail<3>() = joint.axis;
      break;
    case JointKind::spherical:
      S.topRows<3>().setIdentity();
      break;
    case JointKind::universal:
      // omega = R2^T a1 qdot0 + a2 qdot1 in child coordinates: the first axis seen from the child.
      S.col(0).head<3>() = axis_rotation(joint.axis2, q[1]).transpose() * joint.axis;
      S.col(1).head<3>() = joint.axis2;
      break;
    case JointKind::fixed:
      break;
    case JointKind::free:
      S.setIdentity();
      break;
  }
}

MotionVector joint_bias(const JointModel& joint, const Real* q, const Real* qd) {
  MotionVector c;
  if (joint.kind == JointKind::universal) {
    // d/dt (R2^T a1) = -qdot1 a2 x R2^T a1, so S-dot qdot = qdot0 qdot1 (R2^T a1) x a2.
    const Vec3 first = axis_rotation(joint.axis2, q[1]).transpose() * joint.axis;
    c.angular = qd[0] * qd[1] * first.cross(joint.axis2);
  }
  return c;
}

void joint_q_dot(const JointModel& joint, const Real* q, const Real* v, Real* q_dot) {
  switch (joint.kind) {
    case JointKind::revolute:
    case JointKind::prismatic:
      q_dot[0] = v[0];
      return;
    case JointKind::universal:
      q_dot[0] = v[0];
      q_dot[1] = v[1];
      return;
    case JointKind::spherical: {
      Eigen::Map<Vec4> rate(q_dot);
      rate = quaternion_rate(quaternion_at(q), Vec3(v[0], v[1], v[2]));
      return;
    }
    case JointKind::fixed:
      return;
    case JointKind::free: {
      const Vec4 rotation_q = quaternion_at(q + 3);
      Eigen::Map<Vec3> position_rate(q_dot);
      Eigen::Map<Vec4> rotation_rate(q_dot + 3);
      position_rate = rotation_from_quaternion(rotation_q) * Vec3(v[3], v[4], v[5]);
      rotation_rate = quaternion_rate(rotation_q, Vec3(v[0], v[1], v[2]));
      return;
    }
  }
}

void joint_neutral(const JointModel& joint, Real* q) {
  for (int k = 0; k < joint_q_size(joint.kind); ++k) q[k] = 0;
  if (joint.kind == JointKind::spherical) q[0] = 1;
  if (joint.kind == JointKind::free) q[3] = 1;
}

void joint_normalize(const JointModel& joint, Real* q) {
  Real* quaternion = joint.kind == JointKind::spherical ? q
                     : joint.kind == JointKind::free    ? q + 3
                                                        : nullptr;
  if (quaternion != nullptr) Eigen::Map<Vec4>{quaternion}.normalize();
}

}  // namespace pbm
