// The studio's edits without Qt (app/studio/scene_document.h, panels.h's track keys, picking.h):
// an edit is validated by the parser and undone exactly; the format's tables give units and
// ranges; a pixel ray hits the body the camera looks at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "picking.h"
#include "scene/scene_json.h"
#include "scene_document.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

using json = nlohmann::json;

Scene jello() {
  return load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/jello-ball.json");
}

TEST(StudioDocument, EditIsValidatedAndUndoRestoresTheScene) {
  const Scene scene = jello();
  std::string error;
  const auto edited = apply_edit(scene, "/bodies/0/material/w1", 12.5, error);
  ASSERT_TRUE(edited) << error;
  EXPECT_EQ(edited->bodies[0].material.w1, 12.5);
  const SceneEdit edit = make_edit(scene, "/bodies/0/material/w1", 12.5, "w1");
  EXPECT_EQ(edit.before, 15.0);
  const auto undone = apply_edit(*edited, edit.pointer, edit.before, error);
  ASSERT_TRUE(undone);
  EXPECT_EQ(scene_to_json(*undone), scene_to_json(scene));
}

TEST(StudioDocument, RefusedEditNamesTheField) {
  const Scene scene = jello();
  std::string error;
  EXPECT_FALSE(apply_edit(scene, "/bodies/0/material/w1", -1.0, error));
  EXPECT_NE(error.find("bodies[0].material.w1"), std::string::npos) << error;
  EXPECT_NE(error.find("must be >= 0"), std::string::npos) << error;
  EXPECT_FALSE(apply_edit(scene, "/bodies/0/material/no_such_key", 1.0, error));
  EXPECT_FALSE(error.empty());
}

TEST(StudioDocument, HistoryDropsTheRedoBranchOnANewEdit) {
  EditHistory h;
  h.push({"/a", 1, 2, "a"});
  h.push({"/b", 3, 4, "b"});
  EXPECT_EQ(h.undo().pointer, "/b");
  ASSERT_TRUE(h.can_redo());
  h.push({"/c", 5, 6, "c"});
  EXPECT_FALSE(h.can_redo());
  EXPECT_EQ(h.undo().pointer, "/c");
  EXPECT_EQ(h.undo().pointer, "/a");
  EXPECT_FALSE(h.can_undo());
  EXPECT_EQ(h.redo().after, 2);
}

TEST(StudioDocument, TheFormatGivesUnitsAndRanges) {
  const FieldInfo w1 = describe_field("/bodies/0/material/w1");
  EXPECT_EQ(w1.range, ">= 0");
  EXPECT_NE(w1.description.find("3.34"), std::string::npos);
  EXPECT_EQ(describe_field("/bodies/0/material/roughness").range, "[0, 1]");
  EXPECT_EQ(describe_field("/camera/fov").range, "(0, 180)");
  EXPECT_NE(describe_field("/solver/dt").description.find("s"), std::string::npos);
  const FieldInfo level = describe_field("/bodies/0/level");
  EXPECT_EQ(level.choices, (std::vector<std::string>{"rigid", "global", "local", "auto"}));
}

TEST(StudioDocument, EveryPresetIsAValidBody) {
  for (const std::string& preset : body_preset_names()) {
    json scene = json::parse(scene_to_json(jello()));
    scene["bodies"].push_back(body_preset(preset, "extra", Vec3(5, 0, 3)));
    EXPECT_NO_THROW(parse_scene(scene.dump(), preset)) << preset;
  }
}

TEST(StudioDocument, KeyframesOnTheFieldUnderEdit) {
  const Scene scene = jello();
  EXPECT_EQ(track_target_for(scene, "/gravity/2"), "gravity[2]");
  EXPECT_EQ(track_target_for(scene, "/bodies/0/shape/rest/a3"), "bodies[0].q_s0[3]");
  EXPECT_EQ(track_target_for(scene, "/camera/fov"), "camera.fov");
  EXPECT_EQ(track_target_for(scene, "/bodies/0/material/w1"), "");
  EXPECT_EQ(track_target_for(scene, "/obstacles/1/point/2"), "obstacles[1].point[2]");
  EXPECT_EQ(track_target_for(scene, "/obstacles/0/point/0"), "obstacles[0].point[0]");
  // Both obstacles are planes: "center" is a box's key, so no field of theirs is at this pointer
  // (a box's centre: test_scene_tracks_json.cpp).
  EXPECT_EQ(track_target_for(scene, "/obstacles/1/center/2"), "");
  json tracks = tracks_with_key(json::array(), "gravity[2]", 1.0, -5.0);
  tracks = tracks_with_key(tracks, "gravity[2]", 0.5, -9.81);
  tracks = tracks_with_key(tracks, "gravity[2]", 1.0, -4.0);  // replaces the key at 1 s
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0]["keys"], json::parse("[[0.5, -9.81], [1.0, -4.0]]"));
  json j = json::parse(scene_to_json(scene));
  j["tracks"] = tracks;
  const Scene keyed = parse_scene(j.dump(), "keyed");
  EXPECT_EQ(keyed.tracks[0].keys[1].value, -4.0);
  EXPECT_TRUE(
      tracks_without_key(tracks_without_key(tracks, "gravity[2]", 0.5), "gravity[2]", 1.0).empty());
}

