// Picking figures' segments in the viewport (app/studio/picking.h): the ray meets each shape
// where its closed-form surface is, the nearest segment wins, and shapes beside the ray are
// missed.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "picking.h"

namespace pbm {
namespace {

using Vec3f = Eigen::Vector3f;

draw::Primitive segment(draw::PrimitiveShape shape, const Vec3f& center, const Vec3f& half_size,
                        int figure, int index) {
  draw::Primitive p;
  p.shape = shape;
  p.center = center;
  p.half_size = half_size;
  p.figure = figure;
  p.segment = index;
  return p;
}

// A ray from 10 m up +x, looking down -x: it reaches x on the shape's near side at 10 - x.
Ray along_x() {
  return {Vec3f(10, 0, 0), Vec3f(-1, 0, 0)};
}

TEST(PickFigure, EachShapeIsHitWhereItsSurfaceIs) {
  const Vec3f centre(1, 0, 0);
  struct Case {
    draw::PrimitiveShape shape;
    Vec3f half;
    float near_x;  // the surface the ray meets first
  };
  const Case cases[] = {{draw::PrimitiveShape::box, Vec3f(0.3f, 0.2f, 0.1f), 1.3f},
                        {draw::PrimitiveShape::sphere, Vec3f(0.25f, 0, 0), 1.25f},
                        {draw::PrimitiveShape::capsule, Vec3f(0.2f, 0, 0.5f), 1.2f},
                        {draw::PrimitiveShape::cylinder, Vec3f(0.15f, 0, 0.4f), 1.15f}};
  for (const Case& c : cases) {
    draw::Snapshot snap;
    snap.primitives.push_back(segment(c.shape, centre, c.half, 2, 5));
    const std::optional<FigurePick> pick = pick_figure(snap, along_x());
    ASSERT_TRUE(pick) << static_cast<int>(c.shape);
    EXPECT_EQ(pick->figure, 2);
    EXPECT_EQ(pick->segment, 5);
    EXPECT_NEAR(pick->distance, 10 - c.near_x, 1e-4f) << static_cast<int>(c.shape);
    EXPECT_NEAR(pick->point.x(), c.near_x, 1e-4f);
  }
}

TEST(PickFigure, TheNearestSegmentWinsAndRotatedShapesAreHitInTheirOwnFrame) {
  draw::Snapshot snap;
  snap.primitives.push_back(
      segment(draw::PrimitiveShape::sphere, Vec3f(0, 0, 0), Vec3f(0.5f, 0, 0), 0, 0));
  // A capsule lying along y (its local z turned onto world y) nearer the ray's origin.
  draw::Primitive capsule =
      segment(draw::PrimitiveShape::capsule, Vec3f(3, 0.4f, 0), Vec3f(0.1f, 0, 0.5f), 0, 1);
  capsule.rotation = Eigen::AngleAxisf(-std::numbers::pi_v<float> / 2, Vec3f::UnitX()).matrix();
  snap.primitives.push_back(capsule);
  const std::optional<FigurePick> pick = pick_figure(snap, along_x());
  ASSERT_TRUE(pick);
  EXPECT_EQ(pick->segment, 1);
  EXPECT_NEAR(pick->distance, 10 - 3.1f, 1e-4f);
  // Drawables that are not figures' segments (obstacles) are never picked as figures.
  snap.primitives[0].figure = snap.primitives[1].figure = -1;
  EXPECT_FALSE(pick_figure(snap, along_x()));
}

TEST(PickFigure, ARayBesideTheShapeMissesIt) {
  draw::Snapshot snap;
  snap.primitives.push_back(
      segment(draw::PrimitiveShape::box, Vec3f(0, 0, 0), Vec3f(0.5f, 0.5f, 0.5f), 0, 0));
  // Just past the box's edge at y = 0.5, and along its side without meeting it.
  EXPECT_FALSE(pick_figure(snap, {Vec3f(10, 0.51f, 0), Vec3f(-1, 0, 0)}));
  EXPECT_TRUE(pick_figure(snap, {Vec3f(10, 0.49f, 0), Vec3f(-1, 0, 0)}));
  EXPECT_FALSE(pick_figure(snap, {Vec3f(10, 0, 0), Vec3f(1, 0, 0)}));  // pointing away
}

}  // namespace
}  // namespace pbm
