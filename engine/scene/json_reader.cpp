#include "scene/json_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <vector>

namespace pbm {

namespace {

// One open object or array while parsing, for the duplicate-key check.
struct OpenContainer {
  std::string path;
  bool is_array = false;
  std::size_t next_index = 0;  // arrays: index of the next element
  std::string key;             // objects: the key whose value comes next
  std::set<std::string> keys;  // objects: keys seen so far
};

// Path of the value about to be parsed inside `parent` (advancing an array's element count).
std::string path_of_next_value(OpenContainer& parent) {
  if (parent.is_array) return element_path(parent.path, parent.next_index++);
  return child_path(parent.path, parent.key);
}

// nlohmann prefixes what() with "[json.exception.parse_error.101] "; the file name and position
// already say where, so keep only the human part.
std::string strip_exception_id(const std::string& what) {
  if (!what.empty() && what.front() == '[') {
    const std::size_t close = what.find("] ");
    if (close != std::string::npos) return what.substr(close + 2);
  }
  return what;
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
  std::vector<OpenContainer> open;
  const nlohmann::json::parser_callback_t track_keys =
      [&open, &file](int /*depth*/, nlohmann::json::parse_event_t event,
                     nlohmann::json& parsed) -> bool {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start: {
        OpenContainer container;
        container.path = open.empty() ? std::string() : path_of_next_value(open.back());
        container.is_array = event == Event::array_start;
        open.push_back(std::move(container));
        break;
      }
      case Event::object_end:
      case Event::array_end:
        if (!open.empty()) open.pop_back();
        break;
      case Event::key: {
        OpenContainer& object = open.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second) {
          throw Error(file, child_path(object.path, object.key),
                      "duplicate key '" + object.key + "'");
        }
        break;
      }
      case Event::value:
        if (!open.empty() && open.back().is_array) ++open.back().next_index;
        break;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, track_keys);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(
        file, "",
        "invalid JSON: " + strip_exception_id(e.what()) + " (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {
    // e.g. out_of_range 406: a number literal too large for a double.
    throw Error(file, "", "invalid JSON: " + strip_exception_id(e.what()));
  }
}

JsonNode root_node(const nlohmann::json& document, const std::string& file) {
  return JsonNode{&document, std::string(), &file};
}

void fail(const JsonNode& node, const std::string& message) {
  throw Error(node.file ? *node.file : std::string(), node.path, message);
}

std::string child_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element_path(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

void require_object(const JsonNode& node, std::initializer_list<std::string_view> allowed) {
  if (!node.value->is_object()) fail(node, "must be an object");
  for (const auto& [key, value] : node.value->items()) {
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      fail(JsonNode{&value, child_path(node.path, key), node.file}, "unknown key '" + key + "'");
    }
  }
}

std::size_t require_array(const JsonNode& node) {
  if (!node.value->is_array()) fail(node, "must be an array");
  return node.value->size();
}

std::optional<JsonNode> find_child(const JsonNode& object, std::string_view key) {
  const auto it = object.value->find(key);
  if (it == object.value->end()) return std::nullopt;
  return JsonNode{&*it, child_path(object.path, key), object.file};
}

JsonNode require_child(const JsonNode& object, std::string_view key) {
  std::optional<JsonNode> child = find_child(object, key);
  if (!child)
    fail(JsonNode{object.value, child_path(object.path, key), object.file}, "is required");
  return *child;
}

JsonNode element(const JsonNode& array, std::size_t index) {
  return JsonNode{&(*array.value)[index], element_path(array.path, index), array.file};
}

Real read_real(const JsonNode& node) {
  if (!node.value->is_number()) fail(node, "must be a number");
  const Real value = node.value->get<Real>();
  if (!std::isfinite(value)) fail(node, "must be finite");
  return value;
}

int read_int(const JsonNode& node) {
  const nlohmann::json& v = *node.value;
  if (v.is_number_integer()) {
    // Covers both signed and unsigned storage; compare in the widest type before narrowing.
    if (v.is_number_unsigned()) {
      const auto u = v.get<std::uint64_t>();
      if (u <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
        return static_cast<int>(u);
      }
    } else {
      const auto s = v.get<std::int64_t>();
      if (s >= std::numeric_limits<int>::min() && s <= std::numeric_limits<int>::max()) {
        return static_cast<int>(s);
      }
    }
    fail(node, "is out of range for an integer");
  }
  // 16.0 is an integer written with a decimal point; 16.5 is not.
  if (v.is_number_float()) {
    const Real r = v.get<Real>();
    if (std::isfinite(r) && r == std::floor(r) && r >= std::numeric_limits<int>::min() &&
        r <= std::numeric_limits<int>::max()) {
      return static_cast<int>(r);
    }
  }
  fail(node, "must be an integer");
}

bool read_bool(const JsonNode& node) {
  if (!node.value->is_boolean()) fail(node, "must be true or false");
  return node.value->get<bool>();
}

std::string read_string(const JsonNode& node) {
  if (!node.value->is_string()) fail(node, "must be a string");
  return node.value->get<std::string>();
}

VecX read_reals(const JsonNode& node, int n) {
  const std::string expected = "must be an array of " + std::to_string(n) + " numbers";
  if (!node.value->is_array()) fail(node, expected);
  if (node.value->size() != static_cast<std::size_t>(n)) {
    fail(node, expected + " (got " + std::to_string(node.value->size()) + ")");
  }
  VecX values(n);
  for (int i = 0; i < n; ++i) values[i] = read_real(element(node, static_cast<std::size_t>(i)));
  return values;
}

Vec2 read_vec2(const JsonNode& node) {
  return read_reals(node, 2);
}
Vec3 read_vec3(const JsonNode& node) {
  return read_reals(node, 3);
}
Vec4 read_vec4(const JsonNode& node) {
  return read_reals(node, 4);
}

Real require_positive(const JsonNode& node, Real value) {
  if (!(value > 0)) fail(node, "must be > 0");
  return value;
}

Real require_non_negative(const JsonNode& node, Real value) {
  if (!(value >= 0)) fail(node, "must be >= 0");
  return value;
}

Real require_in_range(const JsonNode& node, Real value, Real lo, Real hi) {
  if (!(value >= lo && value <= hi)) {
    fail(node, "must be in [" + format_real(lo) + ", " + format_real(hi) + "]");
  }
  return value;
}

std::string format_real(Real value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace pbm
