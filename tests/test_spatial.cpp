// Quaternions (core/quaternion.h) and spatial vector algebra (core/spatial.h, Featherstone RBDA
// ch. 2): identities on random inputs from a fixed seed, each checked against an independent
// computation (Eigen's Quaterniond and AngleAxisd, 6x6 matrix algebra with Eigen's LU inverse,
// finite differences of a motion, exact quadrature over the solids) rather than against the same
// formula restated.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "core/quaternion.h"
#include "core/spatial.h"

namespace pbm {
namespace {

constexpr int kSamples = 500;
constexpr Real kTol = 1e-12;     // relative, for identities exact in real arithmetic
constexpr Real kRateTol = 1e-7;  // central differences with step kStep
constexpr Real kStep = 1e-5;     // [s]
constexpr Real kPi = std::numbers::pi_v<Real>;

// |a - b|_max <= tol max(1, |b|_max), printing both on failure.
template <typename A, typename B>
::testing::AssertionResult near(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b,
                                Real tol = kTol) {
  const Real scale = std::max<Real>(1, b.cwiseAbs().maxCoeff());
  const Real error = (a - b).cwiseAbs().maxCoeff();
  if (error <= tol * scale) return ::testing::AssertionSuccess();
  std::ostringstream out;
  out << "max error " << error << " > " << tol * scale << "\n" << a << "\nvs\n" << b;
  return ::testing::AssertionFailure() << out.str();
}

::testing::AssertionResult near(Real a, Real b, Real tol = kTol) {
  const Real scale = std::max<Real>(1, std::abs(b));
  if (std::abs(a - b) <= tol * scale) return ::testing::AssertionSuccess();
  std::ostringstream out;
  out.precision(17);
  out << a << " vs " << b << " (error " << std::abs(a - b) << ")";
  return ::testing::AssertionFailure() << out.str();
}

Vec4 to_vec4(const Eigen::Quaterniond& q) {
  return Vec4(q.w(), q.x(), q.y(), q.z());
}
Eigen::Quaterniond to_eigen(const Vec4& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

// Random inputs, the same on every run.
class Sampler {
 public:
  explicit Sampler(unsigned seed) : rng_(seed) {}

  Real uniform(Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng_); }
  Vec3 vec3(Real scale = 1) {
    return Vec3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale));
  }
  // Uniform on the unit 3-sphere (normalized Gaussian 4-vector).
  Vec4 unit_quaternion() {
    std::normal_distribution<Real> normal;
    Vec4 q(normal(rng_), normal(rng_), normal(rng_), normal(rng_));
    return q.normalized();
  }
  // A rotation matrix from Eigen, independent of rotation_from_quaternion.
  Mat3 rotation() { return to_eigen(unit_quaternion()).toRotationMatrix(); }
  MotionVector motion() { return {vec3(3), vec3(3)}; }
  ForceVector force() { return {vec3(3), vec3(3)}; }
  SpatialTransform transform() { return {rotation(), vec3(2)}; }
  // A physically valid body: m > 0, I_c = R diag(s_y + s_z, s_x + s_z, s_x + s_y) R^T from
  // second moments s >= 0 (so the principal moments obey the triangle inequality).
  SpatialInertia inertia() {
    const Vec3 s(uniform(0.01, 1), uniform(0.01, 1), uniform(0.01, 1));
    const Real m = uniform(0.1, 10);
    const Mat3 R = rotation();
    const Vec3 moments = m * Vec3(s.y() + s.z(), s.x() + s.z(), s.x() + s.y());
    return {m, vec3(1), R * moments.asDiagonal() * R.transpose()};
  }

 private:
  std::mt19937 rng_;
};

// ---------------------------------------------------------------------------------------------
// Quaternions

