#include "scene_document.h"

#include <stdexcept>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/scene_json.h"
#include "scene/track_targets.h"

namespace pbm {

using json = nlohmann::json;

std::optional<Scene> apply_edit(const Scene& scene, const std::string& pointer, const json& value,
                                std::string& error) {
  try {
    json j = json::parse(scene_to_json(scene));
    if (pointer.empty()) {
      j = value;
    } else {
      j.at(json::json_pointer(pointer)) = value;  // the field must exist: no typo'd keys
    }
    return parse_scene(j.dump(), scene.file);
  } catch (const Error& e) {
    error = e.what();
  } catch (const json::exception& e) {
    error = scene.file + ": " + pointer + ": " + e.what();
  }
  return std::nullopt;
}

SceneEdit make_edit(const Scene& scene, const std::string& pointer, json value, std::string label) {
  const json j = json::parse(scene_to_json(scene));
  SceneEdit edit;
  edit.pointer = pointer;
  edit.before = pointer.empty() ? j : j.at(json::json_pointer(pointer));
  edit.after = std::move(value);
  edit.label = std::move(label);
  return edit;
}

void EditHistory::push(SceneEdit edit) {
  edits_.resize(done_);
  edits_.push_back(std::move(edit));
  done_ = edits_.size();
}
SceneEdit& EditHistory::undo() {
  if (!can_undo()) throw std::logic_error("nothing to undo");
  return edits_[--done_];
}
const SceneEdit& EditHistory::redo() {
  if (!can_redo()) throw std::logic_error("nothing to redo");
  return edits_[done_++];
}
void EditHistory::clear() {
  edits_.clear();
  done_ = 0;
}

const std::vector<SectionDescription>& scene_format() {
  static const std::vector<SectionDescription> format = describe_scene_format();
  return format;
}

FieldInfo describe_field(const std::string& pointer) {
  FieldInfo info;
  const std::optional<FieldDescription> field = describe_scene_key(scene_format(), pointer);
  if (!field) return info;  // not a key of the format: no words for it
  info.description = std::string(field->format.description);
  if (!field->format.unit.empty()) {
    info.description +=
        (info.description.empty() ? "[" : " [") + std::string(field->format.unit) + "]";
  }
  info.range = range_text(field->format.range);
  for (const std::string_view choice : field->format.choices) info.choices.emplace_back(choice);
  return info;
}

const std::vector<std::string>& body_preset_names() {
  static const std::vector<std::string> names{"sphere", "cube-ish", "cylinder-ish", "tapered",
                                              "bent"};
  return names;
}

json body_preset(const std::string& preset, const std::string& name, const Vec3& position) {
  json shape;
  // Superquadric squareness (2.7): eps -> 0 squares the profile, eps = 1 keeps it round.
  if (preset == "sphere") {
    shape = {{"kind", "superquadric"},
             {"q_s", {{"a0", 1}, {"a1", 1}, {"a2", 1}, {"a3", 1}, {"eps1", 1}, {"eps2", 1}}}};
  } else if (preset == "cube-ish") {
    shape = {{"kind", "superquadric"},
             {"q_s", {{"a0", 1}, {"a1", 1}, {"a2", 1}, {"a3", 1}, {"eps1", 0.3}, {"eps2", 0.3}}}};
  } else if (preset == "cylinder-ish") {
    shape = {
        {"kind", "superquadric"},
        {"q_s", {{"a0", 1}, {"a1", 0.7}, {"a2", 0.7}, {"a3", 1.4}, {"eps1", 0.3}, {"eps2", 1}}}};
  } else if (preset == "tapered") {  // (2.10) with t1 = t2
    shape = {{"kind", "taper_bend"},
             {"q_s",
              {{"a0", 1},
               {"a1", 0.8},
               {"a2", 0.8},
               {"a3", 1.3},
               {"eps1", 1},
               {"eps2", 1},
               {"t1", 0.6},
               {"t2", 0.6},
               {"b1", 0},
               {"b2", 0},
               {"b3", 1}}}};
  } else if (preset == "bent") {  // (2.10): bend amount b1 over the whole length
    shape = {{"kind", "taper_bend"},
             {"q_s",
              {{"a0", 1},
               {"a1", 0.5},
               {"a2", 0.5},
               {"a3", 1.6},
               {"eps1", 1},
               {"eps2", 1},
               {"t1", 0},
               {"t2", 0},
               {"b1", 0.5},
               {"b2", 0},
               {"b3", 1}}}};
  } else {
    throw std::invalid_argument("no body preset '" + preset + "'");
  }
  json stiffness = json::object();
  for (const auto& [key, value] : shape["q_s"].items()) stiffness[key] = 2e4;
  shape["stiffness"] = stiffness;
  return {{"name", name},
          {"level", "local"},
          {"shape", shape},
          {"position", {position.x(), position.y(), position.z()}},
          {"tessellation", {{"kind", "triangles"}, {"rings", 12}, {"segments", 16}}},
          {"material", {{"w0", 20}, {"w1", 15}, {"mass", 100}, {"damping", 1.4}}}};
}

std::string track_target_for(const Scene& scene, const std::string& pointer) {
  return track_target_of_key(scene, pointer);
}

json tracks_with_key(const json& tracks, const std::string& target, double time, double value) {
  json out = tracks;
  for (json& track : out) {
    if (track["target"] != target) continue;
    json keys = json::array();
    bool placed = false;
    for (const json& key : track["keys"]) {
      const double t = key[0].get<double>();
      if (!placed && t >= time) {
        keys.push_back({time, value});
        placed = true;
        if (t == time) continue;
      }
      keys.push_back(key);
    }
    if (!placed) keys.push_back({time, value});
    track["keys"] = keys;
    return out;
  }
  out.push_back({{"target", target}, {"interpolation", "linear"}, {"keys", {{time, value}}}});
  return out;
}

json tracks_without_key(const json& tracks, const std::string& target, double time) {
  json out = json::array();
  for (const json& track : tracks) {
    if (track["target"] != target) {
      out.push_back(track);
      continue;
    }
    json copy = track;
    json keys = json::array();
    for (const json& key : track["keys"]) {
      if (std::abs(key[0].get<double>() - time) > 1e-9) keys.push_back(key);
    }
    if (keys.empty()) continue;  // a track with no key is no track
    copy["keys"] = keys;
    out.push_back(copy);
  }
  return out;
}

}  // namespace pbm
