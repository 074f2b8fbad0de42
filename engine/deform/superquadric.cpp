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
// sgn(x)|x|^eps and ln|x| sgn(x)|x|^eps from a precomputed ln|x| and one exp (a pow and a log
// per term cost several times as much, and this runs for every node at every step).
void signed_power_pair(Real x, Real ln_abs_x, Real eps, Real& power, Real& log_power) {
  if (x == 0) {
    power = log_power = 0;
    return;
  }
  const Real magnitude = std::exp(eps * ln_abs_x);
  power = x > 0 ? magnitude : -magnitude;
  log_power = ln_abs_x * power;
}

Real log_abs_or_zero(Real x) {
  return x == 0 ? 0.0 : std::log(std::abs(x));
}
}  // namespace

SuperquadricAngles superquadric_angles(Real u, Real v) {
  SuperquadricAngles a;
  a.cos_u = std::cos(u);
  a.sin_u = std::sin(u);
  a.cos_v = std::cos(v);
  a.sin_v = std::sin(v);
  a.ln_cos_u = log_abs_or_zero(a.cos_u);
  a.ln_sin_u = log_abs_or_zero(a.sin_u);
  a.ln_cos_v = log_abs_or_zero(a.cos_v);
  a.ln_sin_v = log_abs_or_zero(a.sin_v);
  return a;
}

SignedPowers latitude_powers(const SuperquadricAngles& a, Real eps1) {
  SignedPowers p;
  signed_power_pair(a.cos_u, a.ln_cos_u, eps1, p.C, p.lnC);
  signed_power_pair(a.sin_u, a.ln_sin_u, eps1, p.S, p.lnS);
  return p;
}

SignedPowers longitude_powers(const SuperquadricAngles& a, Real eps2) {
  SignedPowers p;
  signed_power_pair(a.cos_v, a.ln_cos_v, eps2, p.C, p.lnC);
  signed_power_pair(a.sin_v, a.ln_sin_v, eps2, p.S, p.lnS);
  return p;
}

SuperquadricBasis compute_superquadric_basis(const SuperquadricAngles& a, Real eps1, Real eps2) {
  SuperquadricBasis b;
  signed_power_pair(a.cos_u, a.ln_cos_u, eps1, b.C_u, b.lnC_u);
  signed_power_pair(a.sin_u, a.ln_sin_u, eps1, b.S_u, b.lnS_u);
  signed_power_pair(a.cos_v, a.ln_cos_v, eps2, b.C_v, b.lnC_v);
  signed_power_pair(a.sin_v, a.ln_sin_v, eps2, b.S_v, b.lnS_v);
  return b;
}

SuperquadricBasis compute_superquadric_basis(Real u, Real v, Real eps1, Real eps2) {
  return compute_superquadric_basis(superquadric_angles(u, v), eps1, eps2);
}

void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& e,
                           SuperquadricJacobian* J_e) {
  evaluate_superquadric(q_s, superquadric_angles(u, v), w, e, J_e);
}

void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, const SuperquadricAngles& angles,
                           Real w, Vec3& e, SuperquadricJacobian* J_e) {
  evaluate_superquadric(q_s, compute_superquadric_basis(angles, q_s(4), q_s(5)), w, e, J_e);
}

void evaluate_superquadric(const Eigen::Ref<const VecX>& q_s, const SuperquadricBasis& b, Real w,
                           Vec3& e, SuperquadricJacobian* J_e) {
  assert(q_s.size() >= 6);
  const Real a0 = q_s(0), a1 = q_s(1), a2 = q_s(2), a3 = q_s(3);
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

namespace {
// f(q + t r) to second order in t: (f, df/dt, 1/2 d2f/dt2). e is a product of one-parameter
// factors, so its second derivative along r is the t^2 term of the product of their series.
struct Series2 {
  Real f0 = 0, f1 = 0, f2 = 0;
};
Series2 operator*(const Series2& a, const Series2& b) {
  return {a.f0 * b.f0, a.f0 * b.f1 + a.f1 * b.f0, a.f0 * b.f2 + a.f1 * b.f1 + a.f2 * b.f0};
}
// sgn(x)|x|^eps along eps + t r_eps: derivatives ln|x| P and ln|x|^2 P (0 where x = 0).
Series2 power_series(Real power, Real log_power, Real ln_abs_x, Real r_eps) {
  return {power, log_power * r_eps, 0.5 * ln_abs_x * log_power * r_eps * r_eps};
}
}  // namespace

Vec3 superquadric_second_derivative(const Eigen::Ref<const VecX>& q_s,
                                    const SuperquadricAngles& angles, Real w,
                                    const Eigen::Ref<const VecX>& r) {
  return superquadric_second_derivative(q_s, compute_superquadric_basis(angles, q_s(4), q_s(5)),
                                        angles, w, r);
}

Vec3 superquadric_second_derivative(const Eigen::Ref<const VecX>& q_s, const SuperquadricBasis& b,
                                    const SuperquadricAngles& angles, Real w,
                                    const Eigen::Ref<const VecX>& r) {
  assert(q_s.size() >= 6 && r.size() >= 6);
  const Series2 a0{q_s(0), r(0), 0}, a1{q_s(1), r(1), 0}, a2{q_s(2), r(2), 0}, a3{q_s(3), r(3), 0};
  const Series2 C_u = power_series(b.C_u, b.lnC_u, angles.ln_cos_u, r(4));
  const Series2 S_u = power_series(b.S_u, b.lnS_u, angles.ln_sin_u, r(4));
  const Series2 C_v = power_series(b.C_v, b.lnC_v, angles.ln_cos_v, r(5));
  const Series2 S_v = power_series(b.S_v, b.lnS_v, angles.ln_sin_v, r(5));
  return 2.0 * w * Vec3((a0 * a1 * C_u * C_v).f2, (a0 * a2 * C_u * S_v).f2, (a0 * a3 * S_u).f2);
}

}  // namespace pbm
