// What the studio edits, without Qt: edits of the scene as replacements of JSON values (the
// runner's EditScene), checked against the parser before they are posted, an undo/redo history
// of them, the format's description (unit, range) of every field, and body presets.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "scene/scene_format.h"

namespace pbm {

struct SceneEdit {
  std::string pointer;  // RFC 6901, into scene_to_json(scene)
  // A mouse drag is recorded by the runner as it happens: its entry holds the whole scene from
  // before the drag, and `after` stays null until the drag is undone (then it is the scene from
  // just before the undo, for redo).
  nlohmann::json before, after;
  std::string label;  // for the Edit menu ("Undo w1")
};

// The scene with `value` at `pointer`, validated by parse_scene; nullopt and `error` (naming the
// field's JSON path) when the parser refuses it.
std::optional<Scene> apply_edit(const Scene& scene, const std::string& pointer,
                                const nlohmann::json& value, std::string& error);

// An edit of `scene` to `value` at `pointer` with its current value as `before`.
SceneEdit make_edit(const Scene& scene, const std::string& pointer, nlohmann::json value,
                    std::string label);

class EditHistory {
 public:
  void push(SceneEdit edit);  // a new edit: the redo branch is dropped
  bool can_undo() const { return done_ > 0; }
  bool can_redo() const { return done_ < edits_.size(); }
  // The edit to post to undo (its `before`) or redo (its `after`); moves the cursor.
  SceneEdit& undo();
  const SceneEdit& redo();
  const SceneEdit* next_undo() const { return can_undo() ? &edits_[done_ - 1] : nullptr; }
  const SceneEdit* next_redo() const { return can_redo() ? &edits_[done_] : nullptr; }
  void clear();

 private:
  std::vector<SceneEdit> edits_;
  std::size_t done_ = 0;
};

// The format's words for a field (scene/scene_format.h): its description (with the unit in
// brackets) and its range.
struct FieldInfo {
  std::string description;
  std::string range;  // "≥ 0", "> 0", "[0, 1]", "(0, 180)", one of the enum values, or ""
  std::vector<std::string> choices;  // enum values
};
FieldInfo describe_field(const std::string& pointer);
// The format's sections (describe_scene_format()), built once for the UI.
const std::vector<SectionDescription>& scene_format();

// A body preset as the scene JSON of one body ("sphere", "cube-ish", "cylinder-ish", "tapered",
// "bent"), placed at `position`.
nlohmann::json body_preset(const std::string& preset, const std::string& name,
                           const Vec3& position);
const std::vector<std::string>& body_preset_names();

// The scene path of a track target for an inspector field, if the field can be keyframed
// (scene/track_targets.h): "/gravity/2" -> "gravity[2]", "/bodies/0/shape/rest/a1" ->
// "bodies[0].q_s0[1]", "/obstacles/0/center/2" -> "obstacles[0].point[2]" for a box. Empty
// otherwise.
std::string track_target_for(const Scene& scene, const std::string& pointer);

// The scene's tracks (JSON array) with a key of `value` at `time` on `target` (a new track when
// there is none; the key at that time replaced), or without the key at `time`.
nlohmann::json tracks_with_key(const nlohmann::json& tracks, const std::string& target, double time,
                               double value);
nlohmann::json tracks_without_key(const nlohmann::json& tracks, const std::string& target,
                                  double time);

}  // namespace pbm
