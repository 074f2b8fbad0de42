// The narrowphase of segment-segment collisions (collide/convex_contacts.h) against closed forms:
// two spheres, a sphere on a box's face, two crossed capsules, a box standing on a box (four
// points, one at each corner of the smaller face), a capsule lying on a box and a log on a log
// (two points, under their ends), an upright cylinder on a box, solids apart, and the same pair
// swapped (the normal turns round). Bullet is single precision here: 1e-5 m.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "collide/convex_contacts.h"
#include "core/quaternion.h"

namespace pbm {
namespace {

constexpr Real kTolerance = 1e-5;  // [m]: Bullet's float

ConvexSolid solid(ConvexKind kind, const Vec3& size, const Vec3& center,
                  const Mat3& rotation = Mat3::Identity()) {
  return {.kind = kind, .size = size, .rotation = rotation, .center = center};
}

Mat3 about_z(Real angle) {
  return Eigen::AngleAxis<Real>(angle, Vec3::UnitZ()).toRotationMatrix();
}

void expect_near(const Vec3& a, const Vec3& b, Real tolerance) {
  EXPECT_LT((a - b).norm(), tolerance) << a.transpose() << " vs " << b.transpose();
}

TEST(ConvexContacts, TwoSpheresTouchOnTheLineOfTheirCentres) {
  const ConvexSolid a = solid(ConvexKind::sphere, Vec3(0.5, 0, 0), Vec3(0.3, 0.4, 0.8));
  const ConvexSolid b = solid(ConvexKind::sphere, Vec3(0.4, 0, 0), Vec3(0.3, 0.4, 0.0));
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(a, b, out), 1);
  EXPECT_NEAR(out[0].depth, 0.5 + 0.4 - 0.8, kTolerance);
  expect_near(out[0].normal, Vec3::UnitZ(), kTolerance);
  // Midway between b's top (0.4) and a's bottom (0.3).
  expect_near(out[0].point, Vec3(0.3, 0.4, 0.35), kTolerance);
  ASSERT_EQ(convex_contacts(b, a, out), 1);
  expect_near(out[0].normal, -Vec3::UnitZ(), kTolerance);
}

TEST(ConvexContacts, ASphereOnABoxFaceSinksByItsOverlap) {
  const ConvexSolid box = solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3::Zero(), about_z(0.3));
  const ConvexSolid ball = solid(ConvexKind::sphere, Vec3(0.2, 0, 0), Vec3(0.1, -0.05, 0.25));
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(ball, box, out), 1);
  EXPECT_NEAR(out[0].depth, 0.05, kTolerance);
  expect_near(out[0].normal, Vec3::UnitZ(), kTolerance);
  expect_near(out[0].point, Vec3(0.1, -0.05, 0.075), kTolerance);  // between z 0.05 and 0.1
}

TEST(ConvexContacts, CrossedCapsulesTouchWhereTheirAxesPassClosest) {
  // a along x at height 0.15, b along y: the axes pass 0.15 apart, the radii sum to 0.2.
  const Mat3 along_x =
      Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix();
  const Mat3 along_y =
      Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix();
  const ConvexSolid a = solid(ConvexKind::capsule, Vec3(0.1, 0, 0.5), Vec3(0.2, 0, 0.15), along_x);
  const ConvexSolid b = solid(ConvexKind::capsule, Vec3(0.1, 0, 0.5), Vec3(0, 0.3, 0), along_y);
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(a, b, out), 1);
  EXPECT_NEAR(out[0].depth, 0.05, kTolerance);
  expect_near(out[0].normal, Vec3::UnitZ(), kTolerance);
  expect_near(out[0].point, Vec3(0, 0, 0.075), kTolerance);
}

TEST(ConvexContacts, ACapsuleLyingOnABoxRestsOnBothEnds) {
  // Along x, turned 0.5 rad about z, 1 cm into a slab's top (z = 0.1): its end spheres' bottoms.
  const Mat3 lying =
      about_z(0.5) * Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix();
  const ConvexSolid log =
      solid(ConvexKind::capsule, Vec3(0.05, 0, 0.3), Vec3(0.1, 0.2, 0.14), lying);
  const ConvexSolid slab = solid(ConvexKind::box, Vec3(1, 1, 0.1), Vec3::Zero());
  const Vec3 axis = lying.col(2);
  for (const bool swapped : {false, true}) {
    ConvexContacts out;
    ASSERT_EQ(swapped ? convex_contacts(slab, log, out) : convex_contacts(log, slab, out), 2);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(out[k].depth, 0.01, kTolerance);
      expect_near(out[k].normal, swapped ? Vec3(-Vec3::UnitZ()) : Vec3(Vec3::UnitZ()), kTolerance);
      // Under the ends, midway between the slab's top and the capsule's bottom.
      const Vec3 end = Vec3(0.1, 0.2, 0.095) + (k == 0 ? -0.3 : 0.3) * axis;
      expect_near(out[k].point, end, kTolerance);
    }
  }
  // Tilted onto one end, one point: the deepest.
  const Mat3 tilted =
      Eigen::AngleAxis<Real>(std::numbers::pi / 2 - 0.2, Vec3::UnitY()).toRotationMatrix();
  const ConvexSolid leaning = solid(ConvexKind::capsule, Vec3(0.05, 0, 0.3),
                                    Vec3(0, 0, 0.14 + 0.3 * std::sin(0.2)), tilted);
  ConvexContacts out;
  EXPECT_EQ(convex_contacts(leaning, slab, out), 1);
}

