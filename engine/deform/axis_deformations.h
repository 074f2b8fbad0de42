// Superellipsoid with tapering, bending, shearing and twisting along each principal axis,
// s = T2(T1(T3(e))) (2.13)-(2.26), and its 3 x 39 Jacobian with respect to
//   q_s = (a0, a1, a2, a3, eps1, eps2, tau_i, t_i^j, s_i^j, b^{aj}_i, b^{lj}_i, b^{rj}_i) (2.27).
//
// Layout of q_s (0-based):
//   0..5    a0, a1, a2, a3, eps1, eps2
//   6..8    tau1, tau2, tau3                       twist about axis i
//   9..14   t_i^j   for (i,j) = (1,2),(1,3),(2,1),(2,3),(3,1),(3,2)   taper of axis j along i
//   15..20  s_i^j   same pair order                shear
//   21..26  b^{aj}_i                               bend amount
//   27..32  b^{lj}_i                               bend location
//   33..38  b^{rj}_i                               bend range
//
// Deviations from the printed equations, each needed for the zero-deformation shape to be e:
//   - (2.19) prints r_{3_3} as the first component of r_1; T_1 acts along axis 1 and so keeps
//     r_{3_1} (as T_3 keeps e_3 and T_2 keeps r_{1_2}).
//   - (2.20) prints the bend of A_1 as b^{a1}_1, b^{l1}_1, b^{r1}_1; there is no pair (1,1) in
//     (2.27) and A_1 acts on axis 2 (its taper is t_1^2), so pair (1,2) is used.
//   - (2.23) puts A_2 cos(phi_2) - B_2 sin(phi_2) in row 1 and A_2 sin + B_2 cos in row 3. A_2 is
//     built on r_{1_3} and B_2 on r_{1_1}, so with zero twist the print would swap axes 1 and 3.
//     Rows 1 and 3 are exchanged here: s_3 = A_2 cos - B_2 sin, s_1 = A_2 sin + B_2 cos, which
//     makes each twist a right-handed rotation about its axis, as for T_3 and T_1.
// Every T_i is thus the same map in the cyclic axis order (i, j, k) = (3,1,2), (1,2,3), (2,3,1):
// keep p_i, deform p_j into A and p_k into B, then rotate (A, B) by phi_i.
#pragma once

#include <Eigen/Core>

#include "core/types.h"
#include "deform/superquadric.h"

namespace pbm {

constexpr int kAxisDeformationParameterCount = 39;
using AxisDeformationJacobian = Eigen::Matrix<Real, 3, kAxisDeformationParameterCount>;

// Index in q_s of twist tau_i, axis i in {1, 2, 3}.
constexpr int twist_index(int i) {
  return 5 + i;
}
// Position 0..5 of the pair (i, j), j != i, in the order (1,2),(1,3),(2,1),(2,3),(3,1),(3,2).
constexpr int axis_pair_position(int i, int j) {
  return 2 * (i - 1) + (j < i ? j - 1 : j - 2);
}
constexpr int taper_index(int i, int j) {
  return 9 + axis_pair_position(i, j);
}
constexpr int shear_index(int i, int j) {
  return 15 + axis_pair_position(i, j);
}
constexpr int bend_amount_index(int i, int j) {
  return 21 + axis_pair_position(i, j);
}
constexpr int bend_location_index(int i, int j) {
  return 27 + axis_pair_position(i, j);
}
constexpr int bend_range_index(int i, int j) {
  return 33 + axis_pair_position(i, j);
}

// s = T2(T1(T3(e))) at material point (u, v, w), w > 0, a0..a3 > 0. If J != nullptr, writes
// ds/dq_s by the chain rule through the three stages (no heap allocation).
void evaluate_axis_deformations(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& s,
                                AxisDeformationJacobian* J);
void evaluate_axis_deformations(const Eigen::Ref<const VecX>& q_s, const SuperquadricAngles& angles,
                                Real w, Vec3& s, AxisDeformationJacobian* J);

}  // namespace pbm
