// Scene files in and out: the whole scene's parse (its own keys and the solver's), exact round
// trips through scene_to_json and save_scene, and the reader's errors that are no section's own
// (malformed JSON, unknown and repeated keys, wrong types, missing parts, missing files). Each
// section's keys are tested in tests/test_scene_<section>_json.cpp, the format's tables against
// the schema and README in test_scene_format.cpp, the limits in test_scene_limits.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneJson, FullSceneParsesTheSceneAndSolverKeys) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  EXPECT_EQ(s.file, kFile);
  EXPECT_EQ(s.name, "jello-ball");
  EXPECT_EQ(s.gravity, Vec3(0, 0, -9.81));
  EXPECT_EQ(s.solver.dt, 0.031);
  EXPECT_EQ(s.solver.integrator, IntegratorKind::rk45);
  EXPECT_EQ(s.solver.fps, 24);
  EXPECT_EQ(s.solver.body_elasticity, 250);
  EXPECT_EQ(s.solver.body_friction, 0.7);
  EXPECT_TRUE(s.solver.contact_step_reduction);
  EXPECT_EQ(s.solver.max_retries, 6);
  EXPECT_EQ(s.solver.energy_growth_bound, 2);
  EXPECT_EQ(s.solver.constraint_alpha, 7);
  EXPECT_FALSE(s.solver.constraint_beta.has_value());
  EXPECT_EQ(s.solver.constraint_solver, ConstraintSolverKind::sparse);
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->up, Vec3(0, 0, 1));  // normalized
  EXPECT_EQ(s.camera->fov, 35);
}

TEST(SceneJson, RoundTripThroughSceneToJsonIsExact) {
  // 1/3 and 0.1 have no short decimal form: the writer must print round-trip precision.
  json j = full_scene();
  j["bodies"][0]["position"] = {1.0 / 3.0, 0.1, 2.0 / 7.0};
  j["bodies"][1]["orientation"] = {0.3, -0.2, 0.9, 0.1};
  const Scene s = parse_scene(j.dump(), kFile);
  const std::string text = scene_to_json(s);
  const Scene t = parse_scene(text, "again.json");
  expect_same_scene(s, t);
  EXPECT_EQ(t.file, "again.json");
  // The writer is a fixed point: writing the re-read scene gives the same text.
  EXPECT_EQ(scene_to_json(t), text);
  // Pretty: one key per line, 2-space indent.
  EXPECT_NE(text.find("\n  \"bodies\": ["), std::string::npos);
}

TEST(SceneJson, SaveWritesAtomicallyAndLoadReadsItBack) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pbm_scene_json_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "saved.json").string();
  const Scene s = parse_scene(full_scene().dump(), kFile);
  {
    std::ofstream old(path);
    old << "old contents";
  }
  save_scene(s, path);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Scene t = load_scene(path);
  EXPECT_EQ(t.file, path);
  // The same scene, its mesh's relative name now relative to the folder it was saved in.
  expect_same_scene(scene_saved_as(s, path), t);
  EXPECT_EQ(std::filesystem::weakly_canonical(dir / t.obstacles[2].file),
            std::filesystem::weakly_canonical(std::filesystem::absolute(s.obstacles[2].file)));
  // Saving into a directory that does not exist fails cleanly, naming the file.
  const std::string bad = (dir / "no_such_dir" / "x.json").string();
  try {
    save_scene(s, bad);
    ADD_FAILURE() << "expected pbm::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), bad);
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneJsonErrors, MalformedJsonReportsLineAndByte) {
  // The '}' that should be a value is the 14th character of line 3 and byte 2 + 15 + 14 = 31.
  const std::string text = "{\n  \"name\": \"x\",\n  \"bodies\": [}]\n}\n";
  expect_text_error(text, "", "invalid JSON");
  expect_text_error(text, "", "line 3, column 14");
  expect_text_error(text, "", "byte 31");
  expect_text_error("", "", "invalid JSON");
  expect_text_error("[1, 2]", "", "must be an object");
}

TEST(SceneJsonErrors, UnknownKeysAtEveryLevel) {
  json j = full_scene();
  j["foo"] = 1;
  expect_error(j, "foo", "unknown key 'foo'");
  j = full_scene();
  j["bodies"][0]["material"]["foo"] = 1;
  expect_error(j, "bodies[0].material.foo", "unknown key 'foo'");
  j = full_scene();
  j["solver"]["camera"] = 1;
  expect_error(j, "solver.camera", "unknown key 'camera'");
  j = full_scene();
  j["tracks"][1]["speed"] = 1;
  expect_error(j, "tracks[1].speed", "unknown key 'speed'");
  j = full_scene();
  j["lights"] = json::object();  // not part of this format
  expect_error(j, "lights", "unknown key 'lights'");
  j = full_scene();
  j["camera"] = {{"position", {0, -10, 2}}, {"lens", 35}};
  expect_error(j, "camera.lens", "unknown key 'lens'");
}

TEST(SceneJsonErrors, CameraMustSeeSomething) {
  json j = full_scene();
  j["camera"] = {{"position", {0, -10, 2}}, {"target", {0, 0, 1}}, {"fov", 180}};
  expect_error(j, "camera.fov", "must be in (0, 180)");
  j["camera"] = {{"position", {0, 0, 5}}, {"target", {0, 0, 1}}};  // looking along up
  expect_error(j, "camera", "up must not be parallel");
  j["camera"] = {{"position", {1, 2, 3}}, {"target", {1, 2, 3}}};
  expect_error(j, "camera", "position and target must differ");
  j["camera"] = {{"position", {0, -10, 2}}, {"target", {0, 0, 1}}, {"fov", 50}};
  const Scene scene = parse_scene(j.dump(), kFile);
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_EQ(scene.camera->fov, 50);
  EXPECT_EQ(scene.camera->up, Vec3(0, 0, 1));
}

