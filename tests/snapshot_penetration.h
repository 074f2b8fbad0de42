// Whether and how deep the nodes of one body's snapshot lie inside another's closed surface, for
// tests of collisions between bodies.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/snapshot.h"

namespace pbm::test {

using V3 = Eigen::Vector3d;

inline V3 to_d(const Vec3f& v) {
  return v.cast<double>();
}

// Closest distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
inline double point_triangle_distance(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
}

// Winding number of the closed surface around p (van Oosterom-Strackee solid angles / 4 pi):
// 1 inside, 0 outside, whatever the surface's convexity (a dented balloon stays closed).
inline double winding_number(const V3& p, const BodySnapshot& body) {
  double sum = 0;
  for (const auto& t : body.triangles) {
    const V3 a = to_d(body.positions[t[0]]) - p, b = to_d(body.positions[t[1]]) - p,
             c = to_d(body.positions[t[2]]) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)),
                          la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4 * std::numbers::pi);
}

// Deepest node of `a` inside `b`: the node's distance to b's surface [m], 0 if none is inside.
inline double penetration_depth(const BodySnapshot& a, const BodySnapshot& b) {
  double worst = 0;
  for (const Vec3f& xf : a.positions) {
    const V3 x = to_d(xf);
    if (winding_number(x, b) < 0.5) continue;
    double d = 1e300;
    for (const auto& t : b.triangles) {
      d = std::min(d, point_triangle_distance(x, to_d(b.positions[t[0]]), to_d(b.positions[t[1]]),
                                              to_d(b.positions[t[2]])));
    }
    worst = std::max(worst, d);
  }
  return worst;
}

}  // namespace pbm::test