TEST(Quaternion, RotationIsOrthonormalWithUnitDeterminant) {
  Sampler sample(1);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 q = sample.unit_quaternion();
    const Mat3 R = rotation_from_quaternion(q);
    ASSERT_TRUE(near(R.transpose() * R, Mat3::Identity())) << "sample " << i;
    ASSERT_TRUE(near(R.determinant(), 1.0)) << "sample " << i;
    // q is normalized first: any positive multiple is the same rotation.
    ASSERT_TRUE(near(rotation_from_quaternion(sample.uniform(0.1, 10) * q), R)) << "sample " << i;
  }
}

TEST(Quaternion, RotationMatchesEigen) {
  Sampler sample(2);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 q = sample.unit_quaternion();
    ASSERT_TRUE(near(rotation_from_quaternion(q), to_eigen(q).toRotationMatrix()))
        << "sample " << i;
  }
  // Body -> world: a quarter turn about z takes the body x axis to the world y axis.
  const Vec4 quarter_z(std::sqrt(0.5), 0, 0, std::sqrt(0.5));
  EXPECT_TRUE(near(rotation_from_quaternion(quarter_z) * Vec3::UnitX(), Vec3::UnitY()));
}

// q and -q are the same rotation; the result is normalized with w >= 0.
::testing::AssertionResult same_rotation_quaternion(const Vec4& got, const Vec4& want) {
  if (got[0] < 0) return ::testing::AssertionFailure() << "w < 0: " << got.transpose();
  if (!near(got.norm(), 1.0)) return ::testing::AssertionFailure() << "not unit: " << got.norm();
  if (near(got, want) || near(got, Vec4(-want))) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << got.transpose() << " is neither " << want.transpose() << " nor its negative";
}

TEST(Quaternion, FromRotationInvertsRotation) {
  Sampler sample(3);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 q = sample.unit_quaternion();
    const Mat3 R = to_eigen(q).toRotationMatrix();
    ASSERT_TRUE(same_rotation_quaternion(quaternion_from_rotation(R), q)) << "sample " << i;
  }
  EXPECT_TRUE(near(quaternion_from_rotation(Mat3::Identity()), Vec4(1, 0, 0, 0)));
}

// Angles at and just below a half turn, where w -> 0 and a trace-only formula loses all digits.
TEST(Quaternion, FromRotationIsAccurateNearHalfTurn) {
  Sampler sample(4);
  const Real gaps[] = {0, 1e-12, 1e-9, 1e-6, 1e-3};
  for (int i = 0; i < kSamples; ++i) {
    Vec3 axis = sample.vec3();
    if (i < 3) axis = Vec3::Unit(i);  // exact half turns about the coordinate axes
    const Real angle = kPi - gaps[i % 5];
    const Vec4 q = to_vec4(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())));
    const Mat3 R = to_eigen(q).toRotationMatrix();
    const Vec4 got = quaternion_from_rotation(R);
    ASSERT_TRUE(same_rotation_quaternion(got, q)) << "sample " << i;
    ASSERT_TRUE(near(to_eigen(got).toRotationMatrix(), R)) << "sample " << i;
  }
}

TEST(Quaternion, ProductMatchesRotationProduct) {
  Sampler sample(5);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 a = sample.unit_quaternion(), b = sample.unit_quaternion();
    const Vec4 ab = quaternion_product(a, b);
    ASSERT_TRUE(near(to_eigen(ab).toRotationMatrix(),
                     to_eigen(a).toRotationMatrix() * to_eigen(b).toRotationMatrix()))
        << "sample " << i;
    ASSERT_TRUE(near(ab, to_vec4(to_eigen(a) * to_eigen(b)))) << "sample " << i;
    // Non-unit factors too: the product is bilinear, |a b| = |a| |b|.
    const Real sa = sample.uniform(0.1, 3), sb = sample.uniform(0.1, 3);
    ASSERT_TRUE(near(quaternion_product(sa * a, sb * b), Vec4(sa * sb * ab))) << "sample " << i;
  }
}

