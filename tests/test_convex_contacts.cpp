// The narrowphase of segment-segment collisions (collide/convex_contacts.h) against closed forms:
// two spheres, a sphere on a box's face, two crossed capsules, a box standing on a box (four
// points, one at each corner of the smaller face), a capsule lying on a box and a log on a log
// (two points, under their ends), a cylinder on a box standing (four rim points), tilted (the
// rim's arc inside) and lying (under both caps), solids apart, and the same pair swapped (the
// normal turns round). Bullet is single precision here: 1e-5 m.
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

// Standing on its cap, a cylinder rests on four rim points at right angles, each sunk by the
// overlap (the box's signed distance is exact: 1e-12), their mean on its axis, so their equal
// springs hold it up without a torque; the pair swapped turns the normals round.
TEST(ConvexContacts, AnUprightCylinderOnABoxStandsOnFourRimPoints) {
  const ConvexSolid cylinder = solid(ConvexKind::cylinder, Vec3(0.1, 0, 0.2), Vec3(0.05, 0, 0.29));
  const ConvexSolid box = solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3::Zero());
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(cylinder, box, out), 4);
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(out[k].depth, 0.01, 1e-12);
    expect_near(out[k].normal, Vec3::UnitZ(), 1e-12);
    EXPECT_NEAR(std::hypot(out[k].point.x() - 0.05, out[k].point.y()), 0.1, 1e-12);
    EXPECT_NEAR(out[k].point.z(), 0.095, 1e-12);  // midway between the box's top and the rim
    mean += out[k].point / 4;
  }
  expect_near(mean, Vec3(0.05, 0, 0.095), 1e-12);
  // Neighbours at right angles.
  EXPECT_NEAR((out[0].point - Vec3(0.05, 0, 0.095)).dot(out[1].point - Vec3(0.05, 0, 0.095)), 0,
              1e-12);
  ASSERT_EQ(convex_contacts(box, cylinder, out), 4);
  for (int k = 0; k < 4; ++k) expect_near(out[k].normal, -Vec3::UnitZ(), 1e-12);
}

// Tilted by 0.05 rad about x, it rests on the arc of its rim that dips into the box: the points
// found are those whose depth by geometry, 0.01 - |z| of the rim point above the centre, is > 0.
TEST(ConvexContacts, ATiltedCylinderRestsOnTheArcOfItsRimInside) {
  const Real tilt = 0.05;
  const Mat3 R = Eigen::AngleAxis<Real>(tilt, Vec3::UnitX()).toRotationMatrix();
  // The rim's lowest point at z = -0.01 (the box's top is z = 0.1).
  const Real low = 0.2 * std::cos(tilt) + 0.1 * std::sin(tilt);
  const ConvexSolid cylinder =
      solid(ConvexKind::cylinder, Vec3(0.1, 0, 0.2), Vec3(0, 0, 0.1 + low - 0.01), R);
  const ConvexSolid box = solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3::Zero());
  ConvexContacts out;
  const int n = convex_contacts(cylinder, box, out);
  ASSERT_GE(n, 2);
  for (int k = 0; k < n; ++k) {
    // Each point's depth is how far its rim point lies below the box's top.
    const Real rim_z = out[k].point.z() - 0.5 * out[k].depth;
    EXPECT_NEAR(out[k].depth, 0.1 - rim_z, 1e-12);
    EXPECT_GT(out[k].depth, 0);
    EXPECT_LE(out[k].depth, 0.01 + 1e-12);
    expect_near(out[k].normal, Vec3::UnitZ(), 1e-12);
  }
}

// Lying on its side, a cylinder touches along a line: a point under each cap, each sunk by the
// overlap, whatever its roll (22.5 degrees puts the lowest line between two rim points).
TEST(ConvexContacts, ACylinderLyingOnABoxRestsUnderBothCaps) {
  const Mat3 along_x =
      Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()) *
      Eigen::AngleAxis<Real>(std::numbers::pi / 8, Vec3::UnitZ()).toRotationMatrix();
  const ConvexSolid cylinder =
      solid(ConvexKind::cylinder, Vec3(0.1, 0, 0.3), Vec3(0.1, 0.2, 0.1 + 0.1 - 0.002), along_x);
  const ConvexSolid box = solid(ConvexKind::box, Vec3(0.5, 0.5, 0.1), Vec3::Zero());
  ConvexContacts out;
  ASSERT_EQ(convex_contacts(cylinder, box, out), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(out[k].depth, 0.002, kTolerance);
    expect_near(out[k].normal, Vec3::UnitZ(), 1e-4);
    EXPECT_NEAR(out[k].point.z(), 0.099, kTolerance);
    // Within the patch each cap's disc cuts from the box: the chord sqrt(2 r depth) = 0.02 m
    // either side of the lowest line across, the disc's thickness (2e-4 m, at the cap) along.
    EXPECT_LT(std::abs(out[k].point.y() - 0.2), std::sqrt(2 * 0.1 * 0.002));
    const Real along = std::abs(out[k].point.x() - 0.1);
    EXPECT_GT(along, 0.3 - 2e-4 - kTolerance);
    EXPECT_LT(along, 0.3 + kTolerance);
  }
  EXPECT_LT((out[0].point.x() - 0.1) * (out[1].point.x() - 0.1), 0);  // one under each cap
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