// An octahedron of radius 1 as a pickable mesh (pick = `pick`) at `offset`.
draw::Mesh octahedron(int pick, const Eigen::Vector3f& offset) {
  auto topology = std::make_shared<draw::MeshTopology>();
  topology->triangles = {{0, 4, 3}, {3, 4, 1}, {1, 4, 2}, {2, 4, 0},
                         {3, 5, 0}, {1, 5, 3}, {2, 5, 1}, {0, 5, 2}};
  return {.pick = pick,
          .positions = std::make_shared<std::vector<draw::Vec3f>>(std::vector<draw::Vec3f>{
              {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}),
          .topology = topology,
          .offset = offset};
}

TEST(StudioPicking, CentreRayHitsTheBodyInFront) {
  // A unit sphere of 8 triangles' worth at the origin, seen from -y: the centre pixel's ray
  // hits it at y = -1 (to the facet's flatness), the corner pixel's misses.
  draw::Snapshot snap;
  snap.meshes.push_back(octahedron(0, Eigen::Vector3f::Zero()));
  Camera camera;
  camera.position = {0, -10, 0};
  camera.target = {0, 0, 0};
  const Ray centre = pixel_ray(camera, 320, 240, 640, 480);
  EXPECT_NEAR(centre.direction.y(), 1.0f, 1e-6f);
  const auto pick = pick_body(snap, centre);
  ASSERT_TRUE(pick);
  EXPECT_EQ(pick->body, 0);
  EXPECT_NEAR(pick->distance, 9.0f, 1e-4f);  // at the vertex (0, -1, 0)
  EXPECT_EQ(pick->node, 3);                  // (0, -1, 0) is the nearest corner
  EXPECT_FALSE(pick_body(snap, pixel_ray(camera, 0, 0, 640, 480)));
  // The drag plane faces the camera through the picked point: moving the cursor right moves
  // the target along +x at y = -1.
  const Eigen::Vector3f target =
      drag_target(camera, pixel_ray(camera, 400, 240, 640, 480), pick->point);
  EXPECT_NEAR(target.y(), -1.0f, 1e-5f);
  EXPECT_GT(target.x(), 0.5f);
}

// Picking reads draw::Mesh as the renderer does: placed by its offset, and only where pick >= 0
// (a mesh obstacle in front is seen through); pick_bounds frames one body.
TEST(StudioPicking, MeshesArePlacedAndOnlyPickableOnesAreHit) {
  draw::Snapshot snap;
  snap.meshes.push_back(octahedron(-1, Eigen::Vector3f(0, -4, 0)));  // an obstacle, in front
  snap.meshes.push_back(octahedron(3, Eigen::Vector3f(0, 2, 0)));    // body 3, behind it
  Camera camera;
  camera.position = {0, -10, 0};
  camera.target = {0, 0, 0};
  const auto pick = pick_body(snap, pixel_ray(camera, 320, 240, 640, 480));
  ASSERT_TRUE(pick);
  EXPECT_EQ(pick->body, 3);
  EXPECT_NEAR(pick->distance, 11.0f, 1e-4f);  // its vertex (0, -1, 0) moved to y = 1
  EXPECT_NEAR(pick->point.y(), 1.0f, 1e-5f);
  snap.meshes[1].pick = -1;
  EXPECT_FALSE(pick_body(snap, pixel_ray(camera, 320, 240, 640, 480)));
  snap.meshes[1].pick = 3;
  const draw::Bounds bounds = pick_bounds(snap, 3);
  EXPECT_NEAR(bounds.min.y(), 1.0f, 1e-6f);
  EXPECT_NEAR(bounds.max.y(), 3.0f, 1e-6f);
  EXPECT_TRUE(pick_bounds(snap, 7).empty());
}

}  // namespace
}  // namespace pbm

