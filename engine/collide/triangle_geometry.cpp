#include "collide/triangle_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pbm {
namespace {

// Relative size under which a vertex-plane distance is taken for 0 (see the header).
constexpr Real kPlaneSnap = 1e-12;

Real orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// c on the closed segment ab, given that the three are collinear.
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Real o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const Real o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
    return true;
  }
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

bool inside_closed(const std::array<Vec2, 3>& t, const Vec2& p) {
  const Real d0 = orientation(t[0], t[1], p), d1 = orientation(t[1], t[2], p),
             d2 = orientation(t[2], t[0], p);
  const bool has_negative = d0 < 0 || d1 < 0 || d2 < 0;
  const bool has_positive = d0 > 0 || d1 > 0 || d2 > 0;
  return !(has_negative && has_positive);
}

bool coplanar_intersect(const Vec3& normal, const std::array<Vec3, 3>& p,
                        const std::array<Vec3, 3>& q) {
  // Drop the normal's dominant axis: the projection keeps the triangles non-degenerate.
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  const int i0 = (axis + 1) % 3, i1 = (axis + 2) % 3;
  std::array<Vec2, 3> a, b;
  for (int k = 0; k < 3; ++k) {
    a[k] = Vec2(p[k][i0], p[k][i1]);
    b[k] = Vec2(q[k][i0], q[k][i1]);
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (segments_intersect(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
    }
  }
  return inside_closed(b, a[0]) || inside_closed(a, b[0]);
}

// The interval that a triangle cuts from the planes' common line, from the projections v of its
// vertices on the line and their signed distances d to the other plane (Moller's
// COMPUTE_INTERVALS). The vertex alone on its side comes first in isect.
std::array<Real, 2> isect(Real v0, Real v1, Real v2, Real d0, Real d1, Real d2) {
  const Real t0 = v0 + (v1 - v0) * d0 / (d0 - d1);
  const Real t1 = v0 + (v2 - v0) * d0 / (d0 - d2);
  return {std::min(t0, t1), std::max(t0, t1)};
}

// false when the triangle lies in the other plane (the caller then tests in 2D).
bool interval(const std::array<Real, 3>& v, const std::array<Real, 3>& d,
              std::array<Real, 2>& out) {
  if (d[0] * d[1] > 0) {
    out = isect(v[2], v[0], v[1], d[2], d[0], d[1]);
  } else if (d[0] * d[2] > 0) {
    out = isect(v[1], v[0], v[2], d[1], d[0], d[2]);
  } else if (d[1] * d[2] > 0 || d[0] != 0) {
    out = isect(v[0], v[1], v[2], d[0], d[1], d[2]);
  } else if (d[1] != 0) {
    out = isect(v[1], v[0], v[2], d[1], d[0], d[2]);
  } else if (d[2] != 0) {
    out = isect(v[2], v[0], v[1], d[2], d[0], d[1]);
  } else {
    return false;
  }
  return true;
}

// Signed distances (times |n|) of q to the plane through p0 with normal n; snapped near 0.
std::array<Real, 3> plane_distances(const Vec3& n, const Vec3& p0, const std::array<Vec3, 3>& q,
                                    Real snap) {
  std::array<Real, 3> d;
  for (int k = 0; k < 3; ++k) {
    d[k] = n.dot(q[k] - p0);
    if (std::abs(d[k]) <= snap) d[k] = 0;
  }
  return d;
}

bool same_side(const std::array<Real, 3>& d) {
  return (d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0);
}

}  // namespace

bool triangles_intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0,
                         const Vec3& q1, const Vec3& q2) {
  const std::array<Vec3, 3> p{p0, p1, p2}, q{q0, q1, q2};
  Real length = 0;
  for (int k = 0; k < 3; ++k) {
    length = std::max({length, (p[k] - p[(k + 1) % 3]).norm(), (q[k] - q[(k + 1) % 3]).norm()});
  }
  const Vec3 n1 = (p1 - p0).cross(p2 - p0);
  const std::array<Real, 3> dq = plane_distances(n1, p0, q, kPlaneSnap * n1.norm() * length);
  if (same_side(dq)) return false;
  const Vec3 n2 = (q1 - q0).cross(q2 - q0);
  const std::array<Real, 3> dp = plane_distances(n2, q0, p, kPlaneSnap * n2.norm() * length);
  if (same_side(dp)) return false;
  if ((dq[0] == 0 && dq[1] == 0 && dq[2] == 0) || (dp[0] == 0 && dp[1] == 0 && dp[2] == 0)) {
    return coplanar_intersect(n1.squaredNorm() >= n2.squaredNorm() ? n1 : n2, p, q);
  }
  // Project on the common line's dominant axis: the order along the line is kept.
  const Vec3 line = n1.cross(n2);
  int axis = 0;
  line.cwiseAbs().maxCoeff(&axis);
  const std::array<Real, 3> vp{p0[axis], p1[axis], p2[axis]}, vq{q0[axis], q1[axis], q2[axis]};
  std::array<Real, 2> a, b;
  if (!interval(vp, dp, a) || !interval(vq, dq, b)) {
    return coplanar_intersect(n1.squaredNorm() >= n2.squaredNorm() ? n1 : n2, p, q);
  }
  return a[0] <= b[1] && b[0] <= a[1];
}

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: which Voronoi region of the triangle holds p.
  TrianglePoint out;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    out.weights = Vec3(1, 0, 0);
    out.point = a;
    return out;
  }
  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) {
    out.weights = Vec3(0, 1, 0);
    out.point = b;
    return out;
  }
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const Real v = d1 / (d1 - d3);
    out.weights = Vec3(1 - v, v, 0);
    out.point = a + v * ab;
    return out;
  }
  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) {
    out.weights = Vec3(0, 0, 1);
    out.point = c;
    return out;
  }
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const Real w = d2 / (d2 - d6);
    out.weights = Vec3(1 - w, 0, w);
    out.point = a + w * ac;
    return out;
  }
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const Real w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    out.weights = Vec3(0, 1 - w, w);
    out.point = b + w * (c - b);
    return out;
  }
  const Real denom = 1 / (va + vb + vc);
  const Real v = vb * denom, w = vc * denom;
  out.weights = Vec3(1 - v - w, v, w);
  out.point = a + v * ab + w * ac;
  return out;
}

SegmentPoints closest_points_on_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                         const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  SegmentPoints out;
  if (a <= 0 && e <= 0) {
    out.on_p = p0;
    out.on_q = q0;
    return out;
  }
  Real s = 0, u = 0;
  if (a <= 0) {
    u = std::clamp(f / e, 0.0, 1.0);
  } else {
    const Real c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const Real b = d1.dot(d2);
      const Real denominator = a * e - b * b;  // >= 0, 0 when parallel
      s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      u = (b * s + f) / e;
      if (u < 0) {
        u = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (u > 1) {
        u = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  out.s = s;
  out.u = u;
  out.on_p = p0 + s * d1;
  out.on_q = q0 + u * d2;
  return out;
}

}  // namespace pbm
