#include "panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "scene/scene_json.h"

namespace pbm {

using json = nlohmann::json;

namespace {

// Field errors of the inspector, kept until that field is edited successfully.
std::map<std::string, std::string>& field_errors() {
  static std::map<std::string, std::string> errors;
  return errors;
}

void commit(StudioActions& actions, Studio& studio, const std::string& pointer, const json& value,
            const std::string& label) {
  const std::string error = actions.edit(pointer, value, label);
  if (error.empty()) {
    field_errors().erase(pointer);
    studio.last_edited_pointer = pointer;
  } else {
    field_errors()[pointer] = error;
  }
}

void label_with_info(const char* label, const std::string& pointer) {
  const FieldInfo info = describe_field(pointer);
  ImGui::TextUnformatted(label);
  if (!info.range.empty()) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s", info.range.c_str());
  }
  if (!info.description.empty() && ImGui::IsItemHovered()) {
    ImGui::SetTooltip("%s", info.description.c_str());
  }
}

bool is_number_array(const json& v) {
  if (!v.is_array() || v.empty() || v.size() > 4) return false;
  return std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number(); });
}

// One field of the inspector: numbers, strings, booleans, enums and short number arrays are
// edited in place; objects and other arrays open as trees.
void field(Studio& studio, StudioActions& actions, const std::string& key, const json& value,
           const std::string& pointer) {
  ImGui::PushID(pointer.c_str());
  const FieldInfo info = describe_field(pointer);
  if (value.is_object() || (value.is_array() && !is_number_array(value))) {
    if (ImGui::TreeNode(key.c_str())) {
      if (value.is_object()) {
        for (const auto& [k, v] : value.items()) field(studio, actions, k, v, pointer + "/" + k);
      } else {
        for (std::size_t i = 0; i < value.size(); ++i) {
          field(studio, actions, std::to_string(i), value[i], pointer + "/" + std::to_string(i));
        }
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
    return;
  }
  label_with_info(key.c_str(), pointer);
  ImGui::SameLine(170);
  ImGui::SetNextItemWidth(-1);
  if (!info.choices.empty() && value.is_string()) {
    const std::string current = value.get<std::string>();
    if (ImGui::BeginCombo("##v", current.c_str())) {
      for (const std::string& choice : info.choices) {
        if (ImGui::Selectable(choice.c_str(), choice == current) && choice != current) {
          commit(actions, studio, pointer, choice, key);
        }
      }
      ImGui::EndCombo();
    }
  } else if (value.is_boolean()) {
    bool b = value.get<bool>();
    if (ImGui::Checkbox("##v", &b)) commit(actions, studio, pointer, b, key);
  } else if (value.is_number()) {
    double x = value.get<double>();
    ImGui::InputDouble("##v", &x, 0.0, 0.0, "%.6g");
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      if (value.is_number_integer() && std::floor(x) == x) {
        commit(actions, studio, pointer, static_cast<long long>(x), key);
      } else {
        commit(actions, studio, pointer, x, key);
      }
    }
  } else if (is_number_array(value)) {
    double xs[4] = {};
    for (std::size_t i = 0; i < value.size(); ++i) xs[i] = value[i].get<double>();
    ImGui::InputScalarN("##v", ImGuiDataType_Double, xs, static_cast<int>(value.size()), nullptr,
                        nullptr, "%.4g");
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      json a = json::array();
      for (std::size_t i = 0; i < value.size(); ++i) a.push_back(xs[i]);
      commit(actions, studio, pointer, a, key);
    }
  } else if (value.is_string()) {
    char buffer[256];
    std::snprintf(buffer, sizeof(buffer), "%s", value.get<std::string>().c_str());
    ImGui::InputText("##v", buffer, sizeof(buffer));
    if (ImGui::IsItemDeactivatedAfterEdit())
      commit(actions, studio, pointer, std::string(buffer), key);
  } else {
    ImGui::TextUnformatted(value.dump().c_str());
  }
  const auto error = field_errors().find(pointer);
  if (error != field_errors().end()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", error->second.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PopID();
}

// The scene constraint of each point constraint of the model, in model order
// (FrameStats::constraint_violations): a point constraint gives one, a hinge two, in scene order.
std::vector<std::string> point_constraint_names(const Scene& scene) {
  std::vector<std::string> names;
  for (std::size_t c = 0; c < scene.constraints.size(); ++c) {
    const ConstraintDef& def = scene.constraints[c];
    const std::string name = def.name.empty() ? "constraint " + std::to_string(c) : def.name;
    const int points = def.kind == ConstraintKind::hinge ? 2 : 1;
    for (int k = 0; k < points; ++k) names.push_back(name);
  }
  return names;
}

std::string selection_pointer(const Selection& s) {
  if (s.list.empty()) return "-";
  if (s.list == "scene") return "";
  if (s.index < 0) return "/" + s.list;
  return "/" + s.list + "/" + std::to_string(s.index);
}

// Posts `list` with `item` appended and selects the new item.
void add_item(Studio& studio, StudioActions& actions, const std::string& key, const json& items,
              json item, const std::string& label) {
  json with = items;
  with.push_back(std::move(item));
  const std::string error = actions.edit("/" + key, with, label);
  if (error.empty()) {
    studio.selection = {key, static_cast<int>(items.size())};
  } else {
    studio.message = error;
  }
}

// The scene's lists as the format describes them (scene/scene_format.h), each item selectable and
// deletable; "add" offers the studio's body presets for bodies and the format's new item for the
// lists that have one.
void outliner(Studio& studio, StudioActions& actions, const json& scene) {
  if (ImGui::Selectable("Scene (gravity, camera)", studio.selection.list == "scene")) {
    studio.selection = {"scene", -1};
  }
  if (ImGui::Selectable("Solver", studio.selection.list == "solver")) {
    studio.selection = {"solver", -1};
  }
  const std::vector<SectionDescription>& format = scene_format();
  const SectionDescription& top = *find_section(format, "");
  for (std::size_t c = 0; c < top.fields.size(); ++c) {
    const FieldFormat& list = top.fields[c].format;
    if (list.type != ValueType::list) continue;
    const std::string key(list.key);
    const SectionDescription* section = find_section(format, list.section);
    const json items = scene.contains(key) ? scene[key] : json::array();
    ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (!ImGui::TreeNode(key.c_str())) continue;
    for (int i = 0; i < static_cast<int>(items.size()); ++i) {
      const json& item = items[i];
      std::string name = item.contains("name")     ? item["name"].get<std::string>()
                         : item.contains("target") ? item["target"].get<std::string>()
                                                   : std::to_string(i);
      ImGui::PushID(static_cast<int>(c) * 100000 + i);
      const bool selected = studio.selection.list == key && studio.selection.index == i;
      if (ImGui::Selectable(name.c_str(), selected, 0,
                            ImVec2(ImGui::GetContentRegionAvail().x - 24, 0))) {
        studio.selection = {key, i};
      }
      ImGui::SameLine();
      // Bodies need one at least (the parser says so if it is the last).
      if (ImGui::SmallButton("x")) {
        json without = items;
        without.erase(without.begin() + i);
        const std::string error = actions.edit("/" + key, without, "delete " + name);
        if (error.empty()) {
          studio.selection = {};
        } else {
          studio.message = error;
        }
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("delete");
      ImGui::PopID();
    }
    if (list.section == "body") {
      if (ImGui::BeginCombo("##add", "add a body...")) {
        for (const std::string& preset : body_preset_names()) {
          if (ImGui::Selectable(preset.c_str())) {
            const double x = 3.0 * static_cast<double>(items.size());
            add_item(studio, actions, key, items,
                     body_preset(preset, preset + std::to_string(items.size()), Vec3(x, 0, 3)),
                     "add " + preset);
          }
        }
        ImGui::EndCombo();
      }
    } else if (section && !section->new_item.is_null()) {
      const std::string label = "add a " + std::string(section->noun);
      if (ImGui::SmallButton(label.c_str())) {
        add_item(studio, actions, key, items, section->new_item, label);
      }
    }
    ImGui::TreePop();
  }
}

void inspector(Studio& studio, StudioActions& actions, const json& scene) {
  const std::string pointer = selection_pointer(studio.selection);
  if (pointer == "-") {
    ImGui::TextDisabled("Select an item in the outliner, or click a body in the viewport.");
    return;
  }
  json value;
  try {
    value = pointer.empty() ? scene : scene.at(json::json_pointer(pointer));
  } catch (const json::exception&) {
    studio.selection = {};
    return;
  }
  if (pointer.empty()) {  // the scene's own fields, not its collections
    for (const char* key : {"name", "gravity", "camera"}) {
      if (value.contains(key)) field(studio, actions, key, value[key], std::string("/") + key);
    }
    if (!value.contains("camera") && ImGui::Button("add a scene camera")) {
      json whole = scene;
      whole["camera"] = find_section(scene_format(), "camera")->new_item;
      const std::string error = actions.edit("", whole, "add camera");
      if (!error.empty()) studio.message = error;
    }
    return;
  }
  for (const auto& [k, v] : value.items()) field(studio, actions, k, v, pointer + "/" + k);
}

void transport(Studio& studio) {
  Runner& runner = *studio.runner;
  const RunnerStatus& s = studio.status;
  if (ImGui::Button(s.playing ? "Pause" : "Play")) {
    runner.post(s.playing ? Command(Pause{}) : Command(Play{}));
  }
  ImGui::SameLine();
  if (ImGui::Button("Step")) runner.post(StepFrame{});
  ImGui::SameLine();
  if (ImGui::Button("Reset")) runner.post(ResetToStart{});
  float speed = static_cast<float>(studio.speed);
  ImGui::SetNextItemWidth(160);
  if (ImGui::SliderFloat("speed", &speed, 0.05f, 4.0f, "%.2fx", ImGuiSliderFlags_Logarithmic)) {
    studio.speed = speed;
    runner.set_speed(speed);
  }
  ImGui::Text("real-time factor %.2f", s.real_time_factor);
  if (s.scene) {
    const SolverDef& solver = s.scene->solver;
    const int substeps = static_cast<int>(std::ceil(1.0 / (solver.fps * solver.dt) - 1e-9));
    ImGui::Text("dt %.4g s, %d substeps a frame at %.4g fps", solver.dt, substeps, solver.fps);
    ImGui::Text("last frame: %d substeps, %d retries", s.stats.substeps, s.stats.retries);
  }
}

void timeline(Studio& studio, StudioActions& actions, const json& scene) {
  const RunnerStatus& s = studio.status;
  const double fps = s.scene ? s.scene->solver.fps : 30.0;
  int frame = s.frame;
  ImGui::SetNextItemWidth(-1);
  const ImVec2 slider_min = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  // Cached ranges shaded under the slider, keyframes of the selected track as ticks above it.
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float h = ImGui::GetFrameHeight();
  auto x_of = [&](double f) {
    return slider_min.x + width * static_cast<float>(f / std::max(1, s.last_frame));
  };
  for (const auto& [a, b] : s.cached) {
    draw->AddRectFilled(ImVec2(x_of(a), slider_min.y + h - 4),
                        ImVec2(x_of(b + 1), slider_min.y + h), IM_COL32(90, 200, 120, 255));
  }
  if (studio.selection.list == "tracks" && scene.contains("tracks") &&
      studio.selection.index < static_cast<int>(scene["tracks"].size())) {
    for (const json& key : scene["tracks"][studio.selection.index]["keys"]) {
      const float x = x_of(key[0].get<double>() * fps);
      draw->AddTriangleFilled(ImVec2(x - 4, slider_min.y), ImVec2(x + 4, slider_min.y),
                              ImVec2(x, slider_min.y + 6), IM_COL32(255, 210, 60, 255));
    }
  }
  if (ImGui::SliderInt("##frame", &frame, 0, s.last_frame, "frame %d")) {
    studio.runner->post(Seek{frame});
  }
  ImGui::Text("t = %.3f s of %.3f s", s.frame / fps, s.last_frame / fps);
  const std::string target =
      s.scene ? track_target_for(*s.scene, studio.last_edited_pointer) : std::string();
  if (target.empty()) {
    ImGui::TextDisabled("edit a keyframable field (q_s rest, gravity, spring, camera) to key it");
    return;
  }
  ImGui::Text("field %s", target.c_str());
  const double time = s.frame / fps;
  json value;
  try {
    value = scene.at(json::json_pointer(studio.last_edited_pointer));
  } catch (const json::exception&) {
    return;
  }
  const json tracks = scene.contains("tracks") ? scene["tracks"] : json::array();
  if (ImGui::Button("Set key") && value.is_number()) {
    const std::string error = actions.edit(
        "/tracks", tracks_with_key(tracks, target, time, value.get<double>()), "key " + target);
    if (!error.empty()) studio.message = error;
  }
  ImGui::SameLine();
  if (ImGui::Button("Delete key")) {
    const std::string error =
        actions.edit("/tracks", tracks_without_key(tracks, target, time), "delete key " + target);
    if (!error.empty()) studio.message = error;
  }
}

void stats(Studio& studio) {
  const FrameStats& f = studio.status.stats;
  double total = 0;
  for (int k = 0; k < static_cast<int>(StepStage::count); ++k) {
    ImGui::Text("%-15s %8.3f ms", stage_name(static_cast<StepStage>(k)), 1e3 * f.stage_seconds[k]);
    total += f.stage_seconds[k];
  }
  ImGui::Text("%-15s %8.3f ms", "step total", 1e3 * total);
  // The same frame by subsystem (a stage's time goes to the subsystem whose hook ran in it; the
  // integrator's own arithmetic and the drive belong to none).
  ImGui::Separator();
  for (int k = 0; k < kSubsystemCount; ++k) {
    if (f.subsystem_seconds[k] == 0) continue;  // absent from the scene
    ImGui::Text("%-15s %8.3f ms", subsystem_name(static_cast<SubsystemId>(k)),
                1e3 * f.subsystem_seconds[k]);
  }
  ImGui::Text("%d substeps, %d retries, %d rate evaluations", f.substeps, f.retries,
              f.evaluations);
  ImGui::Separator();
  ImGui::Text("kinetic %.4g J  elastic %.4g J  potential %.4g J", f.kinetic, f.elastic,
              f.potential);
  // The run-level guard (docs/architecture.md, "Stability guard"): how near the run is to it.
  ImGui::Text("energy beyond the inputs' work %.4g J of %.4g J allowed", f.energy_surplus,
              f.energy_limit);
  if (f.min_distance > 1e299) {
    ImGui::Text("no obstacles, %d contacts", f.contacts);
  } else {
    ImGui::Text("min obstacle distance %.4g m, %d contacts", f.min_distance, f.contacts);
  }
  std::vector<float> kinetic, elastic, distance, cost;
  for (const StatsSample& p : studio.plot) {
    kinetic.push_back(p.kinetic);
    elastic.push_back(p.elastic);
    distance.push_back(p.min_distance);
    float ms = 0;
    for (float x : p.step_ms) ms += x;
    cost.push_back(ms);
  }
  // Per-constraint violation, the worst first (ch. 7: |C| should decay as e^(-alpha t)).
  const VecX& violations = f.constraint_violations;
  if (violations.size() > 0 && studio.status.scene) {
    const std::vector<std::string> names = point_constraint_names(*studio.status.scene);
    std::vector<int> worst(static_cast<std::size_t>(violations.size()));
    for (std::size_t k = 0; k < worst.size(); ++k) worst[k] = static_cast<int>(k);
    std::stable_sort(worst.begin(), worst.end(),
                     [&](int a, int b) { return violations[a] > violations[b]; });
    ImGui::Text("constraints: %zu points, worst |C|:", worst.size());
    for (std::size_t k = 0; k < std::min<std::size_t>(5, worst.size()); ++k) {
      const int l = worst[k];
      const std::string name = l < static_cast<int>(names.size()) ? names[l] : std::to_string(l);
      ImGui::Text("  %-18s %.3g m", name.c_str(), violations[l]);
    }
  }
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 40);
  if (!kinetic.empty()) {
    ImGui::PlotLines("##k", kinetic.data(), static_cast<int>(kinetic.size()), 0, "kinetic [J]",
                     FLT_MAX, FLT_MAX, size);
    ImGui::PlotLines("##e", elastic.data(), static_cast<int>(elastic.size()), 0, "elastic [J]",
                     FLT_MAX, FLT_MAX, size);
    ImGui::PlotLines("##d", distance.data(), static_cast<int>(distance.size()), 0,
                     "min distance [m]", FLT_MAX, FLT_MAX, size);
    ImGui::PlotLines("##c", cost.data(), static_cast<int>(cost.size()), 0, "step [ms]", FLT_MAX,
                     FLT_MAX, size);
  }
}

}  // namespace

void draw_panels(Studio& studio, StudioActions& actions, float width, float height) {
  json scene =
      studio.status.scene ? json::parse(scene_to_json(*studio.status.scene)) : json::object();
  const float side = 340, bottom = 150;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(side, (height - bottom) * 0.45f), ImGuiCond_Always);
  ImGui::Begin("Outliner", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  outliner(studio, actions, scene);
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(0, (height - bottom) * 0.45f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(side, (height - bottom) * 0.55f), ImGuiCond_Always);
  ImGui::Begin("Inspector", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  inspector(studio, actions, scene);
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(0, height - bottom), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(side, bottom), ImGuiCond_Always);
  ImGui::Begin("Transport", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  transport(studio);
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(side, height - bottom), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width - side - 300, bottom), ImGuiCond_Always);
  ImGui::Begin("Timeline", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  timeline(studio, actions, scene);
  if (!studio.message.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", studio.message.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(width - 300, height - bottom - 260), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(300, bottom + 260), ImGuiCond_Always);
  ImGui::Begin("Stats", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  stats(studio);
  ImGui::End();
}

}  // namespace pbm
