// Eigen aliases and small fixed-size types used across the engine (docs/architecture.md,
// "Style").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pbm {

using Real = double;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;
// 3 x n_s Jacobian of the reference shape with respect to q_s (2.6).
using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;

// Skew-symmetric "dual" matrix p~ of (3.10): p~ y = p x y.
inline Mat3 skew(const Vec3& p) {
  Mat3 m;
  m << 0, -p.z(), p.y(), p.z(), 0, -p.x(), -p.y(), p.x(), 0;
  return m;
}

}  // namespace pbm
