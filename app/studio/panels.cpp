#include "panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "scene/scene_enum_names.h"
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

ImU32 integrator_color(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::euler:
      return IM_COL32(80, 140, 235, 255);
    case IntegratorKind::rk4:
      return IM_COL32(70, 190, 100, 255);
    case IntegratorKind::rk45:
      return IM_COL32(180, 100, 220, 255);
    case IntegratorKind::implicit:
      return IM_COL32(240, 160, 40, 255);
  }
  return IM_COL32_WHITE;
}

// Centre error against wall time on log-log axes (the plot of `pbm bench tradeoff`): points by
// integrator, the Pareto front, the scene's setting ringed; hovering shows a point's numbers and
// a click selects it.
void tradeoff_plot(Studio::Tradeoff& t) {
  const TradeoffReport& r = *t.report;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 240);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(25, 25, 30, 255));
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  auto xy = [](const TradeoffPoint& p) {
    return std::array<double, 2>{std::log10(std::max(p.wall_seconds, 1e-6)),
                                 std::log10(std::max(p.centre_error, 1e-12))};
  };
  for (const TradeoffPoint& p : r.points) {
    if (!p.ok) continue;
    const auto v = xy(p);
    for (int a = 0; a < 2; ++a) {
      lo[a] = std::min(lo[a], v[a]);
      hi[a] = std::max(hi[a], v[a]);
    }
  }
  if (lo[0] > hi[0]) {
    ImGui::TextUnformatted("no run succeeded");
    return;
  }
  for (int a = 0; a < 2; ++a) {
    lo[a] = std::floor(lo[a]);
    hi[a] = std::max(std::ceil(hi[a]), lo[a] + 1);
  }
  const float left = 44, bottom = 18, pad = 8;
  auto to_screen = [&](const std::array<double, 2>& v) {
    return ImVec2(
        origin.x + left +
            static_cast<float>((v[0] - lo[0]) / (hi[0] - lo[0])) * (size.x - left - pad),
        origin.y + pad +
            static_cast<float>((hi[1] - v[1]) / (hi[1] - lo[1])) * (size.y - bottom - pad));
  };
  char text[32];
  for (int e = static_cast<int>(lo[0]); e <= static_cast<int>(hi[0]); ++e) {
    const ImVec2 a = to_screen({static_cast<double>(e), lo[1]});
    const ImVec2 b = to_screen({static_cast<double>(e), hi[1]});
    draw->AddLine(a, b, IM_COL32(60, 60, 70, 255));
    std::snprintf(text, sizeof text, "1e%d s", e);
    draw->AddText(ImVec2(a.x - 12, a.y + 2), IM_COL32(170, 170, 170, 255), text);
  }
  for (int e = static_cast<int>(lo[1]); e <= static_cast<int>(hi[1]); ++e) {
    const ImVec2 a = to_screen({lo[0], static_cast<double>(e)});
    const ImVec2 b = to_screen({hi[0], static_cast<double>(e)});
    draw->AddLine(a, b, IM_COL32(60, 60, 70, 255));
    std::snprintf(text, sizeof text, "1e%d m", e);
    draw->AddText(ImVec2(origin.x + 2, a.y - 7), IM_COL32(170, 170, 170, 255), text);
  }
  std::vector<ImVec2> front;
  std::vector<std::pair<double, ImVec2>> sorted;
  for (const TradeoffPoint& p : r.points) {
    if (p.ok && p.pareto) sorted.emplace_back(p.wall_seconds, to_screen(xy(p)));
  }
  std::sort(sorted.begin(), sorted.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [w, s] : sorted) front.push_back(s);
  if (front.size() > 1) {
    draw->AddPolyline(front.data(), static_cast<int>(front.size()), IM_COL32(230, 230, 230, 255), 0,
                      1.5f);
  }
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  int hovered = -1;
  float nearest = 7;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const TradeoffPoint& p = r.points[i];
    if (!p.ok) continue;
    const ImVec2 s = to_screen(xy(p));
    draw->AddCircleFilled(s, 2.5f + 1.5f * static_cast<float>(std::sqrt(p.setting.resolution)),
                          integrator_color(p.setting.integrator));
    if (p.setting.current) draw->AddCircle(s, 8, IM_COL32(235, 60, 60, 255), 0, 2);
    if (static_cast<int>(i) == t.selected) draw->AddCircle(s, 8, IM_COL32_WHITE, 0, 1.5f);
    const float d = std::hypot(mouse.x - s.x, mouse.y - s.y);
    if (d < nearest) {
      nearest = d;
      hovered = static_cast<int>(i);
    }
  }
  ImGui::InvisibleButton("##tradeoff-plot", size);
  if (hovered >= 0 && ImGui::IsItemHovered()) {
    const TradeoffPoint& p = r.points[hovered];
    ImGui::SetTooltip(
        "%s\nwall %.4f s, %ld substeps\ncentre %.3g m, joints %.3g rad, q_s %.3g\nnodes rms %.3g "
        "m, energy %.3g, deepest contact %.3g m\nits physics' answer off the scene's: %.3g m, "
        "%.3g rad",
        p.setting.label().c_str(), p.wall_seconds, p.substeps, p.centre_error, p.joint_error,
        p.shape_error, p.node_rms, p.energy_error, p.depth, p.physics_centre, p.physics_joint);
    if (ImGui::IsItemClicked()) t.selected = hovered;
  }
  for (IntegratorKind k : {IntegratorKind::euler, IntegratorKind::rk4, IntegratorKind::implicit,
                           IntegratorKind::rk45}) {
    ImGui::ColorButton(name_of(kIntegratorKindNames, k), ImColor(integrator_color(k)),
                       ImGuiColorEditFlags_NoTooltip, ImVec2(10, 10));
    ImGui::SameLine();
    ImGui::Text("%s", name_of(kIntegratorKindNames, k));
    ImGui::SameLine();
  }
  ImGui::TextDisabled("(red ring: the scene's setting; size: resolution)");
}

