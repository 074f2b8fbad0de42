// Matching and checking track targets against the table in scene/track_targets.h.
#include "scene/track_targets.h"

#include <cstdint>

#include "deform/shape_parameters.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

// What a pattern's placeholders matched.
struct TargetMatch {
  int i = 0, k = 0;
  std::string_view name;
};

// Up to 9 decimal digits (no overflow of an int), at least one.
bool match_index(std::string_view& text, int& index) {
  std::size_t digits = 0;
  std::int64_t value = 0;
  while (digits < text.size() && digits < 9 && text[digits] >= '0' && text[digits] <= '9') {
    value = value * 10 + (text[digits] - '0');
    ++digits;
  }
  if (digits == 0 || (digits < text.size() && text[digits] >= '0' && text[digits] <= '9')) {
    return false;
  }
  index = static_cast<int>(value);
  text.remove_prefix(digits);
  return true;
}

// Whether `text` is `pattern` with its placeholders filled in; "{name}" takes the rest of the
// text (a parameter name has no '/', '.', '[' or ']').
bool match(std::string_view pattern, std::string_view text, TargetMatch& m) {
  if (pattern.empty()) return false;
  while (!pattern.empty()) {
    if (pattern.starts_with("{i}") || pattern.starts_with("{k}")) {
      if (!match_index(text, pattern[1] == 'i' ? m.i : m.k)) return false;
      pattern.remove_prefix(3);
    } else if (pattern == "{name}") {
      if (text.empty() || text.find_first_of("/.[]") != std::string_view::npos) return false;
      m.name = text;
      return true;
    } else {
      if (text.empty() || text.front() != pattern.front()) return false;
      pattern.remove_prefix(1);
      text.remove_prefix(1);
    }
  }
  return text.empty();
}

// `pattern` with its placeholders replaced by what they matched.
std::string fill(std::string_view pattern, const TargetMatch& m) {
  std::string out;
  while (!pattern.empty()) {
    if (pattern.starts_with("{i}") || pattern.starts_with("{k}")) {
      out += std::to_string(pattern[1] == 'i' ? m.i : m.k);
      pattern.remove_prefix(3);
    } else if (pattern == "{name}") {
      out += m.name;
      break;
    } else {
      out += pattern.front();
      pattern.remove_prefix(1);
    }
  }
  return out;
}

// "/obstacles/{i}/center/{k}" of "obstacles[{i}].center[{k}]": the key a text names in the file,
// as a JSON pointer.
std::string pointer_of(std::string_view text) {
  std::string pointer = "/";
  for (const char c : text) {
    if (c == '[' || c == '.') {
      pointer += '/';
    } else if (c != ']') {
      pointer += c;
    }
  }
  return pointer;
}

// "bodies[i].q_s0.<name>": a pattern as the messages show it.
std::string shown(std::string_view pattern) {
  std::string out;
  for (std::size_t p = 0; p < pattern.size(); ++p) {
    if (pattern.substr(p).starts_with("{name}")) {
      out += "<name>";
      p += 5;
    } else if (pattern[p] != '{' && pattern[p] != '}') {
      out += pattern[p];
    }
  }
  return out;
}

// "a, b or c" of the shown forms (index form, then by name) of the rows owned by `owner`, or
// of every row when `owner` is null.
std::string expected_forms(const std::string_view* owner) {
  std::vector<std::string> forms;
  for (const TrackTargetFormat& row : kTrackTargets) {
    if (owner && row.owner != *owner) continue;
    forms.push_back(shown(row.text));
    if (!row.named_text.empty()) forms.push_back(shown(row.named_text));
  }
  std::string list;
  for (std::size_t f = 0; f < forms.size(); ++f) {
    list += (f == 0 ? "" : f + 1 == forms.size() ? " or " : ", ") + forms[f];
  }
  return list;
}

// The items of a list owner in `scene`, with the noun and names messages use.
struct OwnerList {
  std::string_view noun;
  std::size_t count = 0;
};
std::optional<OwnerList> owner_list(const Scene& scene, std::string_view owner) {
  if (owner == "bodies") return OwnerList{"body", scene.bodies.size()};
  if (owner == "springs") return OwnerList{"spring", scene.springs.size()};
  if (owner == "obstacles") return OwnerList{"obstacle", scene.obstacles.size()};
  if (owner == "liquids") return OwnerList{"liquid", scene.liquids.size()};
  return std::nullopt;
}
std::string item_name(const Scene& scene, std::string_view owner, int i) {
  const auto index = static_cast<std::size_t>(i);
  if (owner == "bodies") return scene.bodies[index].name;
  if (owner == "springs") return scene.springs[index].name;
  if (owner == "liquids") return scene.liquids[index].name;
  return scene.obstacles[index].name;
}

std::string out_of_range(std::string_view what, int index, std::size_t count) {
  return std::string(what) + " index " + std::to_string(index) + " is out of range (" +
         std::to_string(count) + " available)";
}

// The key between "]." and the next "[" of a kind text ("center" of "obstacles[{i}].center[{k}]").
std::string_view key_of(std::string_view kind_text) {
  const std::size_t begin = kind_text.find("].") + 2;
  return kind_text.substr(begin, kind_text.find('[', begin) - begin);
}

