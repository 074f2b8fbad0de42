// Reference shape s(u; q_s) = T(e(u; a); b) (2.4) and its Jacobian J = ds/dq_s (2.6) for every
// ShapeKind: superquadric (2.7)-(2.9), taper_bend (2.10)-(2.12), general (2.13)-(2.27). The
// parameter metadata (count, defaults, names, valid ranges) is in deform/shape_parameters.h.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/types.h"
#include "deform/shape_parameters.h"
#include "deform/superquadric.h"

namespace pbm {

// s at material point (u, v, w): u in [-pi/2, pi/2], v in [-pi, pi), w in (0, 1] (w = 1 on the
// shell). q_s has n_s entries. If J != nullptr, writes J = ds/dq_s (3 x n_s, already sized by the
// caller). Finite at the poles and the seam; no heap allocation.
void evaluate_reference_shape(ShapeKind kind, const Eigen::Ref<const VecX>& q_s, Real u, Real v,
                              Real w, Vec3& s, Mat3X* J);
// The same with the material point's angles precomputed (superquadric_angles(u, v)).
void evaluate_reference_shape(ShapeKind kind, const Eigen::Ref<const VecX>& q_s,
                              const SuperquadricAngles& angles, Real w, Vec3& s, Mat3X* J);

}  // namespace pbm