// The speed-versus-accuracy panel (docs/architecture.md, "The measured trade").
void tradeoff_panel(Studio& studio, StudioActions& actions) {
  Studio::Tradeoff& t = studio.tradeoff;
  if (std::optional<TradeoffReport> report = t.job->take_report()) {
    t.report = std::move(report);
    t.selected = -1;
  }
  const TradeoffProgressView p = t.job->progress();
  ImGui::SetNextItemWidth(80);
  ImGui::InputFloat("s per run", &t.seconds, 0, 0, "%.2f");
  t.seconds = std::clamp(t.seconds, 0.1f, 60.0f);
  ImGui::SameLine();
  ImGui::Checkbox("dt", &t.dt);
  ImGui::SameLine();
  ImGui::Checkbox("integrator", &t.integrator);
  ImGui::SameLine();
  ImGui::Checkbox("tolerance", &t.tolerance);
  ImGui::SameLine();
  ImGui::Checkbox("resolution", &t.resolution);
  ImGui::SameLine();
  ImGui::Checkbox("contact", &t.contact);
  // The figures' physics knobs: each changes the answer, so each setting has its own reference.
  if (studio.status.scene && !studio.status.scene->figures.empty()) {
    ImGui::TextDisabled("figures:");
    ImGui::SameLine();
    ImGui::Checkbox("stiffness", &t.stiffness);
    ImGui::SameLine();
    ImGui::Checkbox("restitution", &t.restitution);
    ImGui::SameLine();
    ImGui::Checkbox("gains", &t.gains);
    ImGui::SameLine();
    ImGui::Checkbox("settling", &t.settling);
  }
  if (p.running) {
    const float fraction = p.total > 0 ? static_cast<float>(p.done) / p.total : 0.0f;
    ImGui::ProgressBar(fraction, ImVec2(-80, 0), p.label.c_str());
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) t.job->cancel();
  } else if (studio.status.scene) {
    if (ImGui::Button("Measure")) {
      std::vector<std::string> knobs;
      if (t.dt) knobs.push_back("dt");
      if (t.integrator) knobs.push_back("integrator");
      if (t.tolerance) knobs.push_back("tolerance");
      if (t.resolution) knobs.push_back("resolution");
      if (t.contact) knobs.push_back("contact");
      if (studio.status.scene && !studio.status.scene->figures.empty()) {
        if (t.stiffness) knobs.push_back("stiffness");
        if (t.restitution) knobs.push_back("restitution");
        if (t.gains) knobs.push_back("gains");
        if (t.settling) knobs.push_back("settling");
      }
      t.revision = studio.status.scene_revision;
      t.job->start(*studio.status.scene, knobs, t.seconds);
    }
    const std::string error = t.job->error();
    if (!error.empty()) {
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", error.c_str());
    }
  }
  for (const std::string& note : t.job->notes()) ImGui::TextWrapped("%s", note.c_str());
  if (!t.report) return;
  const TradeoffReport& r = *t.report;
  ImGui::Text("reference %s: %.2f s of wall time", r.reference.label().c_str(),
              r.reference_wall_seconds);
  if (studio.status.scene_revision != t.revision) {
    ImGui::TextDisabled("the scene changed since this was measured");
  }
  tradeoff_plot(t);
  // The front (and a selected point off it), each with the button that applies it.
  ImGui::Separator();
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const TradeoffPoint& q = r.points[i];
    if (!q.ok || (!q.pareto && static_cast<int>(i) != t.selected)) continue;
    ImGui::PushID(static_cast<int>(i));
    if (ImGui::SmallButton("Apply") && studio.status.scene) {
      const std::string error = actions.edit(
          "", scene_with_setting(*studio.status.scene, q.setting), "apply " + q.setting.label());
      if (!error.empty()) studio.message = error;
    }
    ImGui::SameLine();
    ImGui::Text("%s%s: %.4f s, centre %.3g m%s", q.setting.label().c_str(),
                q.setting.current ? " (scene's)" : "", q.wall_seconds, q.centre_error,
                q.pareto ? "" : " (off the front)");
    if (!q.setting.scenes_physics()) {
      ImGui::SameLine();
      ImGui::TextDisabled("(other physics: %.3g m off the scene's answer)", q.physics_centre);
    }
    ImGui::PopID();
  }
}

