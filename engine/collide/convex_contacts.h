// Contact points between two convex solids (box, sphere, cylinder, capsule), the narrowphase of
// the articulated figures' segment-segment collisions (sec. 15.3's detection). Bullet computes
// them: its box-box detector (ODE's, up to 4 points: a box resting on a box stands on its face)
// for two boxes, GJK with EPA (the deepest point) for every other pair; a capsule lying along
// the other solid (both its end spheres touching) gets those two points, and a cylinder resting
// on it its rim points inside the other (up to 4: standing on a cap) or, lying on its side, its
// two caps' deepest points. Nothing is cached between
// calls, so the points are a function of the two poses alone (docs/architecture.md,
// "Determinism"). Bullet here is single precision: points and depths carry ~1e-7 relative error.
#pragma once

#include <array>

#include "collide/surface_broadphase.h"
#include "core/types.h"

namespace pbm {

enum class ConvexKind {
  box,       // size: half extents
  sphere,    // size.x: radius
  cylinder,  // size.x: radius, size.z: half length along the shape's z
  capsule,   // size.x: radius, size.z: half length of the straight part along the shape's z
};

// A solid placed in the world: x_world = center + rotation * x_shape.
struct ConvexSolid {
  ConvexKind kind = ConvexKind::box;
  Vec3 size = Vec3::Constant(0.1);  // [m], see ConvexKind
  Mat3 rotation = Mat3::Identity();
  Vec3 center = Vec3::Zero();  // [m]
};

struct ConvexContact {
  Vec3 point = Vec3::Zero();    // midway between the two surfaces [m]
  Vec3 normal = Vec3::UnitZ();  // unit, from b toward a: the direction that separates a
  Real depth = 0;               // how far the solids overlap along normal [m], > 0
};

inline constexpr int kMaxConvexContacts = 4;
using ConvexContacts = std::array<ConvexContact, kMaxConvexContacts>;

// The points where a and b overlap; returns how many (0 when they do not).
int convex_contacts(const ConvexSolid& a, const ConvexSolid& b, ConvexContacts& out);

// The solid's axis-aligned bounding box, exact for a box, a sphere and a capsule.
Box3 convex_bounds(const ConvexSolid& solid);

// Signed distance of the world point x from the solid's surface [m] (< 0 inside), in closed form
// (double precision), and the solid's outward unit normal at the closest surface point (inside:
// toward the nearest face). Exact for every kind.
Real convex_signed_distance(const ConvexSolid& solid, const Vec3& x, Vec3& normal);

}  // namespace pbm
