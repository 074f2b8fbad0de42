// The "bodies[i]" section of scene files with its shape, tessellation and material: values,
// defaults and normalization, shape vectors by name and by index, and each key's errors at its
// path.
#include <gtest/gtest.h>

#include <cmath>

#include "deform/shape_parameters.h"
#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneBodiesJson, ValuesDefaultsAndNormalization) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodyDef& jello = s.bodies[0];
  EXPECT_EQ(jello.name, "jello");
  EXPECT_EQ(jello.level, DeformLevel::global);
  EXPECT_EQ(jello.order, DynamicsOrder::first);
  EXPECT_EQ(jello.shape, ShapeKind::taper_bend);
  // Named q_s: a0 (index 0), eps1 (4) and t1 (6) of (2.11) are set, the rest keep the defaults.
  VecX q_s = default_shape_parameters(ShapeKind::taper_bend);
  q_s[0] = 2.0;
  q_s[4] = 0.5;
  q_s[6] = 0.3;
  ASSERT_EQ(jello.q_s.size(), 11);
  EXPECT_EQ(jello.q_s, q_s);
  // rest: names not given take q_s, not the kind's defaults.
  VecX q_s0 = q_s;
  q_s0[6] = 0.1;
  EXPECT_EQ(jello.q_s0, q_s0);
  EXPECT_EQ(jello.k_s, (VecX::LinSpaced(11, 1, 11)));
  EXPECT_EQ(jello.position, Vec3(1, 2, 3));
  EXPECT_EQ(jello.orientation, Vec4(1, 0, 0, 0));  // [2,0,0,0] / 2
  EXPECT_EQ(jello.tessellation.kind, TessellationKind::quads);
  EXPECT_EQ(jello.tessellation.rings, 4);
  EXPECT_EQ(jello.tessellation.segments, 5);
  EXPECT_EQ(jello.material.nodal_mass, 0.25);
  EXPECT_EQ(jello.material.mass, 0);
  EXPECT_EQ(jello.material.w1, 5);
  EXPECT_EQ(jello.material.color, Vec3(1, 0.5, 0));

  const BodyDef& plain = s.bodies[1];
  EXPECT_EQ(plain.name, "body1");
  EXPECT_EQ(plain.level, DeformLevel::local);
  EXPECT_EQ(plain.order, DynamicsOrder::second);
  EXPECT_EQ(plain.shape, ShapeKind::superquadric);
  EXPECT_EQ(plain.q_s, default_shape_parameters(ShapeKind::superquadric));
  EXPECT_EQ(plain.q_s0, plain.q_s);
  EXPECT_EQ(plain.k_s, VecX::Zero(6));
  // [1,1,0,0] / sqrt(2): unit length, direction kept.
  EXPECT_NEAR(plain.orientation.norm(), 1.0, 1e-15);
  EXPECT_NEAR(plain.orientation[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(plain.orientation[1], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(plain.tessellation.kind, TessellationKind::triangles);
  EXPECT_EQ(plain.tessellation.rings, 16);
  EXPECT_EQ(plain.material.mass, 3);
  EXPECT_EQ(plain.material.nodal_mass, 0);
  EXPECT_EQ(plain.material.w0, 20.0);
  EXPECT_EQ(plain.material.damping, 1.4);

  EXPECT_EQ(s.bodies[0].material.roughness, 0.2);
}

TEST(SceneBodiesJson, GeneralShapeByNameAndTrackByName) {
  // The last of the 39 parameters of (2.27), addressed by whatever name reference_shape.h gives it.
  const int n_s = shape_parameter_count(ShapeKind::general);
  ASSERT_EQ(n_s, 39);
  const std::string last = shape_parameter_name(ShapeKind::general, n_s - 1);
  json j = {
      {"bodies",
       {{{"shape", {{"kind", "general"}, {"q_s", {{last, 0.5}}}}}, {"material", {{"mass", 1}}}}}},
      {"tracks", {{{"target", "bodies[0].q_s0." + last}, {"keys", {{0, 0.5}}}}}}};
  ASSERT_TRUE(check_shape_parameter(ShapeKind::general, n_s - 1, 0.5).empty());
  const Scene s = parse_scene(j.dump(), kFile);
  VecX q_s = default_shape_parameters(ShapeKind::general);
  q_s[n_s - 1] = 0.5;
  EXPECT_EQ(s.bodies[0].q_s, q_s);
  EXPECT_EQ(s.tracks[0].target, "bodies[0].q_s0[38]");
}

TEST(SceneBodiesJsonErrors, RangesNameTheField) {
  json j = full_scene();
  j["bodies"][0]["material"].erase("nodal_mass");
  j["bodies"][0]["material"]["mass"] = -1;
  expect_error(j, "bodies[0].material.mass", "bodies[0].material.mass: must be > 0");
  j = full_scene();
  j["bodies"][0]["material"]["nodal_mass"] = 0;
  expect_error(j, "bodies[0].material.nodal_mass", "must be > 0");
  j = full_scene();
  j["bodies"][0]["material"]["mass"] = 1;  // both masses
  expect_error(j, "bodies[0].material", "exactly one of 'mass'");
  j = full_scene();
  j["bodies"][1]["material"] = json::object();  // neither
  expect_error(j, "bodies[1].material", "exactly one of 'mass'");
  j = full_scene();
  j["bodies"][0]["material"]["w1"] = -0.5;
  expect_error(j, "bodies[0].material.w1", "bodies[0].material.w1: must be >= 0");
  j = full_scene();
  j["bodies"][0]["material"]["color"] = {0, 1.5, 0};
  expect_error(j, "bodies[0].material.color[1]", "must be in [0, 1]");
  j = full_scene();
  j["bodies"][0]["tessellation"]["rings"] = 1;
  expect_error(j, "bodies[0].tessellation.rings", "must be >= 2");
  j = full_scene();
  j["bodies"][0]["tessellation"]["segments"] = 2;
  expect_error(j, "bodies[0].tessellation.segments", "must be >= 3");
  j = full_scene();
  j["bodies"][0]["shape"]["stiffness"][3] = -1;
  expect_error(j, "bodies[0].shape.stiffness[3]", "must be >= 0");
  j = full_scene();
  j["bodies"][0]["orientation"] = {0, 0, 0, 0};
  expect_error(j, "bodies[0].orientation", "must be a nonzero quaternion");
  j = full_scene();
  j["bodies"][1]["name"] = "jello";
  expect_error(j, "bodies[1].name", "duplicate body name 'jello'");
  j = full_scene();
  j["bodies"][1]["name"] = "";
  expect_error(j, "bodies[1].name", "must not be empty");
}

TEST(SceneBodiesJsonErrors, ShapeParametersCheckedByNameAndIndex) {
  json j = full_scene();
  j["bodies"][0]["shape"]["q_s"]["eps1"] = 0;
  expect_error(j, "bodies[0].shape.q_s.eps1", check_shape_parameter(ShapeKind::taper_bend, 4, 0.0));
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"] = {1, 1, 1, 1, -0.2, 1, 0, 0, 0, 0, 1};
  expect_error(j, "bodies[0].shape.q_s[4]", "bodies[0].shape.q_s[4]: must be > 0");
  j = full_scene();
  j["bodies"][0]["shape"]["rest"]["a0"] = -1;
  expect_error(j, "bodies[0].shape.rest.a0", "must be > 0");
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"]["eps3"] = 1;
  expect_error(j, "bodies[0].shape.q_s.eps3", "unknown shape parameter 'eps3'");
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"] = {1, 1, 1, 1, 1, 1};  // 6 entries for an 11-parameter shape
  expect_error(j, "bodies[0].shape.q_s", "must have 11 entries");
  j = full_scene();
  j["bodies"][0]["shape"]["kind"] = "superquadric";  // t1 is not a superquadric parameter
  expect_error(j, "bodies[0].shape.q_s.t1", "unknown shape parameter 't1'");
}

}  // namespace
}  // namespace pbm::scene_test
