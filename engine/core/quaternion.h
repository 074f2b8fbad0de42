// Unit quaternions for rigid-body orientation (Metaxas, sec. 3.1.1 and appendix A).
//
// A quaternion is a Vec4 q = (w, x, y, z) = (s, v): scalar part first, Hamilton product, unit
// length. It stands for the body -> world rotation R(q): R maps body-frame vectors to world-frame
// vectors, x_world = R x_body (3.7), and R(a (x) b) = R(a) R(b). q and -q are the same rotation.
// Angular velocities omega are in the body frame unless a name says otherwise.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "core/types.h"

namespace pbm {

// R(q), the body -> world rotation of q (3.7); q is normalized first, so any nonzero q works.
inline Mat3 rotation_from_quaternion(const Vec4& q) {
  const Vec4 n = q.normalized();
  const Real s = n[0], v1 = n[1], v2 = n[2], v3 = n[3];
  Mat3 R;  // (3.7)
  R << 1 - 2 * (v2 * v2 + v3 * v3), 2 * (v1 * v2 - s * v3), 2 * (v1 * v3 + s * v2),
      2 * (v1 * v2 + s * v3), 1 - 2 * (v1 * v1 + v3 * v3), 2 * (v2 * v3 - s * v1),
      2 * (v1 * v3 - s * v2), 2 * (v2 * v3 + s * v1), 1 - 2 * (v1 * v1 + v2 * v2);
  return R;
}

// q-dot = 1/2 q (x) (0, omega) for the body-frame angular velocity w = omega [rad/s]; q unit.
// q . q-dot = 0, so the rate keeps |q| = 1 to first order.
inline Vec4 quaternion_rate(const Vec4& q, const Vec3& w) {
  // 1/2 q (x) (0, omega): the inverse of omega = G q-dot (A.2, A.3) for a body-frame omega.
  const Real s = q[0], x = q[1], y = q[2], z = q[3];
  return 0.5 * Vec4(-x * w.x() - y * w.y() - z * w.z(), s * w.x() + y * w.z() - z * w.y(),
                    s * w.y() + z * w.x() - x * w.z(), s * w.z() + x * w.y() - y * w.x());
}

// Hamilton product a (x) b = (a_s b_s - a_v . b_v, a_s b_v + b_s a_v + a_v x b_v):
// the rotation "b, then a", R(a (x) b) = R(a) R(b).
inline Vec4 quaternion_product(const Vec4& a, const Vec4& b) {
  return Vec4(a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
              a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
              a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
              a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]);
}

// Conjugate q* = (s, -v); for a unit q it is the inverse rotation, R(q*) = R(q)^T.
inline Vec4 quaternion_conjugate(const Vec4& q) {
  return Vec4(q[0], -q[1], -q[2], -q[3]);
}

// The rotation by angle [rad] about axis (right-hand rule; axis normalized first, nonzero):
// (cos(angle / 2), sin(angle / 2) axis).
inline Vec4 quaternion_from_axis_angle(const Vec3& axis, Real angle) {
  const Vec3 u = axis.normalized();
  const Real half = Real(0.5) * angle;
  const Real s = std::sin(half);
  return Vec4(std::cos(half), s * u.x(), s * u.y(), s * u.z());
}

// The unit q with R(q) = R for a rotation matrix R (orthonormal, det 1), sign chosen so w >= 0.
// Shepperd's method: take the square root of the largest of 4 w^2, 4 x^2, 4 y^2, 4 z^2 (from the
// trace and the diagonal of R) and the other three components from off-diagonal sums and
// differences divided by it, so no division by a small number, even near 180 degrees.
inline Vec4 quaternion_from_rotation(const Mat3& R) {
  const Real trace = R(0, 0) + R(1, 1) + R(2, 2);
  Vec4 q;
  if (trace >= R(0, 0) && trace >= R(1, 1) && trace >= R(2, 2)) {
    const Real t = std::sqrt(1 + trace);  // t = 2 |w|
    q << Real(0.5) * t, (R(2, 1) - R(1, 2)) / (2 * t), (R(0, 2) - R(2, 0)) / (2 * t),
        (R(1, 0) - R(0, 1)) / (2 * t);
  } else if (R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2)) {
    const Real t = std::sqrt(1 + R(0, 0) - R(1, 1) - R(2, 2));  // t = 2 |x|
    q << (R(2, 1) - R(1, 2)) / (2 * t), Real(0.5) * t, (R(0, 1) + R(1, 0)) / (2 * t),
        (R(0, 2) + R(2, 0)) / (2 * t);
  } else if (R(1, 1) >= R(2, 2)) {
    const Real t = std::sqrt(1 - R(0, 0) + R(1, 1) - R(2, 2));  // t = 2 |y|
    q << (R(0, 2) - R(2, 0)) / (2 * t), (R(0, 1) + R(1, 0)) / (2 * t), Real(0.5) * t,
        (R(1, 2) + R(2, 1)) / (2 * t);
  } else {
    const Real t = std::sqrt(1 - R(0, 0) - R(1, 1) + R(2, 2));  // t = 2 |z|
    q << (R(1, 0) - R(0, 1)) / (2 * t), (R(0, 2) + R(2, 0)) / (2 * t),
        (R(1, 2) + R(2, 1)) / (2 * t), Real(0.5) * t;
  }
  if (q[0] < 0) q = -q;
  return q.normalized();
}

// R(q) v, the body-frame vector v in world coordinates (q (x) (0, v) (x) q*); q unit.
// Uses t = 2 q_v x v, R v = v + s t + q_v x t (no 3x3 matrix formed).
inline Vec3 rotate(const Vec4& q, const Vec3& v) {
  const Vec3 u(q[1], q[2], q[3]);
  const Vec3 t = 2 * u.cross(v);
  return v + q[0] * t + u.cross(t);
}

}  // namespace pbm
