// The loads of scene files: "force_fields[i]" (bodies by index or name) and "springs[i]" (a node
// or a material point of a body), with their defaults and errors at their paths.
#include <gtest/gtest.h>

#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneSpringsJson, ForceFieldsAndSpringsWithDefaults) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  ASSERT_EQ(s.force_fields.size(), 2u);
  EXPECT_EQ(s.force_fields[0].kind, ForceFieldKind::force_per_node);
  EXPECT_EQ(s.force_fields[0].bodies, (std::vector<int>{0, 1}));  // "jello" resolved to 0
  EXPECT_EQ(s.force_fields[1].kind, ForceFieldKind::acceleration);
  EXPECT_TRUE(s.force_fields[1].bodies.empty());

  ASSERT_EQ(s.springs.size(), 2u);
  EXPECT_EQ(s.springs[0].body, 0);
  EXPECT_EQ(s.springs[0].node, 21);  // last node of 2 + 4 * 5 = 22
  EXPECT_FALSE(s.springs[0].material_point.has_value());
  EXPECT_EQ(s.springs[0].t_end, 4);
  EXPECT_EQ(s.springs[0].max_force, 30);
  EXPECT_EQ(s.springs[1].max_force, 1e300);
  EXPECT_EQ(s.springs[1].name, "spring1");
  EXPECT_EQ(s.springs[1].node, -1);
  ASSERT_TRUE(s.springs[1].material_point.has_value());
  EXPECT_EQ(*s.springs[1].material_point, Vec2(0.5, -1));
  EXPECT_EQ(s.springs[1].stiffness, 100);
  EXPECT_EQ(s.springs[1].t_end, 1e300);
}

TEST(SceneSpringsJsonErrors, NodeIndexAndBodyReferences) {
  // Body 0 has 2 + 4 * 5 = 22 nodes: 21 is the last one (accepted in full_scene), 22 is out.
  json j = full_scene();
  j["springs"][0]["node"] = 22;
  expect_error(j, "springs[0].node", "node 22 is out of range: body 'jello' has 22 nodes");
  j["springs"][0]["node"] = -1;
  expect_error(j, "springs[0].node", "out of range");
  j = full_scene();
  j["springs"][1]["material_point"] = {2.0, 0};  // u beyond pi/2
  expect_error(j, "springs[1].material_point[0]", "must be in [");
  j = full_scene();
  j["springs"][0]["body"] = "pudding";
  expect_error(j, "springs[0].body", "unknown body 'pudding'");
  j = full_scene();
  j["force_fields"][0]["bodies"] = {0, 2};
  expect_error(j, "force_fields[0].bodies[1]", "body index 2 is out of range");
}

TEST(SceneSpringsJsonErrors, RangesAndRelationsNameTheField) {
  json j = full_scene();
  j["springs"][0]["t_end"] = 0.5;  // before t_begin = 1
  expect_error(j, "springs[0].t_end", "must be >= t_begin");
  j = full_scene();
  j["springs"][0]["max_force"] = 0;
  expect_error(j, "springs[0].max_force", "must be > 0");
  j = full_scene();
  j["springs"][0].erase("node");
  expect_error(j, "springs[0]", "exactly one of 'node' and 'material_point'");
  j = full_scene();
  j["springs"][1]["node"] = 0;  // and its material point
  expect_error(j, "springs[1]", "exactly one of 'node' and 'material_point'");
}

}  // namespace
}  // namespace pbm::scene_test
