#include "picking.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace pbm {

using Vec3f = Eigen::Vector3f;

Ray pixel_ray(const Camera& camera, float x, float y, int width, int height) {
  const Vec3f forward = (camera.target - camera.position).normalized();
  const Vec3f right = forward.cross(camera.up).normalized();
  const Vec3f up = right.cross(forward);
  const float tan_half = std::tan(0.5f * camera.fov * 3.14159265f / 180.0f);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float ndc_x = 2.0f * x / static_cast<float>(width) - 1.0f;
  const float ndc_y = 1.0f - 2.0f * y / static_cast<float>(height);
  const Vec3f d = forward + right * (ndc_x * tan_half * aspect) + up * (ndc_y * tan_half);
  return {camera.position, d.normalized()};
}

std::optional<Pick> pick_body(const draw::Snapshot& snapshot, const Ray& ray) {
  std::optional<Pick> best;
  std::vector<Vec3f> world;
  for (const draw::Mesh& mesh : snapshot.meshes) {
    if (mesh.pick < 0 || !mesh.positions || !mesh.topology) continue;
    world.clear();
    for (const Vec3f& x : *mesh.positions) world.push_back(mesh.rotation * x + mesh.offset);
    for (const std::array<int, 3>& t : mesh.topology->triangles) {
      const Vec3f& p0 = world[t[0]];
      const Vec3f e1 = world[t[1]] - p0, e2 = world[t[2]] - p0;
      const Vec3f h = ray.direction.cross(e2);
      const float det = e1.dot(h);
      if (std::abs(det) < 1e-12f) continue;
      const Vec3f s = ray.origin - p0;
      const float u = s.dot(h) / det;
      if (u < 0 || u > 1) continue;
      const Vec3f q = s.cross(e1);
      const float v = ray.direction.dot(q) / det;
      if (v < 0 || u + v > 1) continue;
      const float distance = e2.dot(q) / det;
      if (distance <= 0 || (best && distance >= best->distance)) continue;
      const float w[3] = {1 - u - v, u, v};
      const int corner = w[0] >= w[1] && w[0] >= w[2] ? 0 : (w[1] >= w[2] ? 1 : 2);
      best = Pick{mesh.pick, t[corner], ray.origin + distance * ray.direction, distance};
    }
  }
  return best;
}

namespace {

// Signed distance from p (the primitive's frame) to its surface (draw/snapshot.h's half_size).
float primitive_distance(const draw::Primitive& shape, const Vec3f& p) {
  const Vec3f& h = shape.half_size;
  switch (shape.shape) {
    case draw::PrimitiveShape::sphere:
      return p.norm() - h.x();
    case draw::PrimitiveShape::capsule: {
      const float z = std::clamp(p.z(), -h.z(), h.z());
      return (p - Vec3f(0, 0, z)).norm() - h.x();
    }
    case draw::PrimitiveShape::cylinder: {
      const Eigen::Vector2f d(p.head<2>().norm() - h.x(), std::abs(p.z()) - h.z());
      return std::min(d.maxCoeff(), 0.0f) + d.cwiseMax(0.0f).norm();
    }
    case draw::PrimitiveShape::box:
    default: {
      const Vec3f q = p.cwiseAbs() - h;
      return q.cwiseMax(0.0f).norm() + std::min(q.maxCoeff(), 0.0f);
    }
  }
}

}  // namespace

std::optional<FigurePick> pick_figure(const draw::Snapshot& snapshot, const Ray& ray) {
  std::optional<FigurePick> best;
  for (const draw::Primitive& shape : snapshot.primitives) {
    if (shape.figure < 0) continue;
    // Into the shape's frame, where its distance function is simple; the rotation keeps lengths,
    // so distances along the ray stay distances.
    const Eigen::Matrix3f to_local = shape.rotation.transpose();
    const Vec3f origin = to_local * (ray.origin - shape.center);
    const Vec3f direction = to_local * ray.direction;
    const float reach = shape.half_size.norm() * 2;  // a bound on the shape's extent
    // Skip shapes the ray passes wide of, and start the march near the shape.
    const float along = -origin.dot(direction);
    if ((origin + along * direction).norm() > reach) continue;
    float t = std::max(0.0f, along - reach);
    const float tolerance = 1e-5f * std::max(reach, 1e-3f);
    for (int k = 0; k < 256 && t <= along + reach; ++k) {
      const float d = primitive_distance(shape, origin + t * direction);
      if (d < tolerance) {
        if (!best || t < best->distance) {
          best = FigurePick{shape.figure, shape.segment, ray.origin + t * ray.direction, t};
        }
        break;
      }
      t += d;
    }
  }
  return best;
}

draw::Bounds pick_bounds(const draw::Snapshot& snapshot, int pick) {
  draw::Bounds bounds;
  for (const draw::Mesh& mesh : snapshot.meshes) {
    if (mesh.pick != pick || !mesh.positions) continue;
    for (const Vec3f& x : *mesh.positions) bounds.add(mesh.rotation * x + mesh.offset);
  }
  return bounds;
}

Vec3f drag_target(const Camera& camera, const Ray& ray, const Vec3f& point) {
  const Vec3f normal = (camera.target - camera.position).normalized();
  const float denom = ray.direction.dot(normal);
  if (std::abs(denom) < 1e-6f) return point;
  return ray.origin + ray.direction * ((point - ray.origin).dot(normal) / denom);
}

}  // namespace pbm