TEST(Quaternion, ConjugateIsInverseRotation) {
  Sampler sample(6);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 q = sample.unit_quaternion();
    const Vec4 q_conj = quaternion_conjugate(q);
    ASSERT_TRUE(near(quaternion_product(q, q_conj), Vec4(1, 0, 0, 0))) << "sample " << i;
    ASSERT_TRUE(
        near(to_eigen(q_conj).toRotationMatrix(), to_eigen(q).toRotationMatrix().transpose()))
        << "sample " << i;
  }
}

TEST(Quaternion, AxisAngleMatchesEigen) {
  Sampler sample(7);
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 axis = sample.vec3();
    const Real angle = sample.uniform(-2 * kPi, 2 * kPi);
    const Vec4 q = quaternion_from_axis_angle(axis, angle);
    ASSERT_TRUE(near(q.norm(), 1.0)) << "sample " << i;
    ASSERT_TRUE(near(to_eigen(q).toRotationMatrix(),
                     Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix()))
        << "sample " << i;
  }
  // Right-hand rule: +90 degrees about z takes x to y.
  EXPECT_TRUE(near(rotate(quaternion_from_axis_angle(Vec3(0, 0, 2), kPi / 2), Vec3::UnitX()),
                   Vec3::UnitY()));
}

TEST(Quaternion, RotateMatchesRotationMatrix) {
  Sampler sample(8);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 q = sample.unit_quaternion();
    const Vec3 v = sample.vec3(5);
    ASSERT_TRUE(near(rotate(q, v), Vec3(to_eigen(q) * v))) << "sample " << i;
    ASSERT_TRUE(near(rotate(q, v), Vec3(rotation_from_quaternion(q) * v))) << "sample " << i;
  }
}

// q(t) = q0 (x) exp(omega t / 2) turns at the constant body-frame rate omega; its derivative by
// central differences must be quaternion_rate(q(t), omega) at any t.
TEST(Quaternion, RateMatchesFiniteDifference) {
  Sampler sample(9);
  for (int i = 0; i < kSamples; ++i) {
    const Eigen::Quaterniond q0 = to_eigen(sample.unit_quaternion());
    const Vec3 omega = sample.vec3(3);  // [rad/s], body frame
    const auto q_at = [&](Real t) {
      return to_vec4(q0 *
                     Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * t, omega.normalized())));
    };
    const Real t = sample.uniform(-1, 1);
    const Vec4 q_dot_fd = (q_at(t + kStep) - q_at(t - kStep)) / (2 * kStep);
    ASSERT_TRUE(near(quaternion_rate(q_at(t), omega), q_dot_fd, kRateTol)) << "sample " << i;
  }
}

TEST(Quaternion, RateIsTangentToUnitSphere) {
  Sampler sample(10);
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 q = sample.unit_quaternion();
    const Vec3 omega = sample.vec3(10);
    const Vec4 q_dot = quaternion_rate(q, omega);
    ASSERT_TRUE(near(q.dot(q_dot), 0.0)) << "sample " << i;
    // |q-dot| = |omega| / 2 for a unit q.
    ASSERT_TRUE(near(q_dot.norm(), omega.norm() / 2)) << "sample " << i;
  }
}

// ---------------------------------------------------------------------------------------------
// Spatial vectors

template <typename A, typename B>
concept Addable = requires(A a, B b) {
  a + b;
};

static_assert(Addable<MotionVector, MotionVector> && Addable<ForceVector, ForceVector>);
static_assert(!Addable<MotionVector, ForceVector> && !Addable<ForceVector, MotionVector>,
              "a motion and a force are different spaces");

