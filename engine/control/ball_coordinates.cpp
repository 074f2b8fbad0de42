#include "control/ball_coordinates.h"

#include <cmath>
#include <numbers>

namespace pbm {

Vec3 ball_rotation_vector(const Real* quaternion) {
  // With w >= 0 the half angle theta / 2 = atan2(|v|, w) lies in [0, pi / 2].
  const Real sign = quaternion[0] < 0 ? -1 : 1;
  const Real w = sign * quaternion[0];
  const Vec3 v = sign * Vec3(quaternion[1], quaternion[2], quaternion[3]);
  const Real s = v.norm();
  const Real half = std::atan2(s, w);
  // r = theta v / |v|; near rest, theta / |v| -> 2 / w (|q| may differ from 1 by rounding).
  if (s < 1e-12) return (2 / std::sqrt(w * w + s * s)) * v;
  return (2 * half / s) * v;
}

Mat3 ball_rate_map(const Vec3& r) {
  const Real theta = r.norm();
  const Mat3 K = skew(r);
  // The coefficient of [r]x^2, 1 / theta^2 - (1 + cos theta) / (2 theta sin theta), written
  // with (1 + cos theta) / sin theta = cot(theta / 2) so that it stays finite at pi; its series
  // 1/12 + theta^2 / 720 below 1e-4 rad, where the closed form loses digits to cancellation.
  const Real c =
      theta < 1e-4 ? 1.0 / 12 + theta * theta / 720
                   : 1 / (theta * theta) - std::cos(theta / 2) / (2 * theta * std::sin(theta / 2));
  return Mat3::Identity() + 0.5 * K + c * K * K;
}

Vec3 ball_rotation_vector_near(const Vec3& r, const Vec3& previous) {
  const Real theta = r.norm();
  if (theta < 1e-12) return r;
  const Vec3 other = r * (1 - 2 * std::numbers::pi / theta);
  return (other - previous).squaredNorm() < (r - previous).squaredNorm() ? other : r;
}

}  // namespace pbm
