// Scene files in and out (format: scenes/README.md): the scene's own table, whose rows are the
// top-level keys and hold the other sections (scene/scene_sections.h), reading every part before
// returning a Scene, and the atomic save.
#include "scene/scene_json.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "scene/scene_sections.h"

namespace pbm {

namespace {

// How many items each list may hold (scenes/README.md, "Limits"): far above any scene of the
// book, low enough that the checks between items (unique names, one track a target), the mesh
// obstacles' distance grids and the dense constraint solve (3 rows a point, two points a hinge:
// at most 6144 rows, a 300 MB matrix) stay affordable; the node budget bounds the bodies' cost.
constexpr Real kMaxBodies = 1024;
constexpr Real kMaxObstacles = 256;
constexpr Real kMaxForceFields = 256;
constexpr Real kMaxSprings = 4096;
constexpr Real kMaxTracks = 4096;
constexpr Real kMaxConstraints = 1024;
constexpr Real kMaxFigures = 256;
constexpr Real kMaxLiquids = 16;  // each up to 256^3 cells: the memory, not the list, binds

// Bodies come before every list that refers to them, tracks after what they drive.
constexpr auto kSceneFields = std::to_array<Field<Scene>>({
    value<&Scene::name>({.key = "name", .description = "Display name."}),
    value<&Scene::gravity>({.key = "gravity",
                            .unit = "m/s^2",
                            .description = "Gravitational acceleration, world frame (z up)."}),
    object<&Scene::solver, kSolverSection>(
        {.key = "solver", .section = "solver", .description = "Time stepping."}),
    object<&Scene::camera, kCameraSection>(
        {.key = "camera",
         .section = "camera",
         .default_note = "automatic framing",
         .description = "Renderer camera; scenes without one are framed automatically."}),
    list<&Scene::bodies, kBodySection>({.key = "bodies",
                                        .limit = kMaxBodies,
                                        .section = "body",
                                        .description = "Deformable bodies."}),
    list<&Scene::obstacles, kObstacleSection>(
        {.key = "obstacles",
         .limit = kMaxObstacles,
         .section = "obstacle",
         .description = "Planes, boxes and meshes (fixed, or moved by tracks)."}),
    list<&Scene::force_fields, kForceFieldSection>(
        {.key = "force_fields",
         .limit = kMaxForceFields,
         .section = "force_field",
         .description = "Extra uniform accelerations or forces."}),
    list<&Scene::springs, kSpringSection>(
        {.key = "springs",
         .limit = kMaxSprings,
         .section = "spring",
         .description = "Point-to-target springs (sec. 6.4's mouse spring)."}),
    // Before the tracks, which may drive a liquid's inflows and surface pressure.
    list<&Scene::liquids, kLiquidSection>(
        {.key = "liquids",
         .limit = kMaxLiquids,
         .section = "liquid",
         .description = "Liquids on a staggered grid with a free surface (ch. 16)."}),
    list<&Scene::tracks, kTrackSection>({.key = "tracks",
                                         .limit = kMaxTracks,
                                         .section = "track",
                                         .description = "Keyframed values."}),
    list<&Scene::constraints, kConstraintSection>(
        {.key = "constraints",
         .limit = kMaxConstraints,
         .section = "constraint",
         .description = "Point-to-point constraints and hinges between bodies (ch. 7)."}),
    list<&Scene::figures, kFigureSection>(
        {.key = "figures",
         .limit = kMaxFigures,
         .section = "figure",
         .description = "Articulated figures: trees of rigid segments (ch. 15)."}),
});

// A scene simulates something: a deformable body, an articulated figure or a liquid.
void check_scene(const JsonNode& node, Scene& scene, const ReadContext&) {
  if (scene.bodies.empty() && scene.figures.empty() && scene.liquids.empty()) {
    const std::optional<JsonNode> bodies = find_child(node, "bodies");
    if (bodies) fail(*bodies, "needs at least one body (or a figure or a liquid)");
    fail(JsonNode{node.value, "bodies", node.file}, "is required (or 'figures' or 'liquids')");
  }
}

constexpr JsonLimits kSceneJsonLimits{.max_bytes = kMaxSceneFileBytes,
                                      .max_depth = kMaxNestingDepth,
                                      .max_values = kMaxJsonValues,
                                      .max_string_bytes = kMaxStringBytes};

}  // namespace

constexpr Section<Scene> kSceneSection{
    .name = "", .noun = "scene", .fields = kSceneFields, .check = check_scene};

Scene parse_scene(const std::string& json_text, const std::string& file_for_messages) {
  const nlohmann::json document = parse_json_text(json_text, file_for_messages, kSceneJsonLimits);
  Scene scene;
  scene.file = file_for_messages;
  read_section(kSceneSection, root_node(document, file_for_messages), scene, ReadContext{scene, 0});
  return scene;
}

Scene load_scene(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw Error(path, "", "cannot open file: it is a directory");
  }
  // Refused before reading: a file that is too large costs nothing.
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > kMaxSceneFileBytes)
    throw Error(path, "", too_large_message(size, kMaxSceneFileBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "", "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path, "", "cannot read file");
  return parse_scene(text.str(), path);
}

std::string scene_to_json(const Scene& scene) {
  return write_section(kSceneSection, scene).dump(2) + "\n";
}

namespace {

// A file the scene names relative to its own folder (a mesh, a motion capture), named again
// relative to `to`'s folder, so that a scene saved elsewhere (save as, the studio's autosave)
// still finds it. Absolute names, and every name of a scene read from text, stay as they are.
void rebase(std::string& name, const std::string& from, const std::string& to) {
  namespace fs = std::filesystem;
  if (name.empty() || from.empty() || fs::path(name).is_absolute()) return;
  const fs::path target = fs::absolute(fs::path(from).parent_path() / name).lexically_normal();
  const fs::path folder = fs::absolute(fs::path(to)).parent_path().lexically_normal();
  const fs::path relative = target.lexically_relative(folder);
  name = relative.empty() ? target.string() : relative.string();
}

}  // namespace

Scene scene_saved_as(const Scene& scene, const std::string& path) {
  Scene out = scene;
  for (ObstacleDef& o : out.obstacles) rebase(o.file, scene.file, path);
  for (FigureDef& f : out.figures) {
    if (f.mocap) rebase(f.mocap->file, scene.file, path);
  }
  out.file = path;
  return out;
}

void save_scene(const Scene& scene, const std::string& path) {
  const std::string text = scene_to_json(scene_saved_as(scene, path));
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path, "", "cannot write file '" + temporary + "'");
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(path, "", "cannot write file '" + temporary + "' (disk full?)");
    }
  }
  // rename() replaces the old file in one step on POSIX file systems.
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error(path, "", "cannot replace file: " + error.message());
  }
}

}  // namespace pbm
