#include "collide/surface_broadphase.h"

#include <BulletCollision/BroadphaseCollision/btDbvt.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pbm {

struct SurfaceBroadphase::Trees {
  std::vector<std::unique_ptr<btDbvt>> tree;         // per body
  std::vector<std::vector<btDbvtNode*>> leaf;        // per body, per triangle
  std::vector<std::vector<std::array<int, 2>>> raw;  // scratch of collect_triangle_pairs
};

SurfaceBroadphase::SurfaceBroadphase() : trees(std::make_unique<Trees>()) {}
SurfaceBroadphase::~SurfaceBroadphase() = default;
SurfaceBroadphase::SurfaceBroadphase(const SurfaceBroadphase&) : trees(std::make_unique<Trees>()) {}
SurfaceBroadphase& SurfaceBroadphase::operator=(const SurfaceBroadphase& other) {
  if (this != &other) *this = SurfaceBroadphase();
  return *this;
}
SurfaceBroadphase::SurfaceBroadphase(SurfaceBroadphase&&) noexcept = default;
SurfaceBroadphase& SurfaceBroadphase::operator=(SurfaceBroadphase&&) noexcept = default;

namespace {

// Bullet stores floats: round each bound outward so the stored box contains the double one.
btDbvtVolume to_bullet(const Box3& box) {
  auto down = [](Real x) {
    return std::nextafter(static_cast<btScalar>(x), -std::numeric_limits<btScalar>::infinity());
  };
  auto up = [](Real x) {
    return std::nextafter(static_cast<btScalar>(x), std::numeric_limits<btScalar>::infinity());
  };
  return btDbvtVolume::FromMM(btVector3(down(box.lo.x()), down(box.lo.y()), down(box.lo.z())),
                              btVector3(up(box.hi.x()), up(box.hi.y()), up(box.hi.z())));
}

bool contains(const btDbvtVolume& stored, const Box3& box) {
  const btVector3& lo = stored.Mins();
  const btVector3& hi = stored.Maxs();
  for (int k = 0; k < 3; ++k) {
    if (!(lo[k] <= box.lo[k] && box.hi[k] <= hi[k])) return false;
  }
  return true;
}

struct PairCollector : btDbvt::ICollide {
  std::vector<std::array<int, 2>>* out = nullptr;
  void Process(const btDbvtNode* a, const btDbvtNode* b) override {
    out->push_back({a->dataAsInt, b->dataAsInt});
  }
};

}  // namespace

void resize_broadphase(const std::vector<int>& triangle_counts, SurfaceBroadphase& broadphase) {
  SurfaceBroadphase::Trees& t = *broadphase.trees;
  bool same = t.tree.size() == triangle_counts.size();
  for (std::size_t b = 0; same && b < triangle_counts.size(); ++b) {
    same = static_cast<int>(t.leaf[b].size()) == triangle_counts[b];
  }
  if (same) return;
  const std::size_t n = triangle_counts.size();
  t.tree.clear();
  t.leaf.assign(n, {});
  t.raw.assign(1, {});
  broadphase.boxes.assign(n, {});
  broadphase.body_boxes.assign(n, Box3{});
  for (std::size_t b = 0; b < n; ++b) {
    t.tree.push_back(std::make_unique<btDbvt>());
    // The traversal's persistent stack, sized now so that a first overlap inside a step does not
    // allocate (it still doubles if ever too small).
    t.tree.back()->m_stkStack.reserve(std::max(256, 4 * triangle_counts[b]));
    t.leaf[b].assign(static_cast<std::size_t>(triangle_counts[b]), nullptr);
    broadphase.boxes[b].assign(static_cast<std::size_t>(triangle_counts[b]), Box3{});
  }
}

void update_swept_surface_tree(int body, const std::vector<Vec3>& x_start,
                               const std::vector<Vec3>& x,
                               const std::vector<std::array<int, 3>>& triangles, Real margin,
                               SurfaceBroadphase& broadphase) {
  SurfaceBroadphase::Trees& t = *broadphase.trees;
  btDbvt& tree = *t.tree[body];
  std::vector<Box3>& boxes = broadphase.boxes[body];
  Box3& whole = broadphase.body_boxes[body];
  whole = Box3{};
  const Vec3 fat = Vec3::Constant(margin);
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    Box3 box;
    for (int v : triangles[k]) {
      box.add(x_start[v]);
      box.add(x[v]);
    }
    box.lo -= fat;
    box.hi += fat;
    boxes[k] = box;
    whole.add(box.lo);
    whole.add(box.hi);
    btDbvtNode*& leaf = t.leaf[body][k];
    if (leaf != nullptr && contains(leaf->volume, box)) continue;
    Box3 stored = box;  // room for another margin of motion before the next reinsertion
    stored.lo -= fat;
    stored.hi += fat;
    btDbvtVolume volume = to_bullet(stored);
    if (leaf == nullptr) {
      leaf = tree.insert(volume, nullptr);
      leaf->dataAsInt = static_cast<int>(k);
    } else {
      tree.update(leaf, volume);
    }
    ++broadphase.reinserted;
  }
}

void update_surface_tree(int body, const std::vector<Vec3>& x,
                         const std::vector<std::array<int, 3>>& triangles, Real margin,
                         SurfaceBroadphase& broadphase) {
  // A box over the same point twice is the box over it once, bit for bit.
  update_swept_surface_tree(body, x, x, triangles, margin, broadphase);
}

void collect_overlapping_triangles(int body_a, int body_b, SurfaceBroadphase& broadphase,
                                   std::vector<std::array<int, 2>>& pairs) {
  SurfaceBroadphase::Trees& t = *broadphase.trees;
  std::vector<std::array<int, 2>>& raw = t.raw[0];
  raw.clear();
  PairCollector collector;
  collector.out = &raw;
  btDbvt& tree_a = *t.tree[body_a];
  tree_a.collideTTpersistentStack(tree_a.m_root, t.tree[body_b]->m_root, collector);
  const std::vector<Box3>& boxes_a = broadphase.boxes[body_a];
  const std::vector<Box3>& boxes_b = broadphase.boxes[body_b];
  for (std::array<int, 2> p : raw) {
    if (body_a == body_b && p[0] > p[1]) std::swap(p[0], p[1]);
    if (boxes_a[p[0]].overlaps(boxes_b[p[1]])) pairs.push_back(p);
  }
}

void collect_triangle_pairs(int body_a, int body_b, SurfaceBroadphase& broadphase,
                            std::vector<std::array<int, 2>>& pairs) {
  const std::size_t first = pairs.size();
  collect_overlapping_triangles(body_a, body_b, broadphase, pairs);
  std::sort(pairs.begin() + static_cast<std::ptrdiff_t>(first), pairs.end());
}

}  // namespace pbm
