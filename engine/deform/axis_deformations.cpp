#include "deform/axis_deformations.h"

#include <cassert>
#include <cmath>
#include <numbers>

#include "deform/superquadric.h"

namespace pbm {
namespace {

using JacobianRow = Eigen::Matrix<Real, 1, kAxisDeformationParameterCount>;

// A or B of (2.16)/(2.17), (2.20)/(2.21), (2.24)/(2.25) for the pair (i, j): deforms p_j by the
// taper t_i^j, bend b^{aj}_i, b^{lj}_i, b^{rj}_i and shear s_i^j, all driven by the axial
// coordinate p_i normalized by L = a0 a_i w. Adds its gradient to dX when dp != nullptr.
Real deform_across_axis(const Eigen::Ref<const VecX>& q_s, int i, int j, const Vec3& p, Real L,
                        Real dL_da0, Real dL_dai, const AxisDeformationJacobian* dp,
                        JacobianRow& dX) {
  constexpr Real pi = std::numbers::pi;
  const Real t = q_s(taper_index(i, j));
  const Real shear = q_s(shear_index(i, j));
  const Real b_a = q_s(bend_amount_index(i, j));
  const Real b_l = q_s(bend_location_index(i, j));
  const Real b_r = q_s(bend_range_index(i, j));
  const Real p_i = p(i - 1), p_j = p(j - 1);
  const Real z = p_i / L;
  const Real rho = (p_i + b_l) / L * pi * b_r;
  const Real cos_rho = std::cos(rho), sin_rho = std::sin(rho);
  const Real X = (t * z + 1) * p_j + b_a * cos_rho + p_i * shear;
  if (dp == nullptr) return X;

  const Real dX_dpi = t * p_j / L - b_a * sin_rho * pi * b_r / L + shear;
  const Real dX_dpj = t * z + 1;
  // z and rho both scale as 1 / L.
  const Real dX_dL = -t * z * p_j / L + b_a * sin_rho * rho / L;
  dX = dX_dpi * dp->row(i - 1) + dX_dpj * dp->row(j - 1);
  dX(0) += dX_dL * dL_da0;
  dX(i) += dX_dL * dL_dai;  // a_i sits at index i of q_s
  dX(taper_index(i, j)) += z * p_j;
  dX(shear_index(i, j)) += p_i;
  dX(bend_amount_index(i, j)) += cos_rho;
  dX(bend_location_index(i, j)) += -b_a * sin_rho * pi * b_r / L;
  dX(bend_range_index(i, j)) += -b_a * sin_rho * (p_i + b_l) * pi / L;
  return X;
}

// T_i of (2.15)/(2.19)/(2.23) (with the corrections in the header), (i, j, k) cyclic.
void apply_axis_deformation(const Eigen::Ref<const VecX>& q_s, int i, int j, int k, Real w,
                            const Vec3& p, const AxisDeformationJacobian* dp, Vec3& r,
                            AxisDeformationJacobian* dr) {
  constexpr Real pi = std::numbers::pi;
  const Real a0 = q_s(0), a_i = q_s(i);
  const Real L = a0 * a_i * w;
  const Real dL_da0 = a_i * w, dL_dai = a0 * w;
  JacobianRow dA, dB;
  const Real A = deform_across_axis(q_s, i, j, p, L, dL_da0, dL_dai, dp, dA);
  const Real B = deform_across_axis(q_s, i, k, p, L, dL_da0, dL_dai, dp, dB);
  // (2.18)/(2.22)/(2.26)
  const Real tau = q_s(twist_index(i));
  const Real phi = p(i - 1) / L * pi * tau;
  const Real cos_phi = std::cos(phi), sin_phi = std::sin(phi);
  r(i - 1) = p(i - 1);
  r(j - 1) = A * cos_phi - B * sin_phi;
  r(k - 1) = A * sin_phi + B * cos_phi;
  if (dp == nullptr) return;

  JacobianRow dphi = (pi * tau / L) * dp->row(i - 1);
  dphi(0) += -phi / L * dL_da0;
  dphi(i) += -phi / L * dL_dai;
  dphi(twist_index(i)) += p(i - 1) / L * pi;
  dr->row(i - 1) = dp->row(i - 1);
  dr->row(j - 1) = cos_phi * dA - sin_phi * dB - r(k - 1) * dphi;
  dr->row(k - 1) = sin_phi * dA + cos_phi * dB + r(j - 1) * dphi;
}

}  // namespace

void evaluate_axis_deformations(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& s,
                                AxisDeformationJacobian* J) {
  evaluate_axis_deformations(q_s, superquadric_angles(u, v), w, s, J);
}

void evaluate_axis_deformations(const Eigen::Ref<const VecX>& q_s, const SuperquadricAngles& angles,
                                Real w, Vec3& s, AxisDeformationJacobian* J) {
  assert(q_s.size() == kAxisDeformationParameterCount);
  Vec3 e;
  SuperquadricJacobian J_e;
  evaluate_superquadric(q_s, angles, w, e, J != nullptr ? &J_e : nullptr);
  AxisDeformationJacobian de, dr3, dr1;
  AxisDeformationJacobian* de_ptr = nullptr;
  AxisDeformationJacobian* dr3_ptr = nullptr;
  AxisDeformationJacobian* dr1_ptr = nullptr;
  if (J != nullptr) {
    de.setZero();
    de.leftCols<6>() = J_e;
    de_ptr = &de;
    dr3_ptr = &dr3;
    dr1_ptr = &dr1;
  }
  Vec3 r3, r1;
  apply_axis_deformation(q_s, 3, 1, 2, w, e, de_ptr, r3, dr3_ptr);    // (2.15)-(2.18)
  apply_axis_deformation(q_s, 1, 2, 3, w, r3, dr3_ptr, r1, dr1_ptr);  // (2.19)-(2.22)
  apply_axis_deformation(q_s, 2, 3, 1, w, r1, dr1_ptr, s, J);         // (2.23)-(2.26)
}

}  // namespace pbm
