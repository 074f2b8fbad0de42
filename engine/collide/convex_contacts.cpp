#include "collide/convex_contacts.h"

#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

namespace pbm {
namespace {

btVector3 bt(const Vec3& v) {
  return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()), static_cast<btScalar>(v.z())};
}
Vec3 ours(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

btTransform transform_of(const ConvexSolid& s) {
  const Mat3& R = s.rotation;
  const btMatrix3x3 basis(static_cast<btScalar>(R(0, 0)), static_cast<btScalar>(R(0, 1)),
                          static_cast<btScalar>(R(0, 2)), static_cast<btScalar>(R(1, 0)),
                          static_cast<btScalar>(R(1, 1)), static_cast<btScalar>(R(1, 2)),
                          static_cast<btScalar>(R(2, 0)), static_cast<btScalar>(R(2, 1)),
                          static_cast<btScalar>(R(2, 2)));
  return btTransform(basis, bt(s.center));
}

// Bullet's shape for a solid. Bullet rounds a box's and a cylinder's edges by their collision
// margin (GJK works on the shape shrunk by it, then adds it back); 1% of the smallest half
// extent keeps that rounding far below a contact spring's depth.
using BulletShape =
    std::variant<std::monostate, btBoxShape, btSphereShape, btCylinderShapeZ, btCapsuleShapeZ>;

btConvexShape& make_shape(const ConvexSolid& s, BulletShape& storage) {
  const btScalar r = static_cast<btScalar>(s.size.x());
  const btScalar h = static_cast<btScalar>(s.size.z());
  switch (s.kind) {
    case ConvexKind::box: {
      btBoxShape& box = storage.emplace<btBoxShape>(bt(s.size));
      box.setMargin(static_cast<btScalar>(0.01 * s.size.minCoeff()));
      return box;
    }
    case ConvexKind::sphere:
      return storage.emplace<btSphereShape>(r);
    case ConvexKind::cylinder: {
      btCylinderShapeZ& cylinder = storage.emplace<btCylinderShapeZ>(btVector3(r, r, h));
      cylinder.setMargin(0.01f * std::min(r, h));
      return cylinder;
    }
    case ConvexKind::capsule:
      return storage.emplace<btCapsuleShapeZ>(r, 2 * h);
  }
  return storage.emplace<btSphereShape>(r);
}

// Collects the box-box detector's points: Bullet reports each on b's surface with b's normal
// (pointing toward a) and a negative distance when they overlap.
struct Collector final : btDiscreteCollisionDetectorInterface::Result {
  ConvexContacts* out = nullptr;
  int count = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3& normal_on_b, const btVector3& point_on_b,
                       btScalar distance) override {
    if (!(distance < 0) || count == kMaxConvexContacts) return;
    const Vec3 n = ours(normal_on_b).normalized();
    (*out)[count++] = {ours(point_on_b) + 0.5 * distance * n, n, -Real(distance)};
  }
};

// The deepest point of two overlapping solids by GJK and EPA; false when they do not overlap.
bool deepest_contact(const ConvexSolid& a, const ConvexSolid& b, ConvexContact& out) {
  BulletShape storage_a, storage_b;
  btConvexShape& shape_a = make_shape(a, storage_a);
  btConvexShape& shape_b = make_shape(b, storage_b);
  btDiscreteCollisionDetectorInterface::ClosestPointInput input;
  input.m_transformA = transform_of(a);
  input.m_transformB = transform_of(b);
  // A fresh simplex and a fixed first axis on every call: no state carried between calls.
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector gjk(&shape_a, &shape_b, &simplex, &epa);
  btPointCollector closest;
  gjk.getClosestPoints(input, closest, nullptr);
  if (!closest.m_hasResult || !(closest.m_distance < 0)) return false;
  const Vec3 n = ours(closest.m_normalOnBInWorld).normalized();
  out = {ours(closest.m_pointInWorld) + 0.5 * closest.m_distance * n, n, -Real(closest.m_distance)};
  return true;
}

// One of a capsule's end spheres (end = -1 or +1), as a solid.
ConvexSolid capsule_end(const ConvexSolid& capsule, Real end) {
  return {.kind = ConvexKind::sphere,
          .size = Vec3::Constant(capsule.size.x()),
          .rotation = capsule.rotation,
          .center = capsule.center + end * capsule.size.z() * capsule.rotation.col(2)};
}