void stats(Studio& studio) {
  if (ImGui::Button("Speed vs accuracy...")) studio.tradeoff.show = true;
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
  ImGui::Text("%d substeps, %d retries, %d rate evaluations", f.substeps, f.retries, f.evaluations);
  // Each liquid (ch. 16) on its own CFL clock: what its substeps and solves cost this frame.
  for (const LiquidFrameStats& l : f.liquids) {
    ImGui::Text("liquid: %d substeps (cfl %.2f), %d solve iterations (max %d, %d unconverged)",
                l.step.substeps, l.step.cfl, l.step.iterations, l.step.max_iterations,
                l.step.unconverged);
    ImGui::Text("  volume %.5g m^3, |div u| %.2g 1/s, %d markers, fastest %.3g m/s", l.volume,
                l.step.divergence, l.markers, l.max_speed);
  }
  // Levels of detail (sim/level_of_detail.h): what the "auto" bodies saved this frame.
  if (f.levels.dormant_bodies > 0 || f.levels.switches > 0) {
    ImGui::Text("%d auto bodies without displacements, %d switched (a switch off: %.3g m, %.3g J)",
                f.levels.dormant_bodies, f.levels.switches, f.levels.position_jump,
                f.levels.energy_jump);
  }
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

// The control panel of fig. 15.11 (the crane's levers): dragging a controller's target sets it
// live during play (sim/runner.h, ControlSet), recorded into the controller's live keys so that
// playback and the saved file repeat it; the whole drag is one undo step.
void control_target(Studio& studio, int figure, int controller, const ControlSample& now) {
  const bool active = studio.control_figure == figure && studio.control_index == controller;
  double value = active ? studio.control_value : now.desired;
  const double speed = std::max(1e-3, 0.005 * std::max(std::abs(value), 1.0));
  ImGui::PushID(figure * 4096 + controller);
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
  const bool changed = ImGui::DragScalar("target", ImGuiDataType_Double, &value,
                                         static_cast<float>(speed), nullptr, nullptr, "%.4f");
  if (ImGui::IsItemActivated() && studio.status.scene) {
    studio.control_figure = figure;
    studio.control_index = controller;
    studio.control_scene_before = nlohmann::json::parse(scene_to_json(*studio.status.scene));
  }
  if (changed && studio.runner) {
    studio.control_value = value;
    studio.runner->post(ControlSet{figure, controller, value});
  }
  if (ImGui::IsItemDeactivated() && studio.control_figure == figure &&
      studio.control_index == controller) {
    if (ImGui::IsItemDeactivatedAfterEdit() && !studio.control_scene_before.is_null()) {
      studio.history.push({"", std::move(studio.control_scene_before), nullptr, "control"});
    }
    studio.control_scene_before = nullptr;
    studio.control_figure = studio.control_index = -1;
  }
  ImGui::SameLine();
  ImGui::Text("actual %.4f", now.actual);
  ImGui::PopID();
}

// A jog lever beside the target (fig. 15.11's crawler and winch levers): held at a speed, the
// target moves at that speed from wherever the controller's desired position is (ControlSet's
// from_desired); released, the lever springs back to 0 and the target stops where it is. The
// whole hold is one undo step.
void control_jog(Studio& studio, int figure, int controller, const ControlSample& now) {
  const bool active = studio.jog_figure == figure && studio.jog_index == controller;
  double rate = active ? studio.jog_rate : 0.0;
  const double speed = 0.002 * std::max(std::abs(now.desired), 1.0);
  ImGui::PushID(figure * 4096 + controller + 2048);
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
  const bool changed = ImGui::DragScalar("jog /s", ImGuiDataType_Double, &rate,
                                         static_cast<float>(speed), nullptr, nullptr, "%+.4f");
  if (figure == 0 && controller == 0) {
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    studio.first_jog_rect = {lo.x, lo.y, hi.x, hi.y};
  }
  if (ImGui::IsItemActivated() && studio.status.scene) {
    studio.jog_figure = figure;
    studio.jog_index = controller;
    studio.jog_rate = 0;
    studio.control_scene_before = nlohmann::json::parse(scene_to_json(*studio.status.scene));
  }
  if (changed && studio.runner) {
    studio.jog_rate = rate;
    studio.runner->post(ControlSet{figure, controller, 0, rate, true});
  }
  if (ImGui::IsItemDeactivated() && active) {
    if (studio.runner && studio.jog_rate != 0) {
      studio.runner->post(ControlSet{figure, controller, 0, 0, true});
    }
    if (ImGui::IsItemDeactivatedAfterEdit() && !studio.control_scene_before.is_null()) {
      studio.history.push({"", std::move(studio.control_scene_before), nullptr, "jog"});
    }
    studio.control_scene_before = nullptr;
    studio.jog_figure = studio.jog_index = -1;
    studio.jog_rate = 0;
  }
  ImGui::PopID();
}

// The keyboard lever (the crane's levers without a mouse): while Page Up or Page Down is held and
// no text field takes the keys, the chosen controller jogs at +-lever_speed from its desired
// position; on release it stops there. Posted only when the keys' state changes.
void keyboard_lever(Studio& studio, const Scene& scene) {
  const bool valid =
      studio.lever_figure >= 0 && studio.lever_figure < static_cast<int>(scene.figures.size()) &&
      studio.lever_index >= 0 &&
      studio.lever_index < static_cast<int>(scene.figures[studio.lever_figure].controllers.size());
  const bool free_keys = !ImGui::GetIO().WantTextInput;
  // ImGui 1.86's IsKeyDown takes the application's key index (io.KeyMap, viewport.cpp), not an
  // ImGuiKey: passed ImGuiKey_PageUp it read the Down arrow's slot and Page Down's as Page Up.
  const auto down = [](ImGuiKey key) { return ImGui::IsKeyDown(ImGui::GetKeyIndex(key)) ? 1 : 0; };
  const int direction = valid && free_keys ? down(ImGuiKey_PageUp) - down(ImGuiKey_PageDown) : 0;
  if (direction == studio.lever_direction) return;
  if (studio.lever_direction == 0 && studio.status.scene) {
    studio.lever_scene_before = nlohmann::json::parse(scene_to_json(*studio.status.scene));
  }
  if (studio.runner && valid) {
    studio.runner->post(ControlSet{studio.lever_figure, studio.lever_index, 0,
                                   direction * studio.lever_speed, true});
  }
  if (direction == 0 && !studio.lever_scene_before.is_null()) {
    studio.history.push({"", std::move(studio.lever_scene_before), nullptr, "lever"});
    studio.lever_scene_before = nullptr;
  }
  studio.lever_direction = direction;
}

// A controller's DOF as the panel names it: its index on a single-axis joint, or on a spherical
// joint the component of the rotation vector it drives (control/ball_coordinates.h).
std::string dof_label(const FigureDef& figure, const ControllerDef& c) {
  for (const SegmentDef& s : figure.segments) {
    if (s.name == c.joint && s.joint.kind == JointKind::spherical && c.dof >= 0 && c.dof < 3) {
      return std::string("r_") + "xyz"[c.dof];
    }
  }
  return std::to_string(c.dof);
}

// The controlled DOFs' trajectories over the last seconds (figs. 15.7, 15.8): desired (white),
// the MRAC reference model (yellow; the desired for PD servos) and actual (cyan), with the
// actuator's output and whether it is at its limit; each with its target, jog lever and the
// choice of the keyboard lever.
void controllers_panel(Studio& studio) {
  ImGui::TextDisabled(
      "drag a target to set it, or hold its jog lever at a speed (recorded as live keys);");
  ImGui::TextDisabled("Page Up / Page Down jog the controller marked 'keys' at the speed below");
  const Scene& scene = *studio.status.scene;
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.4f);
  ImGui::DragScalar("keyboard lever speed /s", ImGuiDataType_Double, &studio.lever_speed, 0.005f,
                    nullptr, nullptr, "%.3f");
  keyboard_lever(studio, scene);
  const FrameStats& f = studio.status.stats;
  int k = 0;
  for (std::size_t fi = 0; fi < scene.figures.size(); ++fi) {
    for (std::size_t ci = 0; ci < scene.figures[fi].controllers.size(); ++ci, ++k) {
      const ControllerDef& c = scene.figures[fi].controllers[ci];
      const bool sampled = fi < f.figures.size() && ci < f.figures[fi].controllers.size();
      const ControlSample now = sampled ? f.figures[fi].controllers[ci] : ControlSample{};
      ImGui::Text("%s / %s [%s] (%s): u %.4g%s", scene.figures[fi].name.c_str(), c.joint.c_str(),
                  dof_label(scene.figures[fi], c).c_str(), name_of(kControllerKindNames, c.kind),
                  now.output, now.saturated ? ", at its limit" : "");
      control_target(studio, static_cast<int>(fi), static_cast<int>(ci), now);
      control_jog(studio, static_cast<int>(fi), static_cast<int>(ci), now);
      ImGui::SameLine();
      ImGui::PushID(k);
      if (ImGui::RadioButton("keys", studio.lever_figure == static_cast<int>(fi) &&
                                         studio.lever_index == static_cast<int>(ci)) &&
          studio.lever_direction == 0) {
        studio.lever_figure = static_cast<int>(fi);
        studio.lever_index = static_cast<int>(ci);
      }
      ImGui::PopID();
      const ImVec2 origin = ImGui::GetCursorScreenPos();
      const ImVec2 size(ImGui::GetContentRegionAvail().x, 70);
      ImDrawList* draw = ImGui::GetWindowDrawList();
      draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                          IM_COL32(25, 25, 30, 255));
      float lo = 1e30f, hi = -1e30f;
      for (const StatsSample& p : studio.plot) {
        if (k >= static_cast<int>(p.control.size())) continue;
        for (float x : p.control[k]) {
          lo = std::min(lo, x);
          hi = std::max(hi, x);
        }
      }
      ImGui::Dummy(size);
      if (lo > hi || studio.plot.size() < 2) continue;
      if (hi - lo < 1e-6f) {
        lo -= 0.5f;
        hi += 0.5f;
      }
      const float n = static_cast<float>(studio.plot.size() - 1);
      const ImU32 colors[3] = {IM_COL32(235, 235, 235, 255), IM_COL32(235, 200, 60, 255),
                               IM_COL32(80, 200, 235, 255)};
      std::vector<ImVec2> line;
      for (int series = 0; series < 3; ++series) {
        line.clear();
        int i = 0;
        for (const StatsSample& p : studio.plot) {
          if (k < static_cast<int>(p.control.size())) {
            const float y = (p.control[k][series] - lo) / (hi - lo);
            line.emplace_back(origin.x + size.x * static_cast<float>(i) / n,
                              origin.y + 4 + (size.y - 8) * (1 - y));
          }
          ++i;
        }
        if (line.size() > 1) {
          draw->AddPolyline(line.data(), static_cast<int>(line.size()), colors[series], 0, 1.5f);
        }
      }
      char range[64];
      std::snprintf(range, sizeof range, "%.3g .. %.3g", lo, hi);
      draw->AddText(ImVec2(origin.x + 4, origin.y + 2), IM_COL32(170, 170, 170, 255), range);
    }
  }
  ImGui::TextDisabled("white: desired; yellow: reference model; cyan: actual");
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
  bool controlled = false;
  if (studio.status.scene) {
    for (const FigureDef& figure : studio.status.scene->figures) {
      controlled = controlled || !figure.controllers.empty();
    }
  }
  if (controlled && studio.show_controllers) {
    ImGui::SetNextWindowPos(ImVec2(width - 730, 20), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(420, 320), ImGuiCond_FirstUseEver);
    ImGui::Begin("Controllers", &studio.show_controllers);
    controllers_panel(studio);
    ImGui::End();
  }
  if (studio.tradeoff.show) {
    ImGui::SetNextWindowPos(ImVec2(side + 20, 20), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(600, 480), ImGuiCond_FirstUseEver);
    ImGui::Begin("Speed vs accuracy", &studio.tradeoff.show);
    tradeoff_panel(studio, actions);
    ImGui::End();
  }
}

}  // namespace pbm
