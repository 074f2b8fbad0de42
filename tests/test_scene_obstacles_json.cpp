// The "obstacles[i]" section of scene files: each kind's keys (a box's centre and a mesh's
// position are stored as the obstacle's point), defaults, normalization, and the errors of keys
// that belong to another kind.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneObstaclesJson, EachKindsKeysWithDefaultsAndNormalization) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  ASSERT_EQ(s.obstacles.size(), 3u);
  const ObstacleDef& floor = s.obstacles[0];
  EXPECT_EQ(floor.kind, ObstacleKind::plane);
  EXPECT_NEAR(floor.normal[0], 0.6, 1e-15);  // (3, 4, 0) / 5
  EXPECT_NEAR(floor.normal[1], 0.8, 1e-15);
  EXPECT_EQ(floor.normal[2], 0);
  EXPECT_EQ(floor.size, Vec2(5, 6));
  EXPECT_EQ(floor.friction, 1);
  EXPECT_EQ(floor.elasticity, 670);
  const ObstacleDef& box = s.obstacles[1];
  EXPECT_EQ(box.name, "obstacle1");
  EXPECT_EQ(box.kind, ObstacleKind::box);
  EXPECT_EQ(box.point, Vec3(1, 1, 1));  // "center" is stored in point
  EXPECT_EQ(box.half_extents, Vec3(0.5, 1, 2));
  EXPECT_EQ(box.orientation, Vec4(0, 0, 0, 1));
  EXPECT_EQ(box.elasticity, 0);
  const ObstacleDef& rock = s.obstacles[2];
  EXPECT_EQ(rock.kind, ObstacleKind::mesh);
  EXPECT_EQ(rock.file, "rock.obj");  // resolved against the scene's folder when the Model loads it
  EXPECT_EQ(rock.point, Vec3(2, 0, 0));
  EXPECT_NEAR(rock.orientation[0], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(rock.scale, 0.5);
}

TEST(SceneObstaclesJsonErrors, KeysMustMatchTheKind) {
  json j = full_scene();
  j["obstacles"][0]["half_extents"] = {1, 1, 1};
  expect_error(j, "obstacles[0].half_extents", "not valid for a plane obstacle");
  j = full_scene();
  j["obstacles"][1]["normal"] = {0, 0, 1};
  expect_error(j, "obstacles[1].normal", "not valid for a box obstacle");
}

TEST(SceneObstaclesJsonErrors, RangesNameTheField) {
  json j = full_scene();
  j["obstacles"][0]["friction"] = 1.5;
  expect_error(j, "obstacles[0].friction", "must be in [0, 1]");
  j = full_scene();
  j["obstacles"][1]["elasticity"] = -1;
  expect_error(j, "obstacles[1].elasticity", "must be >= 0");
  j = full_scene();
  j["obstacles"][1]["half_extents"] = {1, 0, 1};
  expect_error(j, "obstacles[1].half_extents[1]", "must be > 0");
  j = full_scene();
  j["obstacles"][0]["normal"] = {0, 0, 0};
  expect_error(j, "obstacles[0].normal", "must be a nonzero vector");
  j = full_scene();
  j["obstacles"][2].erase("file");
  expect_error(j, "obstacles[2].file", "is required");
}

}  // namespace
}  // namespace pbm::scene_test