TEST(ConvexContacts, ALogOnALogTouchesUnderBothEnds) {
  // Two parallel capsules along x, one 0.19 m above the other (radii 0.1 each: 1 cm overlap).
  const Mat3 along_x =
      Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix();
  const ConvexSolid top = solid(ConvexKind::capsule, Vec3(0.1, 0, 0.4), Vec3(0, 0, 0.19), along_x);
  const ConvexSolid bottom = solid(ConvexKind::capsule, Vec3(0.1, 0, 0.4), Vec3::Zero(), along_x);
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(top, bottom, out), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(out[k].depth, 0.01, kTolerance);
    expect_near(out[k].normal, Vec3::UnitZ(), kTolerance);
    expect_near(out[k].point, Vec3(k == 0 ? -0.4 : 0.4, 0, 0.095), kTolerance);
  }
}

TEST(ConvexContacts, ABoxStandsOnABoxAtFourCorners) {
  // A 1 x 1 plate turned 0.4 rad, 1 cm into a 2 x 2 slab's top.
  const ConvexSolid top =
      solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3(0.1, 0.2, 0.19), about_z(0.4));
  const ConvexSolid slab = solid(ConvexKind::box, Vec3(1, 1, 0.1), Vec3::Zero());
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(top, slab, out), 4);
  Vec3 mean = Vec3::Zero();
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(out[c].depth, 0.01, kTolerance);
    expect_near(out[c].normal, Vec3::UnitZ(), kTolerance);
    EXPECT_NEAR(out[c].point.z(), 0.095, kTolerance);
    // Each point is a corner of the plate's lower face.
    const Vec3 local = about_z(0.4).transpose() * (out[c].point - Vec3(0.1, 0.2, 0.095));
    EXPECT_NEAR(std::abs(local.x()), 0.5, kTolerance);
    EXPECT_NEAR(std::abs(local.y()), 0.5, kTolerance);
    mean += out[c].point / 4;
  }
  expect_near(mean, Vec3(0.1, 0.2, 0.095), kTolerance);
}

TEST(ConvexContacts, AnUprightCylinderOnABoxSinksByItsOverlap) {
  const ConvexSolid cylinder = solid(ConvexKind::cylinder, Vec3(0.1, 0, 0.2), Vec3(0, 0, 0.29));
  const ConvexSolid box = solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3::Zero());
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(cylinder, box, out), 1);
  EXPECT_NEAR(out[0].depth, 0.01, kTolerance);
  expect_near(out[0].normal, Vec3::UnitZ(), kTolerance);
}

TEST(ConvexContacts, SolidsApartHaveNoContact) {
  ConvexContacts out;
  const ConvexSolid box = solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3::Zero());
  EXPECT_EQ(convex_contacts(solid(ConvexKind::sphere, Vec3(0.2, 0, 0), Vec3(0, 0, 0.31)), box, out),
            0);
  EXPECT_EQ(
      convex_contacts(solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3(0, 0, 0.2001)), box, out),
      0);
  EXPECT_EQ(
      convex_contacts(solid(ConvexKind::capsule, Vec3(0.1, 0, 0.3), Vec3(0.65, 0, 0)), box, out),
      0);
}

TEST(ConvexContacts, BoundsHoldTheSolid) {
  // A capsule of radius 0.1, half length 0.5, turned to lie along x: x in [-0.6, 0.6].
  const Mat3 along_x =
      Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix();
  const Box3 box =
      convex_bounds(solid(ConvexKind::capsule, Vec3(0.1, 0, 0.5), Vec3(1, 2, 3), along_x));
  expect_near(box.lo, Vec3(0.4, 1.9, 2.9), 1e-12);
  expect_near(box.hi, Vec3(1.6, 2.1, 3.1), 1e-12);
}

}  // namespace
}  // namespace pbm
