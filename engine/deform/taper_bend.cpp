#include "deform/taper_bend.h"

#include <cassert>
#include <cmath>
#include <numbers>

#include "deform/superquadric.h"

namespace pbm {

void evaluate_taper_bend(const Eigen::Ref<const VecX>& q_s, Real u, Real v, Real w, Vec3& s,
                         TaperBendJacobian* J) {
  evaluate_taper_bend(q_s, superquadric_angles(u, v), w, s, J);
}

void evaluate_taper_bend(const Eigen::Ref<const VecX>& q_s, const SuperquadricAngles& angles,
                         Real w, Vec3& s, TaperBendJacobian* J) {
  assert(q_s.size() == 11);
  constexpr Real pi = std::numbers::pi;
  const Real a0 = q_s(0), a1 = q_s(1), a2 = q_s(2), a3 = q_s(3);
  const Real t1 = q_s(6), t2 = q_s(7), b1 = q_s(8), b2 = q_s(9), b3 = q_s(10);
  const SuperquadricBasis B = compute_superquadric_basis(angles, q_s(4), q_s(5));

  // e of (2.7); e3 / (a0 a3 w) = S_u exactly, used instead of the division in the taper factors.
  const Real e1 = a0 * w * a1 * B.C_u * B.C_v;
  const Real e2 = a0 * w * a2 * B.C_u * B.S_v;
  const Real e3 = a0 * w * a3 * B.S_u;
  const Real L = a0 * a3 * w;  // half length of axis 3, normalizes the axial coordinate
  const Real taper1 = t1 * B.S_u + 1;
  const Real taper2 = t2 * B.S_u + 1;
  const Real r = (e3 + b2) / L * pi * b3;  // the r defined before (2.12)
  const Real sin_r = std::sin(r), cos_r = std::cos(r);

  // (2.10)
  s = Vec3(taper1 * e1 + b1 * cos_r, taper2 * e2, e3);
  if (J == nullptr) return;

  // (2.12), re-derived from (2.10). Entries agree with the print except J_{1,11}: the book prints
  // -b1 pi sin(r) r, but dr/db3 = r / b3 = pi (e3 + b2) / (a0 a3 w), so the correct entry is
  // -b1 sin(r) pi (e3 + b2) / (a0 a3 w). (J_11 and J_15 bend terms as printed are correct: r
  // depends on a0 only through b2 / (a0 a3 w), and on eps1 through S_u.)
  TaperBendJacobian& Js = *J;
  Js.setZero();
  Js(0, 0) = taper1 * w * a1 * B.C_u * B.C_v + b1 * b2 * b3 / (a0 * a0 * w * a3) * pi * sin_r;
  Js(1, 0) = taper2 * w * a2 * B.C_u * B.S_v;
  Js(2, 0) = w * a3 * B.S_u;
  Js(0, 1) = taper1 * a0 * w * B.C_u * B.C_v;
  Js(1, 2) = taper2 * a0 * w * B.C_u * B.S_v;
  Js(0, 3) = b1 * b2 * b3 / (a0 * w * a3 * a3) * pi * sin_r;
  Js(2, 3) = a0 * w * B.S_u;
  Js(0, 4) =
      t1 * B.lnS_u * e1 + taper1 * a0 * w * a1 * B.lnC_u * B.C_v - b1 * b3 * pi * B.lnS_u * sin_r;
  Js(1, 4) = t2 * B.lnS_u * e2 + taper2 * a0 * w * a2 * B.lnC_u * B.S_v;
  Js(2, 4) = a0 * w * a3 * B.lnS_u;
  Js(0, 5) = taper1 * a0 * w * a1 * B.C_u * B.lnC_v;
  Js(1, 5) = taper2 * a0 * w * a2 * B.C_u * B.lnS_v;
  Js(0, 6) = B.S_u * e1;
  Js(1, 7) = B.S_u * e2;
  Js(0, 8) = cos_r;
  Js(0, 9) = -b1 * b3 / L * pi * sin_r;
  Js(0, 10) = -b1 * sin_r * pi * (e3 + b2) / L;
}

}  // namespace pbm
