// 6-D spatial vector algebra in Plücker coordinates, angular part first, as in Featherstone,
// "Rigid Body Dynamics Algorithms" (RBDA, 2008), chapter 2. Fixed-size Eigen types only: nothing
// here allocates.
//
// Frames: a spatial vector is expressed in one Cartesian frame A; its linear part refers to A's
// origin O (the velocity of the body-fixed point at O, the moment about O). A Plücker transform
// B_X_A takes the coordinates of the same vector from frame A to frame B.
// Units: SI throughout; motion [rad/s | m/s] (or /s^2 for accelerations), force [N m | N],
// inertia [kg m^2 | kg m | kg], and m . f is a power [W].
//
// To the project's body convention (core/quaternion.h, R = body -> world rotation, p = body origin
// in world): body_X_world = SpatialTransform{.E = R^T, .r = p}.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "core/types.h"

namespace pbm {

using Vec6 = Eigen::Matrix<Real, 6, 1>;
using Mat6 = Eigen::Matrix<Real, 6, 6>;

// ---------------------------------------------------------------------------------------------
// Spatial vectors

// Spatial motion vector m = [omega; v_O] (velocity, acceleration, joint axis).
struct MotionVector {
  Vec3 angular = Vec3::Zero();  // omega [rad/s]
  Vec3 linear = Vec3::Zero();   // v_O, velocity of the body-fixed point at the origin [m/s]
};

// Spatial force vector f = [n_O; f] (force, momentum, impulse).
struct ForceVector {
  Vec3 moment = Vec3::Zero();  // n_O, moment about the origin [N m]
  Vec3 force = Vec3::Zero();   // f, the resultant force [N]
};

// The 6 Plücker coordinates [angular; linear] and back.
inline Vec6 to_vec6(const MotionVector& m) {
  Vec6 out;
  out << m.angular, m.linear;
  return out;
}
inline Vec6 to_vec6(const ForceVector& f) {
  Vec6 out;
  out << f.moment, f.force;
  return out;
}
inline MotionVector motion_from_vec6(const Vec6& m) {
  return {m.head<3>(), m.tail<3>()};
}
inline ForceVector force_from_vec6(const Vec6& f) {
  return {f.head<3>(), f.tail<3>()};
}

// Vector space operations, within one space only (a motion plus a force does not compile).
inline MotionVector operator+(const MotionVector& a, const MotionVector& b) {
  return {a.angular + b.angular, a.linear + b.linear};
}
inline MotionVector operator-(const MotionVector& a, const MotionVector& b) {
  return {a.angular - b.angular, a.linear - b.linear};
}
inline MotionVector operator-(const MotionVector& a) {
  return {-a.angular, -a.linear};
}
inline MotionVector operator*(Real s, const MotionVector& a) {
  return {s * a.angular, s * a.linear};
}
inline MotionVector operator*(const MotionVector& a, Real s) {
  return s * a;
}
inline MotionVector& operator+=(MotionVector& a, const MotionVector& b) {
  a.angular += b.angular;
  a.linear += b.linear;
  return a;
}
inline MotionVector& operator-=(MotionVector& a, const MotionVector& b) {
  a.angular -= b.angular;
  a.linear -= b.linear;
  return a;
}

inline ForceVector operator+(const ForceVector& a, const ForceVector& b) {
  return {a.moment + b.moment, a.force + b.force};
}
inline ForceVector operator-(const ForceVector& a, const ForceVector& b) {
  return {a.moment - b.moment, a.force - b.force};
}
inline ForceVector operator-(const ForceVector& a) {
  return {-a.moment, -a.force};
}
inline ForceVector operator*(Real s, const ForceVector& a) {
  return {s * a.moment, s * a.force};
}
inline ForceVector operator*(const ForceVector& a, Real s) {
  return s * a;
}
inline ForceVector& operator+=(ForceVector& a, const ForceVector& b) {
  a.moment += b.moment;
  a.force += b.force;
  return a;
}
inline ForceVector& operator-=(ForceVector& a, const ForceVector& b) {
  a.moment -= b.moment;
  a.force -= b.force;
  return a;
}

// Scalar product m . f = omega . n_O + v_O . f, the power [W] of force f on motion m; defined
// only between a motion and a force, and invariant under coordinate change.
inline Real dot(const MotionVector& m, const ForceVector& f) {
  return m.angular.dot(f.moment) + m.linear.dot(f.force);
}

// ---------------------------------------------------------------------------------------------
// Spatial cross products (RBDA sec. 2.9, eqs. 2.31-2.33)

// v x m = [omega x m_omega; omega x m_v + v_O x m_omega], motion x motion (2.31-2.33): the rate
// of change of a motion vector m fixed in a body moving with velocity v.
inline MotionVector cross(const MotionVector& v, const MotionVector& m) {
  return {v.angular.cross(m.angular), v.angular.cross(m.linear) + v.linear.cross(m.angular)};
}

// v x* f = [omega x n + v_O x f; omega x f], motion x force (2.31-2.33): the rate of change of a
// force vector f fixed in a body moving with velocity v.
inline ForceVector cross(const MotionVector& v, const ForceVector& f) {
  return {v.angular.cross(f.moment) + v.linear.cross(f.force), v.angular.cross(f.force)};
}

// crm(v) = v x = [omega~ 0; v_O~ omega~], the 6x6 matrix of cross(v, m) (2.31-2.33).
inline Mat6 crm(const MotionVector& v) {
  Mat6 X;
  X << skew(v.angular), Mat3::Zero(), skew(v.linear), skew(v.angular);
  return X;
}

// crf(v) = v x* = [omega~ v_O~; 0 omega~] = -crm(v)^T, the 6x6 matrix of cross(v, f) (2.31-2.33).
inline Mat6 crf(const MotionVector& v) {
  Mat6 X;
  X << skew(v.angular), skew(v.linear), Mat3::Zero(), skew(v.angular);
  return X;
}

// ---------------------------------------------------------------------------------------------
// Plücker transforms (RBDA Table 2.2)

// B_X_A, the coordinate transform of spatial vectors from frame A to frame B:
//   X = rot(E) xlt(r) = [E 0; -E r~ E] on motions, X* = [E -E r~; 0 E] on forces.
// Default: the identity.
struct SpatialTransform {
  Mat3 E = Mat3::Identity();  // rotation taking 3-D coordinates from A to B, x_B = E (x_A - r)
  Vec3 r = Vec3::Zero();      // position of B's origin relative to A's, in A coordinates [m]
};

// X m = [E omega; E (v_O - r x omega)] (Table 2.2).
inline MotionVector transform_motion(const SpatialTransform& X, const MotionVector& m) {
  return {X.E * m.angular, X.E * (m.linear - X.r.cross(m.angular))};
}

// X* f = [E (n_O - r x f); E f] (Table 2.2).
inline ForceVector transform_force(const SpatialTransform& X, const ForceVector& f) {
  return {X.E * (f.moment - X.r.cross(f.force)), X.E * f.force};
}

// A_X_B = (B_X_A)^-1 = xlt(-r) rot(E^T) = (E^T, -E r).
inline SpatialTransform inverse(const SpatialTransform& X) {
  return {X.E.transpose(), -X.E * X.r};
}

// C_X_A = C_X_B B_X_A = (E_BC E_AB, r_AB + E_AB^T r_BC): the rotations compose and C's origin
// is B's plus r_BC taken back to A coordinates. Written X_BC * X_AB, as the matrices multiply.
inline SpatialTransform operator*(const SpatialTransform& X_BC, const SpatialTransform& X_AB) {
  return {X_BC.E * X_AB.E, X_AB.r + X_AB.E.transpose() * X_BC.r};
}

// The 6x6 matrix of X on motions, [E 0; -E r~ E] (Table 2.2).
inline Mat6 motion_matrix(const SpatialTransform& X) {
  Mat6 M;
  M << X.E, Mat3::Zero(), -X.E * skew(X.r), X.E;
  return M;
}

// The 6x6 matrix of X* on forces, [E -E r~; 0 E] = X^-T (Table 2.2).
inline Mat6 force_matrix(const SpatialTransform& X) {
  Mat6 M;
  M << X.E, -X.E * skew(X.r), Mat3::Zero(), X.E;
  return M;
}

// Coordinate rotations about A's x, y, z axis: B is A rotated by theta [rad] (right-hand rule),
// E = rx(theta), ry(theta), rz(theta) of Table 2.2 (the transpose of the active rotation).
inline SpatialTransform rot_x(Real theta) {
  const Real c = std::cos(theta), s = std::sin(theta);
  SpatialTransform X;
  X.E << 1, 0, 0, 0, c, s, 0, -s, c;
  return X;
}
inline SpatialTransform rot_y(Real theta) {
  const Real c = std::cos(theta), s = std::sin(theta);
  SpatialTransform X;
  X.E << c, 0, -s, 0, 1, 0, s, 0, c;
  return X;
}
inline SpatialTransform rot_z(Real theta) {
  const Real c = std::cos(theta), s = std::sin(theta);
  SpatialTransform X;
  X.E << c, s, 0, -s, c, 0, 0, 0, 1;
  return X;
}

// rot(E) = [E 0; 0 E]: pure rotation, E takes A coordinates to B coordinates (Table 2.2).
inline SpatialTransform rotation(const Mat3& E) {
  return {E, Vec3::Zero()};
}

// xlt(r) = [1 0; -r~ 1]: pure translation, B's origin at r in A coordinates [m] (Table 2.2).
inline SpatialTransform translation(const Vec3& r) {
  return {Mat3::Identity(), r};
}

// ---------------------------------------------------------------------------------------------
// Spatial inertia (RBDA eqs. 2.62-2.63)

// The spatial inertia of a rigid body, in the frame its c is expressed in:
//   I = [I_c + m c~ c~^T, m c~; m c~^T, m 1] (2.63).
// Default: zero (no body), the identity of operator+.
struct SpatialInertia {
  Real m = 0;               // mass [kg], >= 0
  Vec3 c = Vec3::Zero();    // centre of mass in this frame [m]
  Mat3 I_c = Mat3::Zero();  // rotational inertia about the centre of mass, symmetric [kg m^2]
};

// I v = [I_c omega + c x f; f] with f = m (v_O - c x omega): momentum of velocity v, or the force
// to produce acceleration v from rest (2.62-2.63, without forming the 6x6 matrix).
inline ForceVector operator*(const SpatialInertia& I, const MotionVector& v) {
  const Vec3 f = I.m * (v.linear - I.c.cross(v.angular));
  return {I.I_c * v.angular + I.c.cross(f), f};
}

// The 6x6 matrix (2.63).
inline Mat6 inertia_matrix(const SpatialInertia& I) {
  const Mat3 C = skew(I.c);
  Mat6 M;
  M << I.I_c + I.m * C * C.transpose(), I.m * C, I.m * C.transpose(), I.m * Mat3::Identity();
  return M;
}

// I_a + I_b for two bodies expressed in the same frame, rigidly joined (equal to the sum of the
// 6x6 matrices): the masses add, c is the mass-weighted mean, and each I_c moves to the new c by
// the parallel-axis theorem, I_c + m d~ d~^T with d = c_i - c. Two massless inertias give c = 0.
inline SpatialInertia operator+(const SpatialInertia& a, const SpatialInertia& b) {
  SpatialInertia sum;
  sum.m = a.m + b.m;
  if (sum.m > 0) sum.c = (a.m * a.c + b.m * b.c) / sum.m;
  const Mat3 Da = skew(a.c - sum.c), Db = skew(b.c - sum.c);
  sum.I_c = a.I_c + a.m * Da * Da.transpose() + b.I_c + b.m * Db * Db.transpose();
  return sum;
}

// B_I = B_X*_A A_I A_X_B, the inertia A_I of frame A expressed in frame B, X = B_X_A:
// m unchanged, c_B = E (c_A - r), I_c rotated to E I_c E^T.
inline SpatialInertia transform_inertia(const SpatialTransform& X, const SpatialInertia& I) {
  return {I.m, X.E * (I.c - X.r), X.E * I.I_c * X.E.transpose()};
}

// A point mass m [kg] at c [m].
inline SpatialInertia point_mass_inertia(Real m, const Vec3& c) {
  return {m, c, Mat3::Zero()};
}

// A homogeneous solid box of mass m [kg] and half_extents h [m] along the frame's axes (as in
// ObstacleDef), centred on the origin: I_c = m/3 diag(h_y^2 + h_z^2, h_x^2 + h_z^2, h_x^2 + h_y^2)
// (with sides a = 2 h, the familiar m (a_y^2 + a_z^2) / 12).
inline SpatialInertia solid_box_inertia(Real m, const Vec3& half_extents) {
  const Vec3 h2 = half_extents.cwiseProduct(half_extents);
  const Vec3 moments = m / 3 * Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y());
  return {m, Vec3::Zero(), moments.asDiagonal().toDenseMatrix()};
}

// A homogeneous solid sphere of mass m [kg] and radius [m], centred on the origin:
// I_c = 2/5 m radius^2 1.
inline SpatialInertia solid_sphere_inertia(Real m, Real radius) {
  return {m, Vec3::Zero(), Mat3::Identity() * (Real(2) / 5 * m * radius * radius)};
}

// A homogeneous solid cylinder of mass m [kg], radius and height [m], axis along the frame's z,
// centred on the origin: I_zz = m radius^2 / 2, I_xx = I_yy = m (3 radius^2 + height^2) / 12.
inline SpatialInertia solid_cylinder_inertia(Real m, Real radius, Real height) {
  const Real across = m * (3 * radius * radius + height * height) / 12;
  return {m, Vec3::Zero(),
          Vec3(across, across, m * radius * radius / 2).asDiagonal().toDenseMatrix()};
}

}  // namespace pbm