// The index form of `row` for the matched text, or "" with `problem` set.
std::string resolve_row(const Scene& scene, const TrackTargetFormat& row, TargetMatch m,
                        std::string& problem) {
  std::size_t components = static_cast<std::size_t>(row.components);
  if (row.components == kShapeParameterComponents) {
    const BodyDef& body = scene.bodies[static_cast<std::size_t>(m.i)];
    components = static_cast<std::size_t>(shape_parameter_count(body.shape));
    if (!m.name.empty()) {
      m.k = -1;
      std::string names;
      for (int n = 0; n < shape_parameter_count(body.shape); ++n) {
        if (shape_parameter_name(body.shape, n) == m.name) m.k = n;
        names += (n ? ", " : "") + shape_parameter_name(body.shape, n);
      }
      if (m.k < 0) {
        problem = "unknown shape parameter '" + std::string(m.name) + "' for body '" + body.name +
                  "' (expected one of " + names + ")";
        return "";
      }
    }
  }
  if (row.components != 0 && static_cast<std::size_t>(m.k) >= components) {
    problem = out_of_range(row.component, m.k, components);
    return "";
  }
  return fill(row.text, TargetMatch{m.i, m.k, {}});
}

}  // namespace

std::optional<TrackTargetRef> parse_track_target(std::string_view text) {
  for (const TrackTargetFormat& row : kTrackTargets) {
    TargetMatch m;
    if (match(row.text, text, m)) return TrackTargetRef{row.target, m.i, m.k};
  }
  return std::nullopt;
}

std::string format_track_target(TrackTarget target, int i, int k) {
  for (const TrackTargetFormat& row : kTrackTargets) {
    if (row.target == target) return fill(row.text, TargetMatch{i, k, {}});
  }
  return "";
}

std::string resolve_track_target(const Scene& scene, std::string_view text, std::string& problem) {
  // The owner first: an item that does not exist, or a camera the scene lacks, is the problem
  // whatever the rest says.
  std::string_view owner;
  int i = 0;
  for (const TrackTargetFormat& row : kTrackTargets) {
    const std::optional<OwnerList> list = owner_list(scene, row.owner);
    std::string_view rest = text;
    if (list && rest.starts_with(row.owner) && rest.substr(row.owner.size()).starts_with("[")) {
      rest.remove_prefix(row.owner.size() + 1);
      if (!match_index(rest, i) || !rest.starts_with("]")) continue;
      if (static_cast<std::size_t>(i) >= list->count) {
        problem = out_of_range(list->noun, i, list->count);
        return "";
      }
      owner = row.owner;
      break;
    }
    if (row.owner == "camera" && text.starts_with("camera.")) {
      if (!scene.camera) {
        problem = "camera tracks need a 'camera' in the scene";
        return "";
      }
      owner = row.owner;
      break;
    }
  }
  for (const TrackTargetFormat& row : kTrackTargets) {
    if (row.owner != owner) continue;
    TargetMatch m;
    if (match(row.text, text, m) || match(row.named_text, text, m)) {
      return resolve_row(scene, row, m, problem);
    }
    for (const std::string_view kind_text : row.kind_texts) {
      if (match(kind_text, text, m) &&
          obstacle_has_key(scene.obstacles[static_cast<std::size_t>(m.i)].kind,
                           key_of(kind_text))) {
        return resolve_row(scene, row, m, problem);
      }
    }
  }
  if (const std::optional<OwnerList> list = owner_list(scene, owner)) {
    problem = "unknown " + std::string(list->noun) + " track target '" + std::string(text) +
              "' for " + std::string(list->noun) + " '" + item_name(scene, owner, i) +
              "' (expected " + expected_forms(&owner) + ")";
  } else {
    problem = "unknown track target '" + std::string(text) + "' (expected " +
              expected_forms(nullptr) + ")";
  }
  return "";
}

std::string track_target_of_key(const Scene& scene, std::string_view pointer) {
  for (const TrackTargetFormat& row : kTrackTargets) {
    TargetMatch m;
    std::string candidate;
    if (match(row.pointer, pointer, m)) {
      candidate = fill(m.name.empty() ? row.text : row.named_text, m);
    }
    for (const std::string_view kind_text : row.kind_texts) {
      if (candidate.empty() && !kind_text.empty() && match(pointer_of(kind_text), pointer, m)) {
        candidate = fill(kind_text, m);
      }
    }
    if (candidate.empty()) continue;
    std::string problem;
    return resolve_track_target(scene, candidate, problem);
  }
  return "";
}

std::string track_target_pattern() {
  std::string alternatives;
  for (const TrackTargetFormat& row : kTrackTargets) {
    for (const std::string_view form :
         {row.text, row.named_text, row.kind_texts[0], row.kind_texts[1]}) {
      if (form.empty()) continue;
      if (!alternatives.empty()) alternatives += "|";
      for (std::size_t p = 0; p < form.size(); ++p) {
        const std::string_view rest = form.substr(p);
        if (rest.starts_with("{i}") || rest.starts_with("{k}")) {
          alternatives += "[0-9]+";
          p += 2;
        } else if (rest.starts_with("{name}")) {
          alternatives += "[^\\[\\]]+";
          p += 5;
        } else {
          if (form[p] == '[' || form[p] == ']' || form[p] == '.') alternatives += '\\';
          alternatives += form[p];
        }
      }
    }
  }
  return "^(" + alternatives + ")$";
}

}  // namespace pbm
