// The "liquids[i]" section of scene files: its keys and defaults, the round trip, and the errors
// a liquid's definition can have, each at its JSON path (ch. 16's grid, scenes/README.md).
#include <gtest/gtest.h>

#include <tuple>

#include "liquid/liquid_model.h"
#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneLiquidsJson, KeysAndDefaults) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  ASSERT_EQ(s.liquids.size(), 2u);
  const LiquidDef& tank = s.liquids[0];
  EXPECT_EQ(tank.name, "tank");
  EXPECT_EQ(tank.domain.min, Vec3(-1, -0.5, 0));
  EXPECT_EQ(tank.resolution, Eigen::Vector3i(8, 1, 6));
  ASSERT_EQ(tank.fluid.size(), 1u);
  EXPECT_EQ(tank.fluid[0].velocity, Vec3(0.1, 0, 0));
  ASSERT_EQ(tank.inflows.size(), 1u);
  EXPECT_EQ(tank.inflows[0].markers_per_second, 500);
  EXPECT_EQ(tank.walls, WallKind::no_slip);
  EXPECT_EQ(tank.advection, LiquidAdvection::book);
  EXPECT_EQ(tank.solver, PressureSolver::relaxation);
  EXPECT_EQ(tank.markers_per_axis, 3);
  EXPECT_FALSE(tank.ghost_fluid);
  const LiquidDef& other = s.liquids[1];
  EXPECT_EQ(other.name, "liquid1");
  EXPECT_EQ(other.domain.max, Vec3(1, 1, 1));  // the default domain
  EXPECT_EQ(other.surface, SurfaceMethod::height_field);
  EXPECT_EQ(other.solver, PressureSolver::mgpcg);
  EXPECT_EQ(other.cfl, 0.5);
  EXPECT_EQ(other.relaxation, 1.7);  // the book's beta_0
  EXPECT_EQ(other.tolerance, 1e-4);  // the book's epsilon
}

TEST(SceneLiquidsJson, RoundTripIsExact) {
  const Scene a = parse_scene(full_scene().dump(), kFile);
  const Scene b = parse_scene(scene_to_json(a), kFile);
  ASSERT_EQ(b.liquids.size(), a.liquids.size());
  for (std::size_t l = 0; l < a.liquids.size(); ++l) expect_same_liquid(a.liquids[l], b.liquids[l]);
}

TEST(SceneLiquidsJson, ALiquidAloneIsAScene) {
  const Scene s = parse_scene(
      R"({"liquids": [{"fluid": [{"box": {"min": [0, 0, 0], "max": [1, 1, 0.5]}}]}]})", kFile);
  EXPECT_TRUE(s.bodies.empty());
  EXPECT_EQ(s.liquids.size(), 1u);
}

TEST(SceneLiquidsJsonErrors, TheGridsSize) {
  json j = full_scene();
  j["liquids"][0]["resolution"] = {8, 0, 6};
  expect_error(j, "liquids[0].resolution[1]", "must be >= 1");
  j["liquids"][0]["resolution"] = {8, 6};
  expect_error(j, "liquids[0].resolution", "must be an array of 3 integers");
  j["liquids"][0]["resolution"] = {8, 1.5, 6};
  expect_error(j, "liquids[0].resolution[1]", "must be an integer");
  j["liquids"][0]["resolution"] = {8, 5000, 6};
  expect_error(j, "liquids[0].resolution[1]", "must be <= 4096");
  // 257^3 cells: over the 256^3 limit, refused before any array is allocated.
  j["liquids"][0]["resolution"] = {257, 257, 257};
  expect_error(j, "liquids[0].resolution", "at most 16777216");
  j["liquids"][0]["resolution"] = {8, 1, 1};
  expect_error(j, "liquids[0].resolution", "1 cell on one axis only");
}

TEST(SceneLiquidsJsonErrors, BoxesInsideTheDomain) {
  json j = full_scene();
  j["liquids"][0]["fluid"][0]["box"]["max"] = {0, 0.5, 2};
  expect_error(j, "liquids[0].fluid[0].box", "lies outside the liquid's domain");
  j = full_scene();
  j["liquids"][0]["solids"][0]["min"] = {-2, -0.5, 0};
  expect_error(j, "liquids[0].solids[0]", "lies outside the liquid's domain");
  j = full_scene();
  j["liquids"][0]["inflows"][0]["box"]["min"] = {-1.5, -0.5, 1.25};
  expect_error(j, "liquids[0].inflows[0].box", "lies outside the liquid's domain");
  j = full_scene();
  j["liquids"][0]["outflows"][0]["max"] = {1, 0.5, 3};
  expect_error(j, "liquids[0].outflows[0]", "lies outside the liquid's domain");
  j = full_scene();
  j["liquids"][0]["domain"]["max"] = {1, -0.5, 1.5};
  expect_error(j, "liquids[0].domain.max[1]", "must be above min[1]");
  j = full_scene();
  j["liquids"][0]["fluid"][0].erase("box");
  expect_error(j, "liquids[0].fluid[0].box", "is required");
}

TEST(SceneLiquidsJsonErrors, KnobsOutOfRange) {
  const std::vector<std::tuple<std::string, json, std::string>> cases = {
      {"viscosity", -1e-6, "must be >= 0"},
      {"density", 0, "must be > 0"},
      {"cfl", 1.5, "must be in (0, 1]"},
      {"cfl", 0, "must be in (0, 1]"},
      {"relaxation", 2, "must be in [1, 2)"},
      {"tolerance", 0, "must be > 0"},
      {"max_iterations", 0, "must be >= 1"},
      {"markers_per_axis", 9, "must be <= 8"},
      {"volume_correction", 2, "must be in [0, 1]"},
      {"solver", "jacobi", "must be one of"},
      {"walls", "sticky", "must be one of"},
  };
  for (const auto& [key, value, message] : cases) {
    json j = full_scene();
    j["liquids"][0][key] = value;
    expect_error(j, "liquids[0]." + key, message);
  }
  json j = full_scene();
  j["liquids"][1]["name"] = "tank";
  expect_error(j, "liquids[1].name", "names an earlier liquid");
}

TEST(SceneLiquidsJsonErrors, AnInflowThatHoldsNoCellIsRefusedWhenTheModelIsBuilt) {
  json j = full_scene();
  // Between two cell centres in x: no Inflow cell.
  j["liquids"][0]["inflows"][0]["box"] = {{"min", {-0.95, -0.5, 1.3}}, {"max", {-0.9, 0.5, 1.4}}};
  const Scene s = parse_scene(j.dump(), kFile);
  try {
    (void)build_liquid_model(s.liquids[0], s.gravity, kFile, 0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.path(), "liquids[0].inflows[0]");
  }
}

}  // namespace
}  // namespace pbm::scene_test