// The rim of each of a cylinder's caps, as this many points (every 45 degrees).
constexpr int kRimPoints = 8;

// A cylinder's rim points inside the other solid, by the other's exact signed distance: each a
// contact along the other's outward normal there, turned to point from b toward a
// (`cylinder_is_a`). Up to kMaxConvexContacts of them, spread: a whole ring inside (a cylinder
// standing on its cap) gives four at right angles, whose forces balance about its axis; an arc
// (tilted) its two ends and two between. Returns how many.
int rim_contacts(const ConvexSolid& cylinder, const ConvexSolid& other, bool cylinder_is_a,
                 ConvexContacts& out) {
  std::array<ConvexContact, 2 * kRimPoints> inside;
  int n = 0;
  const Real r = cylinder.size.x(), h = cylinder.size.z();
  for (const Real cap : {-1.0, 1.0}) {
    for (int k = 0; k < kRimPoints; ++k) {
      const Real angle = 2 * std::numbers::pi * k / kRimPoints;
      const Vec3 p = cylinder.center +
                     cylinder.rotation * Vec3(r * std::cos(angle), r * std::sin(angle), cap * h);
      Vec3 normal;
      const Real d = convex_signed_distance(other, p, normal);
      if (!(d < 0)) continue;
      inside[static_cast<std::size_t>(n++)] = {p - 0.5 * d * normal,
                                               cylinder_is_a ? normal : Vec3(-normal), -d};
    }
  }
  if (n <= kMaxConvexContacts) {
    std::copy_n(inside.begin(), n, out.begin());
    return n;
  }
  for (int k = 0; k < kMaxConvexContacts; ++k) {
    const int i = n % kMaxConvexContacts == 0
                      ? k * n / kMaxConvexContacts
                      : static_cast<int>(std::lround(k * (n - 1) / Real(kMaxConvexContacts - 1)));
    out[static_cast<std::size_t>(k)] = inside[static_cast<std::size_t>(i)];
  }
  return kMaxConvexContacts;
}

// One of a cylinder's caps (end = -1 or +1) as a disc: a cylinder of a thousandth of its radius
// in half length at that end.
ConvexSolid cylinder_cap(const ConvexSolid& cylinder, Real end) {
  const Real half = 1e-3 * cylinder.size.x();
  return {.kind = ConvexKind::cylinder,
          .size = Vec3(cylinder.size.x(), cylinder.size.x(), half),
          .rotation = cylinder.rotation,
          .center = cylinder.center + end * (cylinder.size.z() - half) * cylinder.rotation.col(2)};
}

}  // namespace

int convex_contacts(const ConvexSolid& a, const ConvexSolid& b, ConvexContacts& out) {
  if (a.kind == ConvexKind::box && b.kind == ConvexKind::box) {
    BulletShape storage_a, storage_b;
    make_shape(a, storage_a);
    make_shape(b, storage_b);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = transform_of(a);
    input.m_transformB = transform_of(b);
    Collector collector;
    collector.out = &out;
    btBoxBoxDetector detector(&std::get<btBoxShape>(storage_a), &std::get<btBoxShape>(storage_b));
    detector.getClosestPoints(input, collector, nullptr);
    return collector.count;
  }
  // A cylinder resting on the other solid touches it on a disc (standing on a cap) or along a line
  // (lying on its side), where GJK's one deepest point would let it rock or roll: its rim points
  // inside the other, where at least two are; else, lying along it, the deepest points of its
  // two caps where both touch; else (an edge or a corner poking in) the deepest point.
  const bool a_cylinder = a.kind == ConvexKind::cylinder && b.kind != ConvexKind::sphere;
  const bool b_cylinder = b.kind == ConvexKind::cylinder && a.kind != ConvexKind::sphere;
  if (a_cylinder || b_cylinder) {
    int n = a_cylinder ? rim_contacts(a, b, true, out) : 0;
    if (n < 2 && b_cylinder) n = rim_contacts(b, a, false, out);
    if (n >= 2) return n;
    ConvexContacts caps;
    int m = 0;
    for (const Real end : {-1.0, 1.0}) {
      const bool touches = a_cylinder ? deepest_contact(cylinder_cap(a, end), b, caps[m])
                                      : deepest_contact(a, cylinder_cap(b, end), caps[m]);
      m += touches ? 1 : 0;
    }
    if (m == 2) {
      out[0] = caps[0];
      out[1] = caps[1];
      return 2;
    }
  }
  // A capsule lying along the other solid touches it along a line: GJK's one deepest point would
  // let it rock on that point, so where both its end spheres touch, they are its two points (a
  // log on the floor, two logs stacked). Otherwise (crossing, tilted onto one end) the deepest
  // point of the whole capsule. A sphere touches a capsule at one point anyway.
  const bool a_capsule = a.kind == ConvexKind::capsule && b.kind != ConvexKind::sphere;
  const bool b_capsule = b.kind == ConvexKind::capsule && a.kind != ConvexKind::sphere;
  if (a_capsule || b_capsule) {
    ConvexContacts ends;
    int n = 0;
    for (const Real end : {-1.0, 1.0}) {
      const bool touches = a_capsule ? deepest_contact(capsule_end(a, end), b, ends[n])
                                     : deepest_contact(a, capsule_end(b, end), ends[n]);
      n += touches ? 1 : 0;
    }
    if (n == 2) {
      out[0] = ends[0];
      out[1] = ends[1];
      return 2;
    }
  }
  return deepest_contact(a, b, out[0]) ? 1 : 0;
}

