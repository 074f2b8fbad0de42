#include "deform/superquadric.h"

#include <cassert>
#include <cmath>

namespace pbm {

Real signed_power(Real x, Real eps) {
  if (x == 0) return 0;
  const Real magnitude = std::pow(std::abs(x), eps);
  return x > 0 ? magnitude : -magnitude;
}

Real log_signed_power(Real x, Real eps) {
  // ln|x| |x|^eps -> 0 as x -> 0 for eps > 0; evaluating it literally would give 0 * -inf = NaN.
  if (x == 0) return 0;
  return std::log(std::abs(x)) * signed_power(x, eps);
}

namespace {
// sgn(x)|x|^eps and ln|x| sgn(x)|x|^eps from one log and one exp (a pow and a log per term cost
// twice as much, and this runs for every node at every step).
void signed_power_pair(Real x, Real eps, Real& power, Real& log_power) {
  if (x == 0) {
    power = log_power = 0;
    return;
  }
  const Real ln = std::log(std::abs(x));
  const Real magnitude = std::exp(eps * ln);
  power = x > 0 ? magnitude : -magnitude;
  log_power = ln * power;
}
}  // namespace

SuperquadricBasis compute_superquadric_basis(Real u, Real v, Real eps1, Real eps2) {
  const Real cos_u = std::cos(u), sin_u = std::sin(u);
  const Real cos_v = std::cos(v), sin_v = std::sin(v);
  SuperquadricBasis b;
  signed_power_pair(cos_u, eps1, b.C_u, b.lnC_u);
  signed_power_pair(sin_u, eps1, b.S_u, b.lnS_u);
  signed_power_pair(cos_v, eps2, b.C_v, b.lnC_v);
  signed_power_pair(sin_v, eps2, b.S_v, b.lnS_v);
  return b;
}

void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& e,
                           SuperquadricJacobian* J_e) {
  assert(q_s.size() >= 6);
  const Real a0 = q_s(0), a1 = q_s(1), a2 = q_s(2), a3 = q_s(3);
  const SuperquadricBasis b = compute_superquadric_basis(u, v, q_s(4), q_s(5));
  // (2.7)
  e = a0 * w * Vec3(a1 * b.C_u * b.C_v, a2 * b.C_u * b.S_v, a3 * b.S_u);
  if (J_e == nullptr) return;
  // (2.9)
  SuperquadricJacobian& J = *J_e;
  J.setZero();
  J(0, 0) = w * a1 * b.C_u * b.C_v;
  J(0, 1) = a0 * w * b.C_u * b.C_v;
  J(0, 4) = a0 * w * a1 * b.lnC_u * b.C_v;
  J(0, 5) = a0 * w * a1 * b.C_u * b.lnC_v;
  J(1, 0) = w * a2 * b.C_u * b.S_v;
  J(1, 2) = a0 * w * b.C_u * b.S_v;
  J(1, 4) = a0 * w * a2 * b.lnC_u * b.S_v;
  J(1, 5) = a0 * w * a2 * b.C_u * b.lnS_v;
  J(2, 0) = w * a3 * b.S_u;
  J(2, 3) = a0 * w * b.S_u;
  J(2, 4) = a0 * w * a3 * b.lnS_u;
}

}  // namespace pbm