TEST(SpatialVector, ArithmeticMatchesSixVectors) {
  Sampler sample(11);
  for (int i = 0; i < kSamples; ++i) {
    const MotionVector a = sample.motion(), b = sample.motion();
    const ForceVector f = sample.force(), g = sample.force();
    const Real s = sample.uniform(-3, 3);
    ASSERT_TRUE(
        near(to_vec6(a + s * b - a * s), Vec6(to_vec6(a) + s * to_vec6(b) - s * to_vec6(a))));
    ASSERT_TRUE(near(to_vec6(-f + g * s), Vec6(-to_vec6(f) + s * to_vec6(g))));
    MotionVector sum = a;
    sum += b;
    sum -= s * a;
    ASSERT_TRUE(near(to_vec6(sum), Vec6(to_vec6(a) + to_vec6(b) - s * to_vec6(a))));
    ASSERT_TRUE(near(to_vec6(motion_from_vec6(to_vec6(a))), to_vec6(a)));
    ASSERT_TRUE(near(to_vec6(force_from_vec6(to_vec6(f))), to_vec6(f)));
    ASSERT_TRUE(near(dot(a, f), to_vec6(a).dot(to_vec6(f))));
  }
}

// ---------------------------------------------------------------------------------------------
// Cross products

TEST(SpatialCross, MatricesMatchFunctionsAndDuality) {
  Sampler sample(12);
  for (int i = 0; i < kSamples; ++i) {
    const MotionVector v = sample.motion(), m = sample.motion();
    const ForceVector f = sample.force();
    ASSERT_TRUE(near(crf(v), Mat6(-crm(v).transpose()))) << "sample " << i;
    ASSERT_TRUE(near(Vec6(crm(v) * to_vec6(m)), to_vec6(cross(v, m)))) << "sample " << i;
    ASSERT_TRUE(near(Vec6(crf(v) * to_vec6(f)), to_vec6(cross(v, f)))) << "sample " << i;
    // v x v = 0, and (v x m) . f = -m . (v x* f).
    ASSERT_TRUE(near(to_vec6(cross(v, v)), Vec6::Zero().eval())) << "sample " << i;
    ASSERT_TRUE(near(Vec6(crm(v) * to_vec6(v)), Vec6::Zero().eval())) << "sample " << i;
    ASSERT_TRUE(near(dot(cross(v, m), f), -dot(m, cross(v, f)))) << "sample " << i;
    // Anticommutative on motions.
    ASSERT_TRUE(near(to_vec6(cross(v, m)), to_vec6(-cross(m, v)))) << "sample " << i;
  }
}

// The cross products are the rates of change of vectors fixed in a body moving with velocity v
// (RBDA sec. 2.9). Frame B(t) starts on A and moves with rotation exp(omega~ t) about its origin,
// the origin at v_O t; a vector fixed in B, seen in A, is A_X_B(t) m_B.
TEST(SpatialCross, IsRateOfBodyFixedVector) {
  Sampler sample(13);
  for (int i = 0; i < kSamples; ++i) {
    const MotionVector v = sample.motion(), m = sample.motion();
    const ForceVector f = sample.force();
    const auto A_X_B = [&](Real t) {
      const Mat3 R = v.angular.norm() > 0
                         ? Mat3(Eigen::AngleAxisd(v.angular.norm() * t, v.angular.normalized()))
                         : Mat3::Identity();
      return SpatialTransform{.E = R, .r = -R.transpose() * (v.linear * t)};
    };
    // Check the construction: A_X_B(t) maps B's origin (zero in B) to v_O t in A.
    ASSERT_TRUE(near(Vec3(inverse(A_X_B(0.7)).r), Vec3(v.linear * 0.7))) << "sample " << i;
    const Vec6 m_rate =
        (to_vec6(transform_motion(A_X_B(kStep), m)) - to_vec6(transform_motion(A_X_B(-kStep), m))) /
        (2 * kStep);
    const Vec6 f_rate =
        (to_vec6(transform_force(A_X_B(kStep), f)) - to_vec6(transform_force(A_X_B(-kStep), f))) /
        (2 * kStep);
    ASSERT_TRUE(near(to_vec6(cross(v, m)), m_rate, kRateTol)) << "sample " << i;
    ASSERT_TRUE(near(to_vec6(cross(v, f)), f_rate, kRateTol)) << "sample " << i;
  }
}