Box3 convex_bounds(const ConvexSolid& s) {
  // Half widths of the solid's box along the world axes: |R| times the shape's half extents
  // (a box's), plus the radius of its rounding (a capsule's ends, a sphere).
  Vec3 half = Vec3::Zero();
  Real round = 0;
  switch (s.kind) {
    case ConvexKind::box:
      half = s.size;
      break;
    case ConvexKind::sphere:
      round = s.size.x();
      break;
    case ConvexKind::cylinder:
      // The caps' discs lie within the box of half extents (r, r, h).
      half = Vec3(s.size.x(), s.size.x(), s.size.z());
      break;
    case ConvexKind::capsule:
      half = Vec3(0, 0, s.size.z());
      round = s.size.x();
      break;
  }
  const Vec3 reach = s.rotation.cwiseAbs() * half + Vec3::Constant(round);
  Box3 box;
  box.add(s.center - reach);
  box.add(s.center + reach);
  return box;
}

Real convex_signed_distance(const ConvexSolid& solid, const Vec3& x, Vec3& normal) {
  const Vec3 p = solid.rotation.transpose() * (x - solid.center);  // in the shape's frame
  const Real r = solid.size.x();
  Vec3 n = Vec3::UnitZ();
  Real d = 0;
  // Distance from a point to a convex set's core (a point or a segment) minus a radius.
  const auto around = [&](const Vec3& core) {
    const Vec3 out = p - core;
    const Real length = out.norm();
    if (length > 0) n = out / length;
    d = length - r;
  };
  switch (solid.kind) {
    case ConvexKind::sphere:
      around(Vec3::Zero());
      break;
    case ConvexKind::capsule:
      around(Vec3(0, 0, std::clamp(p.z(), -solid.size.z(), solid.size.z())));
      break;
    case ConvexKind::box: {
      const Vec3 q = p.cwiseAbs() - solid.size;
      const Vec3 sign = p.unaryExpr([](Real c) { return c < 0 ? Real(-1) : Real(1); });
      if ((q.array() > 0).any()) {
        const Vec3 out = q.cwiseMax(0.0);
        d = out.norm();
        n = sign.cwiseProduct(out) / d;
      } else {
        int axis = 0;
        d = q.maxCoeff(&axis);
        n = Vec3::Zero();
        n[axis] = sign[axis];
      }
      break;
    }
    case ConvexKind::cylinder: {
      const Real rho = std::hypot(p.x(), p.y());
      const Vec3 radial = rho > 0 ? Vec3(p.x() / rho, p.y() / rho, 0) : Vec3::UnitX();
      const Vec3 axial(0, 0, p.z() < 0 ? -1 : 1);
      const Real dr = rho - r, dz = std::abs(p.z()) - solid.size.z();
      if (dr > 0 || dz > 0) {
        const Real a = std::max(dr, Real(0)), b = std::max(dz, Real(0));
        d = std::hypot(a, b);
        n = (a * radial + b * axial) / d;
      } else if (dr > dz) {
        d = dr;
        n = radial;
      } else {
        d = dz;
        n = axial;
      }
      break;
    }
  }
  normal = solid.rotation * n;
  return d;
}

}  // namespace pbm
