// Scene files: JSON text <-> Scene (engine/scene/scene.h). The format, with every key, unit and
// range, is the tables of scene/scene_format.h, documented in scenes/README.md and
// scenes/scene.schema.json.
//
// Loading validates everything once, at the boundary, so that nothing past it needs to check
// its input again: every error is a pbm::Error whose file() is the scene file and whose path() is
// the JSON path of the offending value ("bodies[0].material.w1", "" for whole-file errors such as
// malformed JSON). A Scene is returned only when all of it is valid; there is never a half-built
// Scene. What a file can cost is bounded (scene/scene_format.h, "limits"): a file too large, too
// deep, with too many values, items or nodes is refused before the work it asks for.
#pragma once

#include <string>

#include "scene/scene.h"

namespace pbm {

// Reads and validates the scene file at `path`. Scene::file is set to `path`.
// Throws pbm::Error("cannot open file") when it cannot be read; a file above kMaxSceneFileBytes
// is refused before it is read.
Scene load_scene(const std::string& path);

// Validates `json_text`; `file_for_messages` becomes Scene::file and the file of every error.
Scene parse_scene(const std::string& json_text, const std::string& file_for_messages);

// Pretty JSON (2-space indent) holding every field, q_s by parameter name, track targets in
// index form. parse_scene(scene_to_json(s), f) reproduces s exactly (doubles are written with
// round-trip precision).
std::string scene_to_json(const Scene& scene);

// The scene as a file at `path` holds it: the files it names relative to its own folder (a mesh
// obstacle's, a motion capture's) named relative to `path`'s folder instead, and `file` = path.
Scene scene_saved_as(const Scene& scene, const std::string& path);

// Writes scene_to_json(scene_saved_as(scene, path)) to path + ".tmp", then renames it over
// `path`, so a crash or a full disk never leaves a half-written scene file. Throws
// pbm::Error(path, "", ...) on failure.
void save_scene(const Scene& scene, const std::string& path);

}  // namespace pbm
