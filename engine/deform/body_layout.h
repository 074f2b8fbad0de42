// Where a body's coordinates sit in its slices of State::q and State::v (3.5). Every reader of a
// body's state names its blocks through these accessors instead of literal offsets:
//   q = (q_c (3), q_theta (4, quaternion w,x,y,z), q_s (n_s), q_d (3 n_nodes))
//   v = (c-dot (3, world), omega (3, BODY frame), q_s-dot (n_s), q_d-dot (3 n_nodes))
// A rigid body has n_s = 0 and no q_d; a global one no q_d (docs/architecture.md: a body pays
// only for its level). The angular velocity, not theta-dot, is the rotational velocity
// coordinate: with the quaternion's 4 rates M_theta,theta = int mu B^T B is singular
// (G q_theta = 0), so the quaternion is integrated kinematically, q_theta-dot = 1/2 q_theta (x)
// (0, omega), and renormalized after every step (sec. 6.1).
#pragma once

namespace pbm {

struct BodyLayout {
  int n_s = 0;  // global parameters in the state (0 for rigid bodies)
  int n_d = 0;  // local displacement entries: 3 n_nodes, or 0 without q_d

  static constexpr int kPosition = 0;    // q_c in q, c-dot in v
  static constexpr int kQuaternion = 3;  // q_theta in q
  static constexpr int kOmega = 3;       // omega in v
  static constexpr int kShapeInQ = 7;    // q_s in q
  static constexpr int kShapeInV = 6;    // q_s-dot in v
  static constexpr int kRigidQ = 7;      // q_c and q_theta
  static constexpr int kRigidV = 6;      // c-dot and omega

  int displacement_in_q() const { return kShapeInQ + n_s; }
  int displacement_in_v() const { return kShapeInV + n_s; }
  int q_size() const { return displacement_in_q() + n_d; }
  int v_size() const { return displacement_in_v() + n_d; }
  // Everything after the rigid block (q_s, q_d): the entries whose rate is their velocity.
  int q_after_rigid() const { return n_s + n_d; }
};

// Blocks of a body's own q (its State::q slice); Q is any Eigen vector expression.
template <class Q>
auto position_of(Q&& q) {
  return q.template segment<3>(BodyLayout::kPosition);
}
template <class Q>
auto quaternion_of(Q&& q) {
  return q.template segment<4>(BodyLayout::kQuaternion);
}
template <class Q>
auto shape_of(const BodyLayout& layout, Q&& q) {
  return q.segment(BodyLayout::kShapeInQ, layout.n_s);
}
template <class Q>
auto displacement_of(const BodyLayout& layout, Q&& q) {
  return q.segment(layout.displacement_in_q(), layout.n_d);
}

// Blocks of a body's own v (its State::v slice).
template <class V>
auto velocity_of(V&& v) {
  return v.template segment<3>(BodyLayout::kPosition);
}
template <class V>
auto omega_of(V&& v) {
  return v.template segment<3>(BodyLayout::kOmega);
}
template <class V>
auto shape_rate_of(const BodyLayout& layout, V&& v) {
  return v.segment(BodyLayout::kShapeInV, layout.n_s);
}
template <class V>
auto displacement_rate_of(const BodyLayout& layout, V&& v) {
  return v.segment(layout.displacement_in_v(), layout.n_d);
}

// Blocks of any vector in v's coordinates, a body's rates or a generalized force on its rigid and
// global block (k = 6 + n_s entries): the translational part (c-dot, a force; world frame in v),
// the rotational part (omega, a torque; body frame), and everything after the translation
// (omega and q_s-dot: the entries that keep their meaning when c-dot is taken to the body frame).
template <class V>
auto linear_part(V&& v) {
  return v.template segment<3>(BodyLayout::kPosition);
}
template <class V>
auto angular_part(V&& v) {
  return v.template segment<3>(BodyLayout::kOmega);
}
template <class V>
auto after_translation(V&& v, int k) {
  return v.segment(BodyLayout::kOmega, k - BodyLayout::kOmega);
}

}  // namespace pbm
