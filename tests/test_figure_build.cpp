// A figure's description compiled (sec. 15.1.1): masses and inertias from the segments' geometry
// against an independent numerical integration over each shape, the joint frames from their
// sites, the initial state, and bad descriptions refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "core/quaternion.h"
#include "figure/figure_build.h"

namespace pbm {
namespace {

// Whether the point (shape axes, about its centre) is inside the shape.
bool inside(const SegmentShapeDef& shape, const Vec3& p) {
  const Real r = shape.size.x();
  switch (shape.kind) {
    case SegmentShapeKind::box:
      return (p.cwiseAbs().array() <= shape.size.array()).all();
    case SegmentShapeKind::sphere:
      return p.norm() <= r;
    case SegmentShapeKind::cylinder:
      return p.head<2>().norm() <= r && std::abs(p.z()) <= shape.size.z();
    case SegmentShapeKind::capsule: {
      const Real z = std::clamp(p.z(), -shape.size.z(), shape.size.z());
      return (p - Vec3(0, 0, z)).norm() <= r;
    }
  }
  return false;
}

// Volume and inertia (per unit density) by the midpoint rule on a 160^3 grid over the bounds.
void integrate(const SegmentShapeDef& shape, Real& volume, Mat3& inertia) {
  const Vec3 half =
      shape.kind == SegmentShapeKind::box
          ? shape.size
          : Vec3(shape.size.x(), shape.size.x(),
                 shape.kind == SegmentShapeKind::sphere
                     ? shape.size.x()
                     : shape.size.z() +
                           (shape.kind == SegmentShapeKind::capsule ? shape.size.x() : 0.0));
  constexpr int kCells = 160;
  const Vec3 h = 2 * half / kCells;
  volume = 0;
  inertia.setZero();
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j)
      for (int k = 0; k < kCells; ++k) {
        const Vec3 p = -half + Vec3((i + 0.5) * h.x(), (j + 0.5) * h.y(), (k + 0.5) * h.z());
        if (!inside(shape, p)) continue;
        const Real dv = h.prod();
        volume += dv;
        inertia += dv * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
      }
}

TEST(FigureBuild, ShapeMassAndInertiaAgreeWithNumericalIntegration) {
  const SegmentShapeDef shapes[] = {
      {.kind = SegmentShapeKind::box, .size = Vec3(0.1, 0.2, 0.3)},
      {.kind = SegmentShapeKind::sphere, .size = Vec3(0.15, 0, 0)},
      {.kind = SegmentShapeKind::cylinder, .size = Vec3(0.1, 0, 0.25)},
      {.kind = SegmentShapeKind::capsule, .size = Vec3(0.08, 0, 0.2)}};
  for (const SegmentShapeDef& shape : shapes) {
    Real volume;
    Mat3 inertia;
    integrate(shape, volume, inertia);
    const Real density = 1000;
    const Real mass = density * shape_volume(shape);
    const Mat3 I = shape_inertia(shape, mass);
    std::printf("shape %d: volume %.6g (grid %.6g), I diag %.5g %.5g %.5g (grid %.5g %.5g %.5g)\n",
                static_cast<int>(shape.kind), shape_volume(shape), volume, I(0, 0), I(1, 1),
                I(2, 2), density * inertia(0, 0), density * inertia(1, 1), density * inertia(2, 2));
    EXPECT_NEAR(shape_volume(shape), volume, 2e-3 * volume);
    EXPECT_LT((I - density * inertia).norm(), 2e-3 * I.norm());
  }
}

FigureDef arm() {
  FigureDef def;
  def.name = "arm";
  SegmentDef upper;
  upper.name = "upper";
  upper.joint.kind = JointKind::spherical;
  upper.joint.position = Vec3(0, 0, 1.5);
  upper.shape = {
      .kind = SegmentShapeKind::capsule, .size = Vec3(0.05, 0, 0.15), .center = Vec3(0, 0, -0.2)};
  SegmentDef lower;
  lower.name = "lower";
  lower.parent = "upper";
  lower.joint.kind = JointKind::revolute;
  lower.joint.axis = Vec3(0, 2, 0);  // normalized on load
  lower.joint.position = Vec3(0, 0, -0.4);
  lower.joint.orientation = Vec4(std::cos(0.25), 0, 0, std::sin(0.25));  // turned 0.5 rad about z
  lower.joint.q0 = {0.7};
  lower.joint.v0 = {-1.0};
  lower.joint.damping = 0.3;
  lower.mass = 1.5;
  lower.shape = {
      .kind = SegmentShapeKind::box, .size = Vec3(0.04, 0.04, 0.18), .center = Vec3(0, 0, -0.18)};
  def.segments = {upper, lower};
  return def;
}

TEST(FigureBuild, CompilesJointFramesMassesAndInitialState) {
  const CompiledFigure f = build_figure_model(arm(), "arm.json", "figures[0]");
  ASSERT_EQ(f.model.size(), 2);
  EXPECT_EQ(f.model.n_q, 5);
  EXPECT_EQ(f.model.n_v, 4);
  const SegmentModel& upper = f.model.segments[0];
  const SegmentModel& lower = f.model.segments[1];
  EXPECT_EQ(lower.parent, 0);
  EXPECT_NEAR(upper.inertia.m, 1000 * shape_volume(arm().segments[0].shape), 1e-12);
  EXPECT_DOUBLE_EQ(lower.inertia.m, 1.5);
  EXPECT_LT((lower.inertia.c - Vec3(0, 0, -0.18)).norm(), 1e-15);
  EXPECT_LT((lower.joint.axis - Vec3::UnitY()).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(lower.damping, 0.3);
  // The joint frame on the parent: E takes parent coordinates to the joint frame's, turned
  // 0.5 rad about z, so the parent's x reads (cos 0.5, -sin 0.5, 0) there.
  EXPECT_LT((lower.X_tree.E * Vec3::UnitX() - Vec3(std::cos(0.5), -std::sin(0.5), 0)).norm(),
            1e-15);
  EXPECT_LT((lower.X_tree.r - Vec3(0, 0, -0.4)).norm(), 1e-15);
  // At rest but for q0 and v0: the spherical joint's identity quaternion, the elbow at 0.7 rad.
  VecX q(5);
  q << 1, 0, 0, 0, 0.7;
  EXPECT_EQ(f.q0, q);
  EXPECT_EQ(f.v0, Vec4(0, 0, 0, -1.0));
}

TEST(FigureBuild, BadFiguresAreRefusedNamingTheField) {
  const auto expect_error = [](const FigureDef& def, const std::string& path) {
    try {
      build_figure_model(def, "arm.json", "figures[0]");
      ADD_FAILURE() << "accepted; expected an error at " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.path(), path) << e.what();
      EXPECT_EQ(e.file(), "arm.json");
    }
  };
  FigureDef missing = arm();
  missing.segments[1].parent = "torso";
  expect_error(missing, "figures[0].segments[1].parent");
  FigureDef cycle = arm();
  cycle.segments[0].parent = "lower";
  expect_error(cycle, "figures[0].segments[0].parent");
  FigureDef massless = arm();
  massless.segments[0].density = 0;
  expect_error(massless, "figures[0].segments[0].density");
  FigureDef negative = arm();
  negative.segments[1].mass = -2;
  expect_error(negative, "figures[0].segments[1].mass");
  FigureDef no_axis = arm();
  no_axis.segments[1].joint.axis = Vec3::Zero();
  expect_error(no_axis, "figures[0].segments[1].joint.axis");
  FigureDef flat = arm();
  flat.segments[1].shape.size.y() = 0;
  expect_error(flat, "figures[0].segments[1].shape.size");
  FigureDef twice = arm();
  twice.segments[1].name = "upper";
  expect_error(twice, "figures[0].segments[1].name");
  FigureDef short_q = arm();
  short_q.segments[0].joint.q0 = {1, 0, 0};
  expect_error(short_q, "figures[0].segments[0].joint.q0");
  FigureDef nan_v = arm();
  nan_v.segments[1].joint.v0 = {std::nan("")};
  expect_error(nan_v, "figures[0].segments[1].joint.v0");
  FigureDef empty;
  expect_error(empty, "figures[0].segments");
}

}  // namespace
}  // namespace pbm