// ---------------------------------------------------------------------------------------------
// Plücker transforms

TEST(SpatialTransform, InverseComposesToIdentity) {
  Sampler sample(14);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialTransform X = sample.transform();
    ASSERT_TRUE(near(motion_matrix(inverse(X) * X), Mat6::Identity().eval())) << "sample " << i;
    ASSERT_TRUE(near(motion_matrix(X * inverse(X)), Mat6::Identity().eval())) << "sample " << i;
    ASSERT_TRUE(near(motion_matrix(inverse(X)), Mat6(motion_matrix(X).inverse())))
        << "sample " << i;
    const MotionVector m = sample.motion();
    ASSERT_TRUE(near(to_vec6(transform_motion(inverse(X), transform_motion(X, m))), to_vec6(m)));
  }
}

TEST(SpatialTransform, MatricesMatchApplication) {
  Sampler sample(15);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialTransform X = sample.transform();
    const MotionVector m = sample.motion();
    const ForceVector f = sample.force();
    ASSERT_TRUE(near(Vec6(motion_matrix(X) * to_vec6(m)), to_vec6(transform_motion(X, m))))
        << "sample " << i;
    ASSERT_TRUE(near(Vec6(force_matrix(X) * to_vec6(f)), to_vec6(transform_force(X, f))))
        << "sample " << i;
  }
}

TEST(SpatialTransform, CompositionMatchesMatrixProduct) {
  Sampler sample(16);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialTransform X_AB = sample.transform(), X_BC = sample.transform();
    const SpatialTransform X_AC = X_BC * X_AB;
    ASSERT_TRUE(near(motion_matrix(X_AC), Mat6(motion_matrix(X_BC) * motion_matrix(X_AB))))
        << "sample " << i;
    ASSERT_TRUE(near(force_matrix(X_AC), Mat6(force_matrix(X_BC) * force_matrix(X_AB))))
        << "sample " << i;
  }
}

TEST(SpatialTransform, ForceMatrixIsInverseTranspose) {
  Sampler sample(17);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialTransform X = sample.transform();
    ASSERT_TRUE(near(force_matrix(X), Mat6(motion_matrix(X).inverse().transpose())))
        << "sample " << i;
  }
}

TEST(SpatialTransform, PowerIsInvariant) {
  Sampler sample(18);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialTransform X = sample.transform();
    const MotionVector m = sample.motion();
    const ForceVector f = sample.force();
    ASSERT_TRUE(near(dot(transform_motion(X, m), transform_force(X, f)), dot(m, f)))
        << "sample " << i;
  }
}

TEST(SpatialTransform, DistributesOverCrossProducts) {
  Sampler sample(19);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialTransform X = sample.transform();
    const MotionVector m1 = sample.motion(), m2 = sample.motion();
    const ForceVector f = sample.force();
    ASSERT_TRUE(near(to_vec6(transform_motion(X, cross(m1, m2))),
                     to_vec6(cross(transform_motion(X, m1), transform_motion(X, m2)))))
        << "sample " << i;
    ASSERT_TRUE(near(to_vec6(transform_force(X, cross(m1, f))),
                     to_vec6(cross(transform_motion(X, m1), transform_force(X, f)))))
        << "sample " << i;
  }
}

