// Whether and how deep the nodes of one body's mesh in a snapshot lie inside another's closed
// surface, for tests of collisions between bodies (the meshes' positions are world: body meshes
// are not moved by rotation / offset).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "collide/triangle_geometry.h"
#include "sim/snapshot.h"

namespace pbm::test {

using V3 = Eigen::Vector3d;

inline V3 to_d(const draw::Vec3f& v) {
  return v.cast<double>();
}

// Closest distance from p to triangle abc (the engine's closest point, unit-tested in
// test_body_collisions' TriangleGeometry.ClosestPointRegions).
inline double point_triangle_distance(const V3& p, const V3& a, const V3& b, const V3& c) {
  return (p - closest_point_on_triangle(p, a, b, c).point).norm();
}

// Winding number of the closed surface around p (van Oosterom-Strackee solid angles / 4 pi):
// 1 inside, 0 outside, whatever the surface's convexity (a dented balloon stays closed).
inline double winding_number(const V3& p, const draw::Mesh& body) {
  const std::vector<draw::Vec3f>& x = *body.positions;
  double sum = 0;
  for (const auto& t : body.topology->triangles) {
    const V3 a = to_d(x[t[0]]) - p, b = to_d(x[t[1]]) - p, c = to_d(x[t[2]]) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)),
                          la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4 * std::numbers::pi);
}

// Deepest node of `a` inside `b`: the node's distance to b's surface [m], 0 if none is inside.
inline double penetration_depth(const draw::Mesh& a, const draw::Mesh& b) {
  const std::vector<draw::Vec3f>& xb = *b.positions;
  double worst = 0;
  for (const draw::Vec3f& xf : *a.positions) {
    const V3 x = to_d(xf);
    if (winding_number(x, b) < 0.5) continue;
    double d = 1e300;
    for (const auto& t : b.topology->triangles) {
      d = std::min(d, point_triangle_distance(x, to_d(xb[t[0]]), to_d(xb[t[1]]), to_d(xb[t[2]])));
    }
    worst = std::max(worst, d);
  }
  return worst;
}

}  // namespace pbm::test
