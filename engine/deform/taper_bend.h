// Superellipsoid with linear tapering along axes 1, 2 and bending along axis 3 (2.10), and its
// analytic 3 x 11 Jacobian (2.12) with respect to
//   q_s = (a0, a1, a2, a3, eps1, eps2, t1, t2, b1, b2, b3) (2.11).
#pragma once

#include <Eigen/Core>

#include "core/types.h"
#include "deform/superquadric.h"

namespace pbm {

using TaperBendJacobian = Eigen::Matrix<Real, 3, 11>;

// s of (2.10) at material point (u, v, w), w > 0, a0, a3 > 0. If J != nullptr, writes ds/dq_s.
void evaluate_taper_bend(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& s,
                         TaperBendJacobian* J);
void evaluate_taper_bend(const Eigen::Ref<const VecX>& q_s, const SuperquadricAngles& angles,
                         Real w, Vec3& s, TaperBendJacobian* J);

}  // namespace pbm