// Table 2.2: rx, ry, rz are coordinate rotations (B is A turned by theta), so E is the transpose
// of the active rotation; xlt(r) moves the reference point of a motion to r and of a force to r.
TEST(SpatialTransform, ElementaryTransforms) {
  Sampler sample(20);
  for (int i = 0; i < kSamples; ++i) {
    const Real theta = sample.uniform(-kPi, kPi);
    ASSERT_TRUE(near(rot_x(theta).E, Mat3(Eigen::AngleAxisd(theta, Vec3::UnitX()).inverse())));
    ASSERT_TRUE(near(rot_y(theta).E, Mat3(Eigen::AngleAxisd(theta, Vec3::UnitY()).inverse())));
    ASSERT_TRUE(near(rot_z(theta).E, Mat3(Eigen::AngleAxisd(theta, Vec3::UnitZ()).inverse())));
    ASSERT_TRUE(near(rot_z(theta).r, Vec3::Zero().eval()));

    const Vec3 r = sample.vec3(2);
    const MotionVector m = sample.motion();
    const ForceVector f = sample.force();
    // Velocity of the body point at r: v_O + omega x r; moment about r: n_O - r x f.
    const MotionVector m_at_r = transform_motion(translation(r), m);
    ASSERT_TRUE(near(m_at_r.angular, m.angular));
    ASSERT_TRUE(near(m_at_r.linear, Vec3(m.linear + m.angular.cross(r))));
    const ForceVector f_at_r = transform_force(translation(r), f);
    ASSERT_TRUE(near(f_at_r.force, f.force));
    ASSERT_TRUE(near(f_at_r.moment, Vec3(f.moment - r.cross(f.force))));

    // X = rot(E) xlt(r) = [E 0; -E r~ E].
    const Mat3 E = sample.rotation();
    Mat6 X_expected;
    X_expected << E, Mat3::Zero(), -E * skew(r), E;
    ASSERT_TRUE(near(motion_matrix(rotation(E) * translation(r)), X_expected));
    ASSERT_TRUE(near(motion_matrix(SpatialTransform{.E = E, .r = r}), X_expected));
  }
  // A quarter turn about z: A's x axis is B's -y axis.
  EXPECT_TRUE(
      near(transform_motion(rot_z(kPi / 2), MotionVector{Vec3::UnitX(), Vec3::Zero()}).angular,
           Vec3(-Vec3::UnitY())));
}

// ---------------------------------------------------------------------------------------------
// Spatial inertia

TEST(SpatialInertia, MatrixIsSymmetricPositiveDefinite) {
  Sampler sample(21);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialInertia I = sample.inertia();
    const Mat6 M = inertia_matrix(I);
    ASSERT_TRUE(near(M, Mat6(M.transpose()))) << "sample " << i;
    const Eigen::SelfAdjointEigenSolver<Mat6> eigen(M);
    ASSERT_GT(eigen.eigenvalues().minCoeff(), 0) << "sample " << i;
    const MotionVector v = sample.motion();
    ASSERT_TRUE(near(Vec6(M * to_vec6(v)), to_vec6(I * v))) << "sample " << i;
  }
}

// 1/2 v . I v = 1/2 m |v_c|^2 + 1/2 omega . I_c omega with v_c = v_O + omega x c the velocity of
// the centre of mass (König), and the same in every frame.
TEST(SpatialInertia, KineticEnergyIsFrameInvariant) {
  Sampler sample(22);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialInertia I_A = sample.inertia();
    const MotionVector v_A = sample.motion();
    const Real energy = 0.5 * dot(v_A, I_A * v_A);
    const Vec3 v_c = v_A.linear + v_A.angular.cross(I_A.c);
    ASSERT_TRUE(near(
        energy, 0.5 * I_A.m * v_c.squaredNorm() + 0.5 * v_A.angular.dot(I_A.I_c * v_A.angular)))
        << "sample " << i;
    const SpatialTransform X = sample.transform();
    const SpatialInertia I_B = transform_inertia(X, I_A);
    const MotionVector v_B = transform_motion(X, v_A);
    ASSERT_TRUE(near(0.5 * dot(v_B, I_B * v_B), energy)) << "sample " << i;
    // Momentum is a force vector: it transforms with X*.
    ASSERT_TRUE(near(to_vec6(I_B * v_B), to_vec6(transform_force(X, I_A * v_A)))) << "sample " << i;
  }
}

