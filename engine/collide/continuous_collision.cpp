#include "collide/continuous_collision.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "collide/triangle_geometry.h"

namespace pbm {
namespace {

Real evaluate_cubic(const std::array<Real, 4>& c, Real t) {
  return ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
}

// Root of the cubic in [lo, hi], where it is monotone and changes sign, by bisection: slower than
// Newton but never leaves the bracket, and 64 halvings reach the last bit of [0, 1].
Real bisect(const std::array<Real, 4>& c, Real lo, Real hi) {
  const bool rising = evaluate_cubic(c, lo) < 0;
  for (int k = 0; k < 64; ++k) {
    const Real mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if ((evaluate_cubic(c, mid) < 0) == rising) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return lo;
}

// Coefficients of (a(t) x b(t)) . e(t) with each vector linear in t: v(t) = v0 + t dv.
std::array<Real, 4> triple_product_cubic(const Vec3& a0, const Vec3& da, const Vec3& b0,
                                         const Vec3& db, const Vec3& e0, const Vec3& de) {
  const Vec3 n0 = a0.cross(b0);
  const Vec3 n1 = da.cross(b0) + a0.cross(db);
  const Vec3 n2 = da.cross(db);
  return {n0.dot(e0), n1.dot(e0) + n0.dot(de), n2.dot(e0) + n1.dot(de), n2.dot(de)};
}

FourPoints at_time(const FourPoints& x0, const FourPoints& x1, Real t) {
  FourPoints x;
  for (int k = 0; k < 4; ++k) x[k] = x0[k] + t * (x1[k] - x0[k]);
  return x;
}

// The normal's sign: against the relative approach over the step, else away from the second
// element at the start.
void orient(const FourPoints& x0, const FourPoints& x1, ContinuousContact& c) {
  Vec3 motion = Vec3::Zero(), start = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    motion += c.weights[k] * (x1[k] - x0[k]);
    start += c.weights[k] * x0[k];
  }
  const Real approach = c.normal.dot(motion);
  if (approach > 0 || (approach == 0 && c.normal.dot(start) < 0)) c.normal = -c.normal;
}

// A unit vector normal to a (or to a and b when they are parallel), for degenerate contacts.
Vec3 fallback_normal(const Vec3& a, const Vec3& b) {
  const Vec3 n = a.cross(b);
  if (n.norm() > 0) return n.normalized();
  if (a.norm() > 0) return a.unitOrthogonal();
  if (b.norm() > 0) return b.unitOrthogonal();
  return Vec3::UnitZ();
}

// Whether e is farther than tolerance from the plane spanned by a and b (the node from the
// face's plane, or the two edges' lines from each other): a lower bound of the elements'
// distance, cheap, so most candidate times need no closest points.
bool farther_than(const Vec3& a, const Vec3& b, const Vec3& e, Real tolerance) {
  const Vec3 n = a.cross(b);
  return std::abs(n.dot(e)) > tolerance * n.norm();
}

// At most 7 entries: an insertion sort (std::sort on a fixed-size array trips GCC 12's
// -Warray-bounds when built with -fsanitize=thread).
void insertion_sort(Real* v, int n) {
  for (int i = 1; i < n; ++i) {
    const Real x = v[i];
    int j = i;
    for (; j > 0 && v[j - 1] > x; --j) v[j] = v[j - 1];
    v[j] = x;
  }
}

}  // namespace

int coplanarity_candidate_times(const std::array<Real, 4>& c, std::array<Real, 7>& times) {
  // Turning points: roots of 3 c3 t^2 + 2 c2 t + c1 (the stable quadratic formula).
  std::array<Real, 4> breaks{};
  int n_breaks = 0;
  breaks[n_breaks++] = 0;
  const Real qa = 3 * c[3], qb = 2 * c[2], qc = c[1];
  auto add_break = [&](Real t) {
    if (t > 0 && t < 1) breaks[n_breaks++] = t;
  };
  if (qa == 0) {
    if (qb != 0) add_break(-qc / qb);
  } else {
    const Real discriminant = qb * qb - 4 * qa * qc;
    if (discriminant >= 0) {
      const Real q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
      add_break(q / qa);
      if (q != 0) add_break(qc / q);
    }
  }
  // Two turning points at most after 0 (std::sort here trips GCC 12's -Warray-bounds under TSan).
  if (n_breaks == 3 && breaks[2] < breaks[1]) std::swap(breaks[1], breaks[2]);
  int n = 0;
  auto add_time = [&](Real t) {
    if (n == 0 || times[n - 1] != t) times[n++] = t;
  };
  add_time(0);  // the step's ends: elements that start or end touching, coplanar or not
  for (int k = 0; k < n_breaks; ++k) {
    const Real lo = breaks[k];
    const Real hi = k + 1 < n_breaks ? breaks[k + 1] : 1.0;
    const Real f_lo = evaluate_cubic(c, lo), f_hi = evaluate_cubic(c, hi);
    if (k > 0) add_time(lo);  // a turning point (the closest approach to coplanarity) or a root
    if (f_lo != 0 && f_hi != 0 && (f_lo < 0) != (f_hi < 0)) add_time(bisect(c, lo, hi));
  }
  add_time(1);
  insertion_sort(times.data(), n);
  n = static_cast<int>(std::unique(times.begin(), times.begin() + n) - times.begin());
  return n;
}

ContinuousContact detect_node_face_collision(const FourPoints& x0, const FourPoints& x1,
                                             Real tolerance) {
  const std::array<Real, 4> cubic = triple_product_cubic(
      x0[2] - x0[1], (x1[2] - x1[1]) - (x0[2] - x0[1]), x0[3] - x0[1],
      (x1[3] - x1[1]) - (x0[3] - x0[1]), x0[0] - x0[1], (x1[0] - x1[1]) - (x0[0] - x0[1]));
  std::array<Real, 7> times{};
  const int n = coplanarity_candidate_times(cubic, times);
  ContinuousContact c;
  for (int k = 0; k < n; ++k) {
    const FourPoints x = at_time(x0, x1, times[k]);
    if (farther_than(x[2] - x[1], x[3] - x[1], x[0] - x[1], tolerance)) continue;
    const TrianglePoint y = closest_point_on_triangle(x[0], x[1], x[2], x[3]);
    const Real distance = (x[0] - y.point).norm();
    if (!(distance <= tolerance)) continue;
    c.hit = true;
    c.t = times[k];
    c.distance = distance;
    c.weights = {1.0, -y.weights[0], -y.weights[1], -y.weights[2]};
    c.normal = fallback_normal(x[2] - x[1], x[3] - x[1]);
    orient(x0, x1, c);
    return c;
  }
  return c;
}

ContinuousContact detect_edge_edge_collision(const FourPoints& x0, const FourPoints& x1,
                                             Real tolerance) {
  const std::array<Real, 4> cubic = triple_product_cubic(
      x0[1] - x0[0], (x1[1] - x1[0]) - (x0[1] - x0[0]), x0[3] - x0[2],
      (x1[3] - x1[2]) - (x0[3] - x0[2]), x0[2] - x0[0], (x1[2] - x1[0]) - (x0[2] - x0[0]));
  std::array<Real, 7> times{};
  const int n = coplanarity_candidate_times(cubic, times);
  ContinuousContact c;
  for (int k = 0; k < n; ++k) {
    const FourPoints x = at_time(x0, x1, times[k]);
    if (farther_than(x[1] - x[0], x[3] - x[2], x[2] - x[0], tolerance)) continue;
    const SegmentPoints p = closest_points_on_segments(x[0], x[1], x[2], x[3]);
    const Real distance = (p.on_p - p.on_q).norm();
    if (!(distance <= tolerance)) continue;
    c.hit = true;
    c.t = times[k];
    c.distance = distance;
    c.weights = {1 - p.s, p.s, -(1 - p.u), -p.u};
    c.normal = fallback_normal(x[1] - x[0], x[3] - x[2]);
    orient(x0, x1, c);
    return c;
  }
  return c;
}

}  // namespace pbm
