// What a scene file says of constraints (scenes/README.md, section "constraints"): plain
// definitions with defaults, validated by the scene reader and compiled into a
// ConstraintSystemModel (constrain/constraint_model.h). Data only.
#pragma once

#include <optional>
#include <string>

#include "core/types.h"

namespace pbm {

// A point-to-point constraint (7.21), or a hinge: two of them on an axis plus a rotational spring.
enum class ConstraintKind { point, hinge };
// How N f_c + r = 0 (7.33) is solved: dense LU, or a sparse LDL^T for loop-free systems.
enum class ConstraintSolverKind { dense, sparse };

// One end of a constraint: a point of a body (a node, a material point (u, v) resolved to the
// nearest node like springs, or a point fixed in the body frame), or a fixed world anchor.
struct ConstraintEndDef {
  int body = -1;                       // index into the scene's bodies; < 0: the world anchor
  int node = -1;                       // >= 0: node index
  std::optional<Vec2> material_point;  // (u, v) in radians
  std::optional<Vec3> point;           // body frame [m]
  Vec3 world = Vec3::Zero();           // world frame [m], when body < 0
};

// Holonomic constraint between two ends (7.1), stabilized by Baumgarte's (7.14).
struct ConstraintDef {
  std::string name;
  ConstraintKind kind = ConstraintKind::point;
  ConstraintEndDef a, b;      // a is always a body
  std::optional<Real> alpha;  // overrides solver.constraint_alpha [1/s], >= 0
  std::optional<Real> beta;   // overrides solver.constraint_beta [1/s], >= 0
  Vec3 axis{0, 1, 0};         // hinge: axis at the initial state, world frame (normalized on load)
  Real length = 0.2;          // hinge: distance between its two point constraints [m], > 0
  Real stiffness = 0;         // hinge: rotational spring [N m/rad], >= 0 (sec. 6.4's see-saw)
  Real rest_angle = 0;        // hinge: angle of a relative to b where the spring is slack [rad]
  Real damping = 0;           // hinge: rotational damper [N m s/rad], >= 0
};

}  // namespace pbm