TEST(SpatialInertia, TransformMatchesMatrixProduct) {
  Sampler sample(23);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialInertia I = sample.inertia();
    const SpatialTransform X = sample.transform();
    const Mat6 expected = force_matrix(X) * inertia_matrix(I) * motion_matrix(X).inverse();
    ASSERT_TRUE(near(inertia_matrix(transform_inertia(X, I)), expected)) << "sample " << i;
  }
}

// About a point p (frame translated to p), the rotational block is
// I_c + m (|d|^2 1 - d d^T) with d = c - p.
TEST(SpatialInertia, ShiftAgreesWithParallelAxisTheorem) {
  Sampler sample(24);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialInertia I = sample.inertia();
    const Vec3 p = sample.vec3(2);
    const Vec3 d = I.c - p;
    const Mat3 expected = I.I_c + I.m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
    const Mat6 shifted = inertia_matrix(transform_inertia(translation(p), I));
    ASSERT_TRUE(near(Mat3(shifted.topLeftCorner<3, 3>()), expected)) << "sample " << i;
    ASSERT_TRUE(near(Mat3(shifted.bottomRightCorner<3, 3>()), Mat3(I.m * Mat3::Identity())));
    // The first moment m c~ relative to p.
    ASSERT_TRUE(near(Mat3(shifted.topRightCorner<3, 3>()), Mat3(I.m * skew(d))));
  }
}

TEST(SpatialInertia, SumMatchesMatrixSum) {
  Sampler sample(25);
  for (int i = 0; i < kSamples; ++i) {
    const SpatialInertia a = sample.inertia(), b = sample.inertia();
    const SpatialInertia sum = a + b;
    ASSERT_TRUE(near(inertia_matrix(sum), Mat6(inertia_matrix(a) + inertia_matrix(b))))
        << "sample " << i;
    const MotionVector v = sample.motion();
    ASSERT_TRUE(near(to_vec6(sum * v), to_vec6(a * v + b * v))) << "sample " << i;
    ASSERT_TRUE(near(inertia_matrix(a + SpatialInertia{}), inertia_matrix(a))) << "sample " << i;
  }
  EXPECT_TRUE(near(inertia_matrix(SpatialInertia{} + SpatialInertia{}), Mat6::Zero().eval()));
}

// A particle's momentum: linear m v_p with v_p = v_O + omega x c, angular c x (m v_p).
TEST(SpatialInertia, PointMassMomentum) {
  Sampler sample(26);
  for (int i = 0; i < kSamples; ++i) {
    const Real m = sample.uniform(0.1, 10);
    const Vec3 c = sample.vec3(2);
    const MotionVector v = sample.motion();
    const ForceVector h = point_mass_inertia(m, c) * v;
    const Vec3 p = m * (v.linear + v.angular.cross(c));
    ASSERT_TRUE(near(h.force, p)) << "sample " << i;
    ASSERT_TRUE(near(h.moment, Vec3(c.cross(p)))) << "sample " << i;
  }
}

TEST(SpatialInertia, SolidsMatchClosedForms) {
  // Sphere, m = 3 kg, r = 2 m: 2/5 m r^2 = 4.8 kg m^2.
  const SpatialInertia sphere = solid_sphere_inertia(3, 2);
  EXPECT_EQ(sphere.m, 3);
  EXPECT_TRUE(near(sphere.c, Vec3::Zero().eval()));
  EXPECT_TRUE(near(sphere.I_c, Mat3(4.8 * Mat3::Identity())));
  // Box, m = 12 kg, sides 1 x 2 x 3 m: m (b^2 + c^2) / 12 = 13, 10, 5 kg m^2.
  const SpatialInertia box = solid_box_inertia(12, Vec3(0.5, 1, 1.5));
  EXPECT_EQ(box.m, 12);
  EXPECT_TRUE(near(box.c, Vec3::Zero().eval()));
  EXPECT_TRUE(near(box.I_c, Mat3(Vec3(13, 10, 5).asDiagonal())));
  // Cylinder, m = 6 kg, r = 1 m, h = 2 m: I_zz = m r^2 / 2 = 3, I_xx = m (3 r^2 + h^2) / 12 = 3.5.
  const SpatialInertia cylinder = solid_cylinder_inertia(6, 1, 2);
  EXPECT_EQ(cylinder.m, 6);
  EXPECT_TRUE(near(cylinder.c, Vec3::Zero().eval()));
  EXPECT_TRUE(near(cylinder.I_c, Mat3(Vec3(3.5, 3.5, 3).asDiagonal())));
}