namespace pbm {
namespace {

// Every value a shipped file gives is in the file the studio saved, with the same value; the
// saved file may add defaults and write some values in their canonical spelling, each checked
// against what it stands for rather than against the writer's output:
// - numbers to 1e-12 relative (a quaternion is normalized on load);
// - a body named in the file, saved as its index in `bodies`;
// - a shape vector given as an array, saved as an object keyed by parameter names: the same
//   values;
// - a track target spelled with a parameter name, saved as the parser's canonical target.
struct Containment {
  const json& saved_root;
  const Scene& scene;  // the shipped file as the parser read it
  std::string saved_file;
  std::vector<std::string> differences;

  void differ(const std::string& path, const json& given, const json& saved) {
    differences.push_back(path + ": " + given.dump() + " saved as " + saved.dump());
  }
  void check(const json& given, const json& saved, const std::string& path) {
    if (given.is_object() && saved.is_object()) {
      for (const auto& [key, value] : given.items()) {
        const std::string child = path.empty() ? key : path + "." + key;
        if (!saved.contains(key)) {
          differences.push_back(child + ": missing from the saved file");
        } else {
          check(value, saved[key], child);
        }
      }
    } else if (given.is_array() && saved.is_array() && given.size() == saved.size()) {
      for (std::size_t i = 0; i < given.size(); ++i) {
        check(given[i], saved[i], path + "[" + std::to_string(i) + "]");
      }
    } else if (given.is_array() && saved.is_object() && given.size() == saved.size()) {
      std::vector<double> a, b;
      for (const json& value : given) a.push_back(value.get<double>());
      for (const auto& [key, value] : saved.items()) b.push_back(value.get<double>());
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      if (a != b) differ(path, given, saved);
    } else if (given.is_number() && saved.is_number()) {
      const double x = given.get<double>(), y = saved.get<double>();
      if (std::abs(x - y) > 1e-12 * std::abs(x)) differ(path, given, saved);
    } else if (given.is_string() && saved.is_number_unsigned() && path.ends_with(".body")) {
      const json& bodies = saved_root.at("bodies");
      const auto index = saved.get<std::size_t>();
      if (index >= bodies.size() || bodies[index].value("name", "") != given.get<std::string>()) {
        differ(path, given, saved);
      }
    } else if (given.is_string() && saved.is_string() && path.starts_with("tracks[") &&
               path.ends_with("].target")) {
      const std::size_t track = std::stoul(path.substr(7));
      if (saved.get<std::string>() != scene.tracks.at(track).target) differ(path, given, saved);
    } else if (given.is_string() && saved.is_string() && path.ends_with(".file")) {
      // A file named relative to the scene is named relative to where it was saved.
      namespace fs = std::filesystem;
      const auto resolved = [](const std::string& scene_file, const std::string& name) {
        return fs::weakly_canonical(fs::path(scene_file).parent_path() / name);
      };
      if (resolved(scene.file, given.get<std::string>()) !=
          resolved(saved_file, saved.get<std::string>())) {
        differ(path, given, saved);
      }
    } else if (given != saved) {
      differ(path, given, saved);
    }
  }
};

// Save and load of every scene the project ships is lossless (docs/architecture.md, "Data
// flow": the Scene is the whole document), judged without the writer: every value of the shipped
// file is in the saved file, and the saved file, loaded, simulates to the same bits.
TEST(StudioDocument, EveryShippedSceneRoundTripsThroughSaveAndLoad) {
  namespace fs = std::filesystem;
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(PBM_SOURCE_DIR) / "scenes")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".json" || name == "scene.schema.json") continue;
    const Scene scene = load_scene(entry.path().string());
    const fs::path copy = fs::temp_directory_path() / ("pbm-roundtrip-" + name);
    save_scene(scene, copy.string());
    std::ifstream given_file(entry.path()), saved_file(copy);
    const json saved = json::parse(saved_file);
    Containment containment{saved, scene, copy.string(), {}};
    containment.check(json::parse(given_file), saved, "");
    for (const std::string& difference : containment.differences) {
      ADD_FAILURE() << name << ": " << difference;
    }
    Simulation original(scene), reloaded(load_scene(copy.string()));
    for (int frame = 0; frame < 3; ++frame) {
      ASSERT_TRUE(advance_frame(original).ok) << name;
      ASSERT_TRUE(advance_frame(reloaded).ok) << name;
    }
    EXPECT_EQ(hash_state(reloaded.state), hash_state(original.state)) << name;
    fs::remove(copy);
    ++scenes;
  }
  EXPECT_GE(scenes, 9);
}

}  // namespace
}  // namespace pbm
