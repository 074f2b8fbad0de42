// Continuous collision detection of surface elements over one step (Bridson, Fedkiw and Anderson
// 2002, "Robust treatment of collisions, contact and friction for cloth animation", sec. 6.4;
// Provot 1997): the four points of a node-triangle or edge-edge pair move on straight lines from
// x0 (the step's start) to x1 (its end), x(t) = x0 + t (x1 - x0), t in [0, 1]. They can touch only
// when the four are coplanar, (x_1 - x_0) x (x_2 - x_0) . (x_3 - x_0) = 0, a cubic in t. Its roots
// in [0, 1], found to rounding by bisection between the cubic's turning points (where it is
// monotone), are the candidate times; the turning points themselves are tried too, so a pair
// that grazes the plane without crossing it is not lost, and so are t = 0 and t = 1 (a pair
// ending the step touching counts: the surfaces are closed sets). At each candidate time in
// increasing order the distance between the elements is measured (closest points,
// triangle_geometry.h); the first one within tolerance is the contact. A pair that stays coplanar
// for the whole step (the cubic vanishes identically) is seen only at t = 0: in-plane motion is
// left to the proximity stage.
//
// Points: node-face: 0 the node, 1..3 the triangle (counter-clockwise from outside); edge-edge:
// 0-1 the first edge, 2-3 the second.
// Output weights c (sum 0): the relative position of the first element from the second at time
// t is sum_k c_k x_k(t); node-face (1, -w_1, -w_2, -w_3) with w the triangle's barycentric
// weights of the contact point, edge-edge (1 - s, s, -(1 - u), -u). The unit normal points so that
// the relative motion over the step approaches along -normal (n . sum c_k (x1_k - x0_k) <= 0): an
// impulse +j n on the first element and -j n on the second opposes the approach.
#pragma once

#include <array>

#include "core/types.h"

namespace pbm {

struct ContinuousContact {
  bool hit = false;
  Real t = 0;                     // time fraction of the first contact, in [0, 1]
  std::array<Real, 4> weights{};  // c_k above, at t
  Vec3 normal = Vec3::UnitZ();    // unit, world, at t (see above)
  Real distance = 0;              // between the elements at t [m]
};

using FourPoints = std::array<Vec3, 4>;

ContinuousContact detect_node_face_collision(const FourPoints& x0, const FourPoints& x1,
                                             Real tolerance);
ContinuousContact detect_edge_edge_collision(const FourPoints& x0, const FourPoints& x1,
                                             Real tolerance);

// 0, 1, the roots in [0, 1] of c[0] + c[1] t + c[2] t^2 + c[3] t^3 and its turning points
// there, sorted and unique, into times; returns how many (at most 7).
int coplanarity_candidate_times(const std::array<Real, 4>& c, std::array<Real, 7>& times);

}  // namespace pbm
