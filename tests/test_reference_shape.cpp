// Reference shapes s(u; q_s) of chapter 2 and their Jacobians J = ds/dq_s (2.6): analytic /
// chain-rule Jacobians against central finite differences, finiteness at the poles and seam, and
// closed-form special cases that tie the three shape kinds together.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "deform/axis_deformations.h"
#include "deform/reference_shape.h"
#include "deform/superquadric.h"

namespace pbm {
namespace {

constexpr Real pi = std::numbers::pi;
constexpr ShapeKind kKinds[3] = {ShapeKind::superquadric, ShapeKind::taper_bend,
                                 ShapeKind::general};

Real uniform(std::mt19937_64& rng, Real lo, Real hi) {
  return std::uniform_real_distribution<Real>(lo, hi)(rng);
}

// Random valid parameters with every deformation active.
VecX random_parameters(ShapeKind kind, std::mt19937_64& rng) {
  VecX q_s = default_shape_parameters(kind);
  q_s(0) = uniform(rng, 0.5, 2.0);
  for (int i = 1; i <= 3; ++i) q_s(i) = uniform(rng, 0.3, 1.5);
  q_s(4) = uniform(rng, 0.3, 3.0);
  q_s(5) = uniform(rng, 0.3, 3.0);
  if (kind == ShapeKind::taper_bend) {
    q_s(6) = uniform(rng, -0.9, 0.9);
    q_s(7) = uniform(rng, -0.9, 0.9);
    q_s(8) = uniform(rng, -0.5, 0.5);
    q_s(9) = uniform(rng, -0.9, 0.9);
    q_s(10) = uniform(rng, 0.2, 1.0);
  }
  if (kind == ShapeKind::general) {
    for (int i = 1; i <= 3; ++i) {
      q_s(twist_index(i)) = uniform(rng, -1.0, 1.0);
      for (int j = 1; j <= 3; ++j) {
        if (j == i) continue;
        q_s(taper_index(i, j)) = uniform(rng, -0.9, 0.9);
        q_s(shear_index(i, j)) = uniform(rng, -0.5, 0.5);
        q_s(bend_amount_index(i, j)) = uniform(rng, -0.5, 0.5);
        q_s(bend_location_index(i, j)) = uniform(rng, -0.9, 0.9);
        q_s(bend_range_index(i, j)) = uniform(rng, 0.2, 1.0);
      }
    }
  }
  for (int k = 0; k < q_s.size(); ++k) {
    EXPECT_EQ(check_shape_parameter(kind, k, q_s(k)), "") << shape_parameter_name(kind, k);
  }
  return q_s;
}

Vec3 shape(ShapeKind kind, const VecX& q_s, Real u, Real v, Real w) {
  Vec3 s;
  evaluate_reference_shape(kind, q_s, u, v, w, s, nullptr);
  return s;
}

// Largest |J_fd - J| / max(1, |J|) over the entries; central differences with Richardson
// extrapolation (error O(h^4)) so truncation stays far below the tolerance even where high
// derivatives in eps grow like ln|cos u|^k near the poles.
Real jacobian_error(ShapeKind kind, const VecX& q_s, Real u, Real v, Real w) {
  const int n_s = shape_parameter_count(kind);
  Mat3X J(3, n_s);
  Vec3 s;
  evaluate_reference_shape(kind, q_s, u, v, w, s, &J);
  EXPECT_TRUE(s.isApprox(shape(kind, q_s, u, v, w), 0.0)) << "s must not depend on J != nullptr";
  Real worst = 0;
  for (int k = 0; k < n_s; ++k) {
    const Real h = 1e-4 * std::max(Real(1), std::abs(q_s(k)));
    auto central = [&](Real step) {
      VecX plus = q_s, minus = q_s;
      plus(k) += step;
      minus(k) -= step;
      return Vec3((shape(kind, plus, u, v, w) - shape(kind, minus, u, v, w)) / (2 * step));
    };
    const Vec3 fd = (4 * central(h / 2) - central(h)) / 3;
    for (int r = 0; r < 3; ++r) {
      const Real err = std::abs(fd(r) - J(r, k)) / std::max(Real(1), std::abs(J(r, k)));
      if (!(err <= worst)) worst = err;  // also catches NaN
    }
  }
  return worst;
}

TEST(ReferenceShape, SignedPowersAreFiniteAtZero) {
  EXPECT_EQ(signed_power(0.0, 0.3), 0.0);
  EXPECT_EQ(log_signed_power(0.0, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(signed_power(-0.25, 0.5), -0.5);
  EXPECT_DOUBLE_EQ(log_signed_power(-0.25, 0.5), -0.5 * std::log(0.25));
  EXPECT_DOUBLE_EQ(signed_power(0.125, 1.0 / 3.0), 0.5);
}

TEST(ReferenceShape, JacobianMatchesFiniteDifferencesInside) {
  std::mt19937_64 rng(7);
  for (ShapeKind kind : kKinds) {
    Real worst = 0;
    for (int sample = 0; sample < 240; ++sample) {
      const VecX q_s = random_parameters(kind, rng);
      const Real u = uniform(rng, -pi / 2, pi / 2);
      const Real v = uniform(rng, -pi, pi);
      const Real w = sample % 2 == 0 ? 1.0 : uniform(rng, 0.5, 1.0);
      const Real err = jacobian_error(kind, q_s, u, v, w);
      EXPECT_LT(err, 1e-6) << "kind " << int(kind) << " u " << u << " v " << v << " w " << w;
      worst = std::max(worst, err);
    }
    std::printf("kind %d: max FD error inside %.3g\n", int(kind), worst);
  }
}

TEST(ReferenceShape, JacobianMatchesFiniteDifferencesNearPolesAndSeam) {
  std::mt19937_64 rng(11);
  constexpr Real kSpecialV[5] = {-pi, -pi / 2, 0, pi / 2, pi};
  for (ShapeKind kind : kKinds) {
    Real worst = 0;
    for (int sample = 0; sample < 240; ++sample) {
      const VecX q_s = random_parameters(kind, rng);
      Real u = uniform(rng, -pi / 2, pi / 2);
      Real v = uniform(rng, -pi, pi);
      if (sample % 2 == 0) {  // near a pole
        u = (sample % 4 == 0 ? 1 : -1) * (pi / 2 - 1e-3 * uniform(rng, 0, 1));
      } else {  // near the seam v = +-pi or the lines sin v = 0, cos v = 0
        v = std::clamp(kSpecialV[sample / 2 % 5] + 1e-3 * uniform(rng, -1, 1), -pi, pi);
      }
      const Real w = sample % 3 == 0 ? 1.0 : uniform(rng, 0.5, 1.0);
      const Real err = jacobian_error(kind, q_s, u, v, w);
      EXPECT_LT(err, 1e-6) << "kind " << int(kind) << " u " << u << " v " << v << " w " << w;
      worst = std::max(worst, err);
    }
    std::printf("kind %d: max FD error near poles/seam %.3g\n", int(kind), worst);
  }
}

// J-dot q_s-dot of (3.18) for the superquadric: its exact second derivative along r against the
// derivative of the Jacobian along r, (J(q + h r) - J(q - h r)) r / 2h, inside and near poles.
TEST(ReferenceShape, SuperquadricSecondDerivativeMatchesTheJacobiansDifference) {
  std::mt19937_64 rng(13);
  Real worst = 0;
  for (int sample = 0; sample < 240; ++sample) {
    const VecX q_s = random_parameters(ShapeKind::superquadric, rng);
    VecX r(6);
    for (int k = 0; k < 6; ++k) r(k) = uniform(rng, -1, 1);
    Real u = uniform(rng, -pi / 2, pi / 2);
    if (sample % 3 == 0) u = (sample % 2 == 0 ? 1 : -1) * (pi / 2 - 1e-3 * uniform(rng, 0, 1));
    const Real v = uniform(rng, -pi, pi);
    const Real w = uniform(rng, 0.5, 1.0);
    const SuperquadricAngles angles = superquadric_angles(u, v);
    const Vec3 exact = superquadric_second_derivative(q_s, angles, w, r);
    auto Jr = [&](Real step) {
      SuperquadricJacobian J;
      Vec3 e;
      evaluate_superquadric(q_s + step * r, angles, w, e, &J);
      return Vec3(J * r);
    };
    const Real h = 1e-4;
    auto central = [&](Real step) { return Vec3((Jr(step) - Jr(-step)) / (2 * step)); };
    const Vec3 fd = (4 * central(h / 2) - central(h)) / 3;
    const Real err = (fd - exact).norm() / std::max(Real(1), exact.norm());
    EXPECT_LT(err, 1e-7) << "u " << u << " v " << v;
    worst = std::max(worst, err);
  }
  std::printf("superquadric J-dot q-dot: max FD error %.3g\n", worst);
}

TEST(ReferenceShape, FiniteExactlyAtPolesAndSeam) {
  std::mt19937_64 rng(13);
  constexpr Real kU[3] = {-pi / 2, 0, pi / 2};
  constexpr Real kV[5] = {-pi, -pi / 2, 0, pi / 2, pi};
  for (ShapeKind kind : kKinds) {
    for (int sample = 0; sample < 4; ++sample) {
      const VecX q_s = random_parameters(kind, rng);
      for (Real u : kU) {
        for (Real v : kV) {
          Mat3X J(3, shape_parameter_count(kind));
          Vec3 s;
          evaluate_reference_shape(kind, q_s, u, v, 1.0, s, &J);
          EXPECT_TRUE(s.allFinite()) << "u " << u << " v " << v;
          EXPECT_TRUE(J.allFinite()) << "u " << u << " v " << v;
        }
      }
    }
  }
  // At u = 0, v = 0 the sines are exactly 0: the eps1 column of (2.9) has the limit 0 in row 3.
  Mat3X J(3, 6);
  Vec3 s;
  evaluate_reference_shape(ShapeKind::superquadric,
                           default_shape_parameters(ShapeKind::superquadric), 0.0, 0.0, 1.0, s, &J);
  EXPECT_EQ(J(2, 4), 0.0);
  EXPECT_EQ(J(1, 5), 0.0);
  EXPECT_TRUE(s.isApprox(Vec3(1, 0, 0)));
}

TEST(ReferenceShape, UnitAspectSuperquadricIsSphereOfRadiusA0) {
  std::mt19937_64 rng(17);
  VecX q_s = default_shape_parameters(ShapeKind::superquadric);
  for (int sample = 0; sample < 100; ++sample) {
    q_s(0) = uniform(rng, 0.1, 5.0);
    const Real u = uniform(rng, -pi / 2, pi / 2), v = uniform(rng, -pi, pi);
    const Real w = uniform(rng, 0.1, 1.0);
    const Vec3 s = shape(ShapeKind::superquadric, q_s, u, v, w);
    EXPECT_NEAR(s.norm(), q_s(0) * w, 1e-12);
    // Latitude u and longitude v of (2.7).
    EXPECT_NEAR(s.z(), q_s(0) * w * std::sin(u), 1e-12);
    EXPECT_NEAR(std::atan2(s.y(), s.x()), v, 1e-9);
  }
}

// Both deformed kinds reduce to e when their deformations vanish, in s and in the a, eps columns.
TEST(ReferenceShape, ZeroDeformationEqualsSuperquadric) {
  std::mt19937_64 rng(19);
  for (ShapeKind kind : {ShapeKind::taper_bend, ShapeKind::general}) {
    for (int sample = 0; sample < 50; ++sample) {
      const VecX q_e = random_parameters(ShapeKind::superquadric, rng);
      VecX q_s = default_shape_parameters(kind);
      q_s.head<6>() = q_e;
      const Real u = uniform(rng, -pi / 2, pi / 2), v = uniform(rng, -pi, pi);
      const Real w = uniform(rng, 0.5, 1.0);
      Mat3X J_e(3, 6), J_s(3, shape_parameter_count(kind));
      Vec3 e, s;
      evaluate_reference_shape(ShapeKind::superquadric, q_e, u, v, w, e, &J_e);
      evaluate_reference_shape(kind, q_s, u, v, w, s, &J_s);
      EXPECT_LT((s - e).norm(), 1e-12);
      EXPECT_LT((J_s.leftCols<6>() - J_e).cwiseAbs().maxCoeff(), 1e-10);
    }
  }
}

// The axis-3 stage T3 (2.15)-(2.17) with t_3^1 = t1, t_3^2 = t2, b^{a1}_3 = b1, b^{l1}_3 = b2,
// b^{r1}_3 = b3 and everything else zero is (2.10) term by term, so s and every Jacobian column
// (mapped) must agree: the hand-derived (2.12) against the chain rule through T2(T1(T3)).
TEST(ReferenceShape, GeneralWithAxis3TaperAndBendEqualsTaperBend) {
  std::mt19937_64 rng(23);
  int mapped[11] = {0,
                    1,
                    2,
                    3,
                    4,
                    5,
                    taper_index(3, 1),
                    taper_index(3, 2),
                    bend_amount_index(3, 1),
                    bend_location_index(3, 1),
                    bend_range_index(3, 1)};
  for (int sample = 0; sample < 100; ++sample) {
    const VecX q_tb = random_parameters(ShapeKind::taper_bend, rng);
    VecX q_g = default_shape_parameters(ShapeKind::general);
    for (int k = 0; k < 11; ++k) q_g(mapped[k]) = q_tb(k);
    if (sample < 30) {  // first alone: the single taper t_3^1 against t1
      for (int k = 7; k < 10; ++k) q_g(mapped[k]) = 0;
      q_g(mapped[10]) = 1;
    }
    VecX q_tb_used = q_tb;
    for (int k = 6; k < 11; ++k) q_tb_used(k) = q_g(mapped[k]);
    const Real u = uniform(rng, -pi / 2, pi / 2), v = uniform(rng, -pi, pi);
    const Real w = uniform(rng, 0.5, 1.0);
    Mat3X J_tb(3, 11), J_g(3, 39);
    Vec3 s_tb, s_g;
    evaluate_reference_shape(ShapeKind::taper_bend, q_tb_used, u, v, w, s_tb, &J_tb);
    evaluate_reference_shape(ShapeKind::general, q_g, u, v, w, s_g, &J_g);
    EXPECT_LT((s_tb - s_g).norm(), 1e-12);
    for (int k = 0; k < 11; ++k) {
      EXPECT_LT((J_tb.col(k) - J_g.col(mapped[k])).norm(), 1e-10)
          << shape_parameter_name(ShapeKind::taper_bend, k);
    }
  }
}

// A lone twist tau_i is a right-handed rotation about axis i by pi tau_i e_i / (a0 a_i w),
// (2.18)/(2.22)/(2.26); checks the axis bookkeeping of T1 and T2 (see axis_deformations.h).
TEST(ReferenceShape, LoneTwistIsRotationAboutItsAxis) {
  std::mt19937_64 rng(29);
  for (int i = 1; i <= 3; ++i) {
    for (int sample = 0; sample < 20; ++sample) {
      VecX q_g = default_shape_parameters(ShapeKind::general);
      q_g.head<6>() = random_parameters(ShapeKind::superquadric, rng);
      q_g(twist_index(i)) = uniform(rng, -1, 1);
      const Real u = uniform(rng, -pi / 2, pi / 2), v = uniform(rng, -pi, pi);
      const Real w = uniform(rng, 0.5, 1.0);
      const Vec3 e = shape(ShapeKind::superquadric, q_g.head<6>(), u, v, w);
      const Real phi = e(i - 1) / (q_g(0) * q_g(i) * w) * pi * q_g(twist_index(i));
      const Vec3 axis = Vec3::Unit(i - 1);
      const Vec3 expected = Eigen::AngleAxisd(phi, axis) * e;
      EXPECT_LT((shape(ShapeKind::general, q_g, u, v, w) - expected).norm(), 1e-12);
    }
  }
}

// A lone taper t_i^j scales coordinate j by (t_i^j e_i / (a0 a_i w) + 1), a lone shear s_i^j adds
// s_i^j e_i to it: (2.16)/(2.20)/(2.24) with the other terms zero.
TEST(ReferenceShape, LoneTaperAndShearScaleAndShiftOneCoordinate) {
  std::mt19937_64 rng(31);
  for (int i = 1; i <= 3; ++i) {
    for (int j = 1; j <= 3; ++j) {
      if (j == i) continue;
      VecX q_g = default_shape_parameters(ShapeKind::general);
      q_g.head<6>() = random_parameters(ShapeKind::superquadric, rng);
      const Real t = uniform(rng, -0.9, 0.9), shear = uniform(rng, -0.5, 0.5);
      q_g(taper_index(i, j)) = t;
      q_g(shear_index(i, j)) = shear;
      const Real u = uniform(rng, -pi / 2, pi / 2), v = uniform(rng, -pi, pi);
      const Real w = uniform(rng, 0.5, 1.0);
      Vec3 expected = shape(ShapeKind::superquadric, q_g.head<6>(), u, v, w);
      const Real e_i = expected(i - 1);
      expected(j - 1) = (t * e_i / (q_g(0) * q_g(i) * w) + 1) * expected(j - 1) + shear * e_i;
      EXPECT_LT((shape(ShapeKind::general, q_g, u, v, w) - expected).norm(), 1e-12)
          << "i " << i << " j " << j;
    }
  }
}

TEST(ReferenceShape, ParameterMetadata) {
  EXPECT_EQ(shape_parameter_count(ShapeKind::superquadric), 6);
  EXPECT_EQ(shape_parameter_count(ShapeKind::taper_bend), 11);
  EXPECT_EQ(shape_parameter_count(ShapeKind::general), 39);
  for (ShapeKind kind : kKinds) {
    const VecX q_s = default_shape_parameters(kind);
    ASSERT_EQ(q_s.size(), shape_parameter_count(kind));
    for (int k = 0; k < q_s.size(); ++k) {
      EXPECT_EQ(check_shape_parameter(kind, k, q_s(k)), "") << shape_parameter_name(kind, k);
    }
    // The default is the unit sphere.
    EXPECT_NEAR(shape(kind, q_s, 0.3, -1.2, 1.0).norm(), 1.0, 1e-12);
    EXPECT_NE(check_shape_parameter(kind, 0, 0.0), "");
    EXPECT_NE(check_shape_parameter(kind, 4, -1.0), "");
    EXPECT_NE(check_shape_parameter(kind, 1, std::nan("")), "");
  }
  EXPECT_EQ(shape_parameter_name(ShapeKind::superquadric, 4), "eps1");
  EXPECT_EQ(shape_parameter_name(ShapeKind::taper_bend, 10), "b3");
  EXPECT_EQ(shape_parameter_name(ShapeKind::general, 6), "tau1");
  EXPECT_EQ(shape_parameter_name(ShapeKind::general, taper_index(3, 1)), "t3^1");
  EXPECT_EQ(shape_parameter_name(ShapeKind::general, shear_index(1, 2)), "s1^2");
  EXPECT_EQ(shape_parameter_name(ShapeKind::general, bend_amount_index(2, 3)), "ba2^3");
  EXPECT_EQ(shape_parameter_name(ShapeKind::general, 38), "br3^2");
  EXPECT_EQ(check_shape_parameter(ShapeKind::taper_bend, 6, 1.5), "must be in [-1, 1]");
  EXPECT_EQ(check_shape_parameter(ShapeKind::taper_bend, 8, -7.0), "");
  EXPECT_EQ(check_shape_parameter(ShapeKind::taper_bend, 10, 0.0), "must be in (0, 1]");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, taper_index(2, 1), -1.5),
            "must be in [-1, 1]");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, twist_index(2), 5.0), "");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, shear_index(3, 2), -4.0), "");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, bend_amount_index(3, 2), 3.0), "");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, bend_location_index(1, 3), 2.0),
            "must be in [-1, 1]");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, bend_range_index(2, 1), 1.5),
            "must be in (0, 1]");
  EXPECT_EQ(check_shape_parameter(ShapeKind::general, 2, 1.7), "");  // a2 > 1 allowed
  EXPECT_NE(check_shape_parameter(ShapeKind::general, 39, 1.0), "");
}

}  // namespace
}  // namespace pbm
