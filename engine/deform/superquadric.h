// Superquadric ellipsoid solid e(u, v, w; a0, a1, a2, a3, eps1, eps2) (2.7) and its Jacobian with
// respect to its six parameters (2.9). Also the signed powers C^eps, S^eps shared by every
// reference shape built on e (taper_bend.h, axis_deformations.h).
#pragma once

#include <Eigen/Core>

#include "core/types.h"

namespace pbm {

// 3 x 6 Jacobian de/d(a0, a1, a2, a3, eps1, eps2).
using SuperquadricJacobian = Eigen::Matrix<Real, 3, 6>;

// sgn(x) |x|^eps, the C^eps / S^eps of (2.7); 0 at x = 0 for eps > 0.
Real signed_power(Real x, Real eps);
// d/deps [sgn(x) |x|^eps] = ln|x| sgn(x) |x|^eps; its limit 0 at x = 0 (eps > 0) so poles and the
// seam stay finite in (2.9).
Real log_signed_power(Real x, Real eps);

// The trigonometric factors of (2.7)/(2.9) at one material point (u, v).
struct SuperquadricBasis {
  Real C_u = 0;    // sgn(cos u) |cos u|^eps1
  Real S_u = 0;    // sgn(sin u) |sin u|^eps1
  Real C_v = 0;    // sgn(cos v) |cos v|^eps2
  Real S_v = 0;    // sgn(sin v) |sin v|^eps2
  Real lnC_u = 0;  // ln|cos u| C_u = dC_u/deps1
  Real lnS_u = 0;  // ln|sin u| S_u = dS_u/deps1
  Real lnC_v = 0;  // ln|cos v| C_v = dC_v/deps2
  Real lnS_v = 0;  // ln|sin v| S_v = dS_v/deps2
};

// The eps-independent part of (2.7) at one material point: cos/sin of u and v and their log
// magnitudes (0 where the value is 0). A node's (u, v) never changes, so bodies precompute these
// once and every step pays only one exp per term.
struct SuperquadricAngles {
  Real cos_u = 1, sin_u = 0, cos_v = 1, sin_v = 0;
  Real ln_cos_u = 0, ln_sin_u = 0, ln_cos_v = 0, ln_sin_v = 0;
};
SuperquadricAngles superquadric_angles(Real u, Real v);

// The signed powers of one latitude (C_u, S_u with eps1) or one longitude (C_v, S_v with eps2)
// and their eps-derivatives. A tessellation's grid has few distinct u and v, so bodies compute
// these once per distinct value and assemble each node's basis from two of them.
struct SignedPowers {
  Real C = 0, S = 0, lnC = 0, lnS = 0;
};
SignedPowers latitude_powers(const SuperquadricAngles& angles, Real eps1);
SignedPowers longitude_powers(const SuperquadricAngles& angles, Real eps2);
inline SuperquadricBasis combine_powers(const SignedPowers& u, const SignedPowers& v) {
  return {u.C, u.S, v.C, v.S, u.lnC, u.lnS, v.lnC, v.lnS};
}

// u in [-pi/2, pi/2] (latitude), v in [-pi, pi) (longitude); eps1, eps2 > 0.
SuperquadricBasis compute_superquadric_basis(Real u, Real v, Real eps1, Real eps2);
SuperquadricBasis compute_superquadric_basis(const SuperquadricAngles& angles, Real eps1,
                                             Real eps2);

// e of (2.7) from q_s(0..5) = (a0, a1, a2, a3, eps1, eps2) (2.8); q_s may be longer (the deformed
// shapes append their parameters). If J_e != nullptr, writes de/dq_s(0..5) (2.9).
void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& e,
                           SuperquadricJacobian* J_e);
void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, const SuperquadricAngles& angles,
                           Real w, Vec3& e, SuperquadricJacobian* J_e);
// The same from the basis at q_s's eps1, eps2.
void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, const SuperquadricBasis& basis,
                           Real w, Vec3& e, SuperquadricJacobian* J_e);

// sum_ij d2e/dq_i dq_j r_i r_j over q_s(0..5) for a direction r (6 entries): with r = q_s-dot it
// is the J-dot q_s-dot that the velocity-product acceleration of (3.18) needs, exactly, where a
// second difference of e costs two more evaluations.
Vec3 superquadric_second_derivative(const Eigen::Ref<const VecX>& q_s,
                                    const SuperquadricAngles& angles, Real w,
                                    const Eigen::Ref<const VecX>& r);
// The same from the basis at q_s's eps1, eps2 (as evaluate_superquadric returned it): no exp.
Vec3 superquadric_second_derivative(const Eigen::Ref<const VecX>& q_s, const SuperquadricBasis& b,
                                    const SuperquadricAngles& angles, Real w,
                                    const Eigen::Ref<const VecX>& r);

}  // namespace pbm
