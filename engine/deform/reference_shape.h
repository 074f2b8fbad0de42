// Reference shape s(u; q_s) = T(e(u; a); b) (2.4) and its Jacobian J = ds/dq_s (2.6) for every
// ShapeKind: superquadric (2.7)-(2.9), taper_bend (2.10)-(2.12), general (2.13)-(2.27). Also the
// parameter metadata (count, defaults, names, valid ranges) used by scene loading and the UI.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/types.h"
#include "deform/superquadric.h"
#include "scene/scene.h"

namespace pbm {

// n_s: 6 (2.8), 11 (2.11) or 39 (2.27). Declared in scene/scene.h.
int shape_parameter_count(ShapeKind kind);

// s at material point (u, v, w): u in [-pi/2, pi/2], v in [-pi, pi), w in (0, 1] (w = 1 on the
// shell). q_s has n_s entries. If J != nullptr, writes J = ds/dq_s (3 x n_s, already sized by the
// caller). Finite at the poles and the seam; no heap allocation.
void evaluate_reference_shape(ShapeKind kind, const Eigen::Ref<const VecX>& q_s, Real u, Real v,
                              Real w, Vec3& s, Mat3X* J);
// The same with the material point's angles precomputed (superquadric_angles(u, v)).
void evaluate_reference_shape(ShapeKind kind, const Eigen::Ref<const VecX>& q_s,
                              const SuperquadricAngles& angles, Real w, Vec3& s, Mat3X* J);

// The unit sphere: a0 = a1 = a2 = a3 = 1, eps1 = eps2 = 1, deformations 0, bend ranges 1.
VecX default_shape_parameters(ShapeKind kind);

// "a0", ..., "eps2", then "t1", "t2", "b1", "b2", "b3" (taper_bend) or "tau1".."tau3", "t1^2",
// ..., "s1^2", ..., "ba1^2", ..., "bl1^2", ..., "br1^2", ... (general, pair order of (2.27)).
std::string shape_parameter_name(ShapeKind kind, int index);

// Empty if value is valid for q_s(index), else why not (e.g. "must be > 0"). a0, a1..a3, eps > 0
// (a_i > 1 allowed for elongated shapes, unlike the book's a_i <= 1); tapers and bend locations
// in [-1, 1]; bend ranges in (0, 1]; bend amounts, twists and shears any finite value.
std::string check_shape_parameter(ShapeKind kind, int index, Real value);

}  // namespace pbm
