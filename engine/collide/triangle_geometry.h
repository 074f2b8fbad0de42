// Exact-predicate-free geometry of surface triangles for the deformable-deformable narrow phase
// (sec. 5.2.2, step 1: "we check if a polygon from the first model intersects with any polygons
// of the second model").
//
// triangles_intersect: Moller's interval test ("A fast triangle-triangle intersection test",
// 1997). The triangles are closed sets: touching at a point or along an edge counts as
// intersecting. Signed vertex-plane distances below 1e-12 of the pair's scale are snapped to 0,
// so a vertex lying on the other plane up to rounding is treated as on it; coplanar pairs fall
// back to a 2D edge-crossing and containment test in the plane's dominant projection.
//
// closest_point_on_triangle: the point y = w0 a + w1 b + w2 c of the closed triangle nearest to p
// (Voronoi regions of the vertices, edges and face), with w >= 0 and w0 + w1 + w2 = 1 exactly
// (w0 is computed as 1 - w1 - w2).
//
// closest_points_on_segments: the parameters s, u in [0, 1] of the nearest points
// p0 + s (p1 - p0) and q0 + u (q1 - q0) of two closed segments (Ericson, "Real-Time Collision
// Detection", 5.1.9); parallel segments take the lowest s that attains the distance.
#pragma once

#include "core/types.h"

namespace pbm {

bool triangles_intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0,
                         const Vec3& q1, const Vec3& q2);

struct TrianglePoint {
  Vec3 point = Vec3::Zero();    // world
  Vec3 weights = Vec3::Zero();  // barycentric, sum exactly 1
};
TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

struct SegmentPoints {
  Real s = 0, u = 0;                              // along p0 -> p1 and q0 -> q1, in [0, 1]
  Vec3 on_p = Vec3::Zero(), on_q = Vec3::Zero();  // the points, world
};
SegmentPoints closest_points_on_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                         const Vec3& q1);

}  // namespace pbm