// The inertia per unit mass of a homogeneous solid, int (|p|^2 1 - p p^T) dV / int dV, by a
// quadrature exact for these integrands: 3-point Gauss-Legendre (exact to degree 5) along
// polynomial directions and the uniform rule (exact for trigonometric degree < 8) around the
// circle. Each sample point carries its weight times the volume element.
struct QuadraturePoint {
  Vec3 p;
  Real weight;
};

Mat3 inertia_per_unit_mass(const std::vector<QuadraturePoint>& points) {
  Mat3 sum = Mat3::Zero();
  Real volume = 0;
  for (const QuadraturePoint& q : points) {
    sum += q.weight * (q.p.squaredNorm() * Mat3::Identity() - q.p * q.p.transpose());
    volume += q.weight;
  }
  return sum / volume;
}

constexpr Real kGaussNode[3] = {-0.7745966692414833770, 0, 0.7745966692414833770};  // sqrt(3/5)
constexpr Real kGaussWeight[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
constexpr int kAngles = 8;

TEST(SpatialInertia, SolidsMatchQuadrature) {
  Sampler sample(27);
  for (int i = 0; i < 50; ++i) {
    const Real m = sample.uniform(0.1, 10);
    const Vec3 h(sample.uniform(0.1, 2), sample.uniform(0.1, 2), sample.uniform(0.1, 2));
    const Real radius = sample.uniform(0.1, 2), height = sample.uniform(0.1, 3);

    std::vector<QuadraturePoint> box, sphere, cylinder;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        for (int c = 0; c < 3; ++c) {
          const Real w = kGaussWeight[a] * kGaussWeight[b] * kGaussWeight[c];
          box.push_back(
              {Vec3(h.x() * kGaussNode[a], h.y() * kGaussNode[b], h.z() * kGaussNode[c]), w});
        }
        for (int k = 0; k < kAngles; ++k) {
          const Real phi = 2 * kPi * k / kAngles;
          // Sphere: rho in [0, R], u = cos(polar angle) in [-1, 1], dV = rho^2 d rho du d phi.
          const Real rho = radius * (1 + kGaussNode[a]) / 2, u = kGaussNode[b];
          const Real across = rho * std::sqrt(1 - u * u);
          sphere.push_back({Vec3(across * std::cos(phi), across * std::sin(phi), rho * u),
                            kGaussWeight[a] * kGaussWeight[b] * rho * rho});
          // Cylinder: s in [0, R], z in [-H/2, H/2], dV = s ds dz d phi.
          const Real s = radius * (1 + kGaussNode[a]) / 2, z = height / 2 * kGaussNode[b];
          cylinder.push_back({Vec3(s * std::cos(phi), s * std::sin(phi), z),
                              kGaussWeight[a] * kGaussWeight[b] * s});
        }
      }
    }
    ASSERT_TRUE(near(solid_box_inertia(m, h).I_c, Mat3(m * inertia_per_unit_mass(box))))
        << "sample " << i;
    ASSERT_TRUE(near(solid_sphere_inertia(m, radius).I_c, Mat3(m * inertia_per_unit_mass(sphere))))
        << "sample " << i;
    ASSERT_TRUE(near(solid_cylinder_inertia(m, radius, height).I_c,
                     Mat3(m * inertia_per_unit_mass(cylinder))))
        << "sample " << i;
  }
}

}  // namespace
}  // namespace pbm