TEST(SceneJsonErrors, SolverRangesNameTheField) {
  json j = full_scene();
  j["solver"]["body_elasticity"] = -1;
  expect_error(j, "solver.body_elasticity", "must be >= 0");
  j = full_scene();
  j["solver"]["dt"] = 0;
  expect_error(j, "solver.dt", "must be > 0");
  j = full_scene();
  j["solver"]["contact_dt_factor"] = 0;
  expect_error(j, "solver.contact_dt_factor", "must be in (0, 1]");
  j = full_scene();
  j["solver"]["contact_dt_factor"] = 1;  // upper bound is allowed...
  EXPECT_NO_THROW(parse_scene(j.dump(), kFile));
  j["solver"]["contact_dt_factor"] = 1.0000001;  // ...just above it is not
  expect_error(j, "solver.contact_dt_factor", "must be in (0, 1]");
  j = full_scene();
  j["solver"]["max_retries"] = 21;
  expect_error(j, "solver.max_retries", "must be in [0, 20]");
  json solver = {{"bodies", {{{"material", {{"mass", 1}}}}}},
                 {"solver", {{"constraint_solver", "cholesky"}}}};
  expect_error(solver, "solver.constraint_solver", "must be one of \"dense\", \"sparse\"");
  // The adaptive step is the implicit integrator's (sim/adaptive_step.h); its tolerance > 0.
  json adaptive = {{"bodies", {{{"material", {{"mass", 1}}}}}},
                   {"solver", {{"integrator", "rk4"}, {"adaptive", true}}}};
  expect_error(adaptive, "solver", "adaptive: only the implicit integrator");
  adaptive["solver"]["integrator"] = "implicit";
  EXPECT_TRUE(parse_scene(adaptive.dump(), kFile).solver.adaptive);
  adaptive["solver"]["adaptive_tolerance"] = 0;
  expect_error(adaptive, "solver.adaptive_tolerance", "must be > 0");
}

TEST(SceneJsonErrors, DuplicateKeyNamesItsPath) {
  expect_text_error(R"({"bodies": [{"material": {"mass": 1, "mass": 2}}]})",
                    "bodies[0].material.mass", "duplicate key 'mass'");
  expect_text_error(R"({"name": "a", "bodies": [{"material": {"mass": 1}}], "name": "b"})", "name",
                    "duplicate key");
}

TEST(SceneJsonErrors, WrongTypes) {
  json j = full_scene();
  j["solver"]["dt"] = "fast";
  expect_error(j, "solver.dt", "must be a number");
  j["solver"]["dt"] = nullptr;
  expect_error(j, "solver.dt", "must be a number");
  j = full_scene();
  j["bodies"][0]["material"]["w0"] = true;
  expect_error(j, "bodies[0].material.w0", "must be a number");
  j = full_scene();
  j["bodies"][0]["tessellation"]["rings"] = 16.5;
  expect_error(j, "bodies[0].tessellation.rings", "must be an integer");
  j["bodies"][0]["tessellation"]["rings"] = 4.0;  // integral value written as a float is fine
  EXPECT_NO_THROW(parse_scene(j.dump(), kFile));
  j = full_scene();
  j["bodies"][0]["position"] = {1, 2};
  expect_error(j, "bodies[0].position", "must be an array of 3 numbers");
  j = full_scene();
  j["bodies"][0]["velocity"] = {1, "2", 3};
  expect_error(j, "bodies[0].velocity[1]", "must be a number");
  j = full_scene();
  j["bodies"][0]["orientation"] = {1, 0, 0};
  expect_error(j, "bodies[0].orientation", "must be an array of 4 numbers");
  j = full_scene();
  j["name"] = 5;
  expect_error(j, "name", "must be a string");
  j = full_scene();
  j["bodies"][0]["level"] = "soft";
  expect_error(j, "bodies[0].level", "must be one of \"rigid\", \"global\", \"local\", \"auto\"");
  j = full_scene();
  j["solver"]["contact_step_reduction"] = 1;
  expect_error(j, "solver.contact_step_reduction", "must be true or false");
  j = full_scene();
  j["bodies"] = json::object();
  expect_error(j, "bodies", "must be an array");
  j = full_scene();
  j["bodies"][0]["material"] = 1;
  expect_error(j, "bodies[0].material", "must be an object");
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"] = "round";
  expect_error(j, "bodies[0].shape.q_s", "must be an array of 11 numbers or an object");
}

TEST(SceneJsonErrors, MissingRequiredParts) {
  expect_text_error(R"({"name": "empty"})", "bodies", "is required (or 'figures' or 'liquids')");
  expect_text_error(R"({"bodies": []})", "bodies", "at least one body");
  expect_text_error(R"({"bodies": [{}]})", "bodies[0].material", "is required");
  json j = full_scene();
  j["tracks"][0].erase("keys");
  expect_error(j, "tracks[0].keys", "is required");
  j = full_scene();
  j["springs"][0].erase("node");
  expect_error(j, "springs[0]", "exactly one of 'node' and 'material_point'");
}

TEST(SceneJsonErrors, MissingFileNamesTheFile) {
  try {
    load_scene(std::filesystem::temp_directory_path().string());
    ADD_FAILURE() << "expected pbm::Error for a directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos) << e.what();
  }
  const std::string path = "/nonexistent_pbm_dir/missing_scene_42.json";
  try {
    load_scene(path);
    ADD_FAILURE() << "expected pbm::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.path(), "");
    EXPECT_NE(std::string(e.what()).find("missing_scene_42.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos);
  }
}

}  // namespace
}  // namespace pbm::scene_test
