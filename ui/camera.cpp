#include "camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace pbm {

Camera camera_from_view(const draw::CameraView& view) {
  Camera c;
  c.position = view.position;
  c.target = view.target;
  c.up = view.up;
  c.fov = std::clamp(view.fov, 1.0f, 179.0f);
  return c;
}

Camera frame_bounds(const draw::Bounds& bounds, float aspect) {
  Camera c;
  if (bounds.empty()) return c;
  const Eigen::Vector3f lo = bounds.min, hi = bounds.max;
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * (hi - lo).norm(), 0.1f);
  const float half_fov = 0.5f * c.fov * std::numbers::pi_v<float> / 180.0f;
  const float fit = std::min(std::tan(half_fov), std::tan(half_fov) * aspect);
  const float distance = 1.2f * radius / fit;
  const Eigen::Vector3f direction = Eigen::Vector3f(0.55f, -0.75f, 0.38f).normalized();
  c.target = centre;
  c.position = centre + distance * direction;
  return c;
}

Camera frame_focus(const draw::Snapshot& snapshot, float aspect) {
  return frame_bounds(snapshot.focus, aspect);
}

Eigen::Matrix4f view_matrix(const Camera& camera) {
  const Eigen::Vector3f f = (camera.target - camera.position).normalized();
  const Eigen::Vector3f s = f.cross(camera.up).normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(camera.position);
  m(1, 3) = -u.dot(camera.position);
  m(2, 3) = f.dot(camera.position);
  return m;
}

Eigen::Matrix4f perspective_matrix(float fov_degrees, float aspect, float near, float far) {
  const float t = 1.0f / std::tan(0.5f * fov_degrees * std::numbers::pi_v<float> / 180.0f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = t / aspect;
  m(1, 1) = t;
  m(2, 2) = (far + near) / (near - far);
  m(2, 3) = 2.0f * far * near / (near - far);
  m(3, 2) = -1.0f;
  return m;
}

Eigen::Matrix4f orthographic_matrix(float left, float right, float bottom, float top, float near,
                                    float far) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = 2.0f / (right - left);
  m(1, 1) = 2.0f / (top - bottom);
  m(2, 2) = -2.0f / (far - near);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

}  // namespace pbm
