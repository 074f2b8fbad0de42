// Broadphase of the deformable-deformable collisions (sec. 5.2.2): one Bullet dynamic AABB tree
// (btDbvt) per body over its surface triangles, refitted every step.
//
// A triangle's leaf stores its box fattened by 2 margin (rounded outward to Bullet's float) and is
// reinserted only when the box fattened by 1 margin leaves it, so most steps move no leaf. The
// leaves' volumes therefore depend on the tree's history; to keep results a function of the state
// alone (docs/architecture.md, "Determinism": a rebuilt workspace must give the same bits), every
// pair the tree reports is re-checked against the current boxes fattened by 1 margin, in double,
// and the pairs are sorted. The reported set is thus exactly "current fattened boxes overlap",
// whatever the tree's shape or traversal order.
//
// Copying the structure gives an empty one (its trees are rebuilt on the next update): it is
// scratch, never State.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/types.h"

namespace pbm {

struct Box3 {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool overlaps(const Box3& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

struct SurfaceBroadphase {
  SurfaceBroadphase();
  ~SurfaceBroadphase();
  SurfaceBroadphase(const SurfaceBroadphase&);
  SurfaceBroadphase& operator=(const SurfaceBroadphase&);
  SurfaceBroadphase(SurfaceBroadphase&&) noexcept;
  SurfaceBroadphase& operator=(SurfaceBroadphase&&) noexcept;

  struct Trees;  // Bullet's trees, hidden so the engine's headers never include Bullet
  std::unique_ptr<Trees> trees;
  // Per body, per surface triangle: its current box fattened by 1 margin (world) [m].
  std::vector<std::vector<Box3>> boxes;
  std::vector<Box3> body_boxes;  // union of each body's triangle boxes
  int reinserted = 0;            // leaves moved in the last update (cost statistic)
};

// Sizes the trees for bodies with the given triangle counts (a no-op when they already match).
void resize_broadphase(const std::vector<int>& triangle_counts, SurfaceBroadphase& broadphase);

// Recomputes body's triangle boxes from the world node positions x and refits its tree.
void update_surface_tree(int body, const std::vector<Vec3>& x,
                         const std::vector<std::array<int, 3>>& triangles, Real margin,
                         SurfaceBroadphase& broadphase);

// The same over boxes that cover each triangle at both x_start and x (its sweep over a step whose
// nodes move on straight lines), for continuous collision detection (collide/self_collision.h).
void update_swept_surface_tree(int body, const std::vector<Vec3>& x_start,
                               const std::vector<Vec3>& x,
                               const std::vector<std::array<int, 3>>& triangles, Real margin,
                               SurfaceBroadphase& broadphase);

// Appends the triangle pairs (ta of body_a, tb of body_b) whose current fattened boxes overlap,
// sorted. body_a == body_b gives each unordered pair of distinct triangles once, ta < tb.
void collect_triangle_pairs(int body_a, int body_b, SurfaceBroadphase& broadphase,
                            std::vector<std::array<int, 2>>& pairs);

// The same pairs in the trees' traversal order, which depends on their insertion history (a
// workspace's, not the state's): for callers whose result does not depend on the order.
void collect_overlapping_triangles(int body_a, int body_b, SurfaceBroadphase& broadphase,
                                   std::vector<std::array<int, 2>>& pairs);

}  // namespace pbm
