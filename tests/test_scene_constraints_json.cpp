// The "constraints[i]" section of scene files and its ends "a" and "b" (ch. 7): body points by
// node, material point or body-frame point, world anchors, hinges, and errors at their paths.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneConstraintsJson, EndsWithDefaultsAndOverrides) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  EXPECT_EQ(s.solver.constraint_alpha, 7);
  EXPECT_FALSE(s.solver.constraint_beta.has_value());
  EXPECT_EQ(s.solver.constraint_solver, ConstraintSolverKind::sparse);
  ASSERT_EQ(s.constraints.size(), 3u);
  EXPECT_EQ(s.constraints[0].a.body, 0);
  EXPECT_EQ(s.constraints[0].a.node, 3);
  EXPECT_EQ(s.constraints[0].b.material_point, Vec2(0.2, 0.3));
  EXPECT_EQ(s.constraints[0].alpha, 20.0);
  EXPECT_EQ(s.constraints[1].name, "constraint1");
  EXPECT_EQ(s.constraints[1].b.body, -1);
  EXPECT_EQ(s.constraints[1].b.world, Vec3(0, 0, 5));
  EXPECT_EQ(s.constraints[1].beta, 3.0);
  EXPECT_EQ(s.constraints[2].kind, ConstraintKind::hinge);
  EXPECT_EQ(s.constraints[2].axis, Vec3(0, 1, 0));
}

TEST(SceneConstraintsJsonErrors, ErrorsNameTheirPath) {
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"a", {{"body", "tail"}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a.body"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"body", 7}, {"node", 0}}}},
       "constraints[0].b.body"},
      {{{"a", {{"world", {0, 0, 0}}}}, {"b", {{"body", 0}, {"node", 0}}}},
       "constraints[0].a.world"},
      {{{"a", {{"body", 0}, {"node", 0}, {"point", {0, 0, 0}}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a"},
      {{{"a", {{"body", 0}, {"node", 999}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a.node"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}, {"body", 0}}}},
       "constraints[0].b.body"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}, {"axis", {0, 0, 1}}},
       "constraints[0].axis"},
      {{{"kind", "hinge"}, {"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}, {"alpha", -1}},
       "constraints[0].alpha"},
      {{{"a", {{"body", 0}, {"node", 0}}}}, "constraints[0].b"},
  };
  for (const auto& [constraint, path] : cases) {
    json j = {{"bodies", {{{"name", "ball"}, {"material", {{"mass", 1}}}}}},
              {"constraints", {constraint}}};
    try {
      parse_scene(j.dump(), kFile);
      ADD_FAILURE() << "expected an error at " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.path(), path) << e.what();
      EXPECT_EQ(e.file(), kFile);
    }
  }
  json solver = {{"bodies", {{{"material", {{"mass", 1}}}}}},
                 {"solver", {{"constraint_solver", "cholesky"}}}};
  EXPECT_THROW(parse_scene(solver.dump(), kFile), Error);
}

}  // namespace
}  // namespace pbm::scene_test
