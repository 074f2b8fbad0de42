// The checks every section's rows share: ranges, strings, list lengths and references to bodies
// and their nodes.
#include "scene/scene_fields.h"

#include <cmath>
#include <numbers>

namespace pbm {

namespace {

bool is_bounded(Real bound) {
  return std::isfinite(bound);
}

bool in_range(const Range& range, Real value) {
  const bool above = range.lo_open ? value > range.lo : value >= range.lo;
  const bool below = range.hi_open ? value < range.hi : value <= range.hi;
  return above && below;
}

// "1 body", "2 bodies".
std::string count_of(std::size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

int node_count(const BodyDef& body) {
  return 2 + body.tessellation.rings * body.tessellation.segments;
}

}  // namespace

std::string bound_text(Real bound) {
  if (bound == std::floor(bound) && std::abs(bound) < 1e15) {
    return std::to_string(static_cast<long long>(bound));
  }
  return format_real(bound);
}

std::string range_text(const Range& range) {
  const bool lo = is_bounded(range.lo), hi = is_bounded(range.hi);
  if (lo && hi) {
    return std::string(range.lo_open ? "(" : "[") + bound_text(range.lo) + ", " +
           bound_text(range.hi) + (range.hi_open ? ")" : "]");
  }
  if (lo) return (range.lo_open ? "> " : ">= ") + bound_text(range.lo);
  if (hi) return (range.hi_open ? "< " : "<= ") + bound_text(range.hi);
  return "";
}

std::string range_requirement(const Range& range) {
  const bool two_sided = is_bounded(range.lo) && is_bounded(range.hi);
  return (two_sided ? "must be in " : "must be ") + range_text(range);
}

Real check_range(const FieldFormat& format, const JsonNode& node, Real value) {
  if (!in_range(format.range, value)) fail(node, range_requirement(format.range));
  if (value > format.limit) fail(node, "must be <= " + bound_text(format.limit));
  return value;
}

std::string read_text(const FieldFormat& format, const JsonNode& node) {
  std::string text = read_string(node);
  if (format.non_empty && text.empty()) fail(node, "must not be empty");
  return text;
}

std::size_t require_list_length(const FieldFormat& format, const JsonNode& node) {
  const std::size_t n = require_array(node);
  if (static_cast<Real>(n) > format.limit) {
    fail(node, "must have at most " + bound_text(format.limit) + " entries (got " +
                   std::to_string(n) + ")");
  }
  if (static_cast<Real>(n) < format.range.lo) {
    fail(node, format.range.lo == 1
                   ? "must have at least one " + std::string(format.section)
                   : "must have at least " + bound_text(format.range.lo) + " entries");
  }
  return n;
}

int read_body_reference(const JsonNode& node, const std::vector<BodyDef>& bodies) {
  if (node.value->is_string()) {
    const std::string name = read_string(node);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == name) return static_cast<int>(i);
    }
    fail(node, "unknown body '" + name + "'");
  }
  if (!node.value->is_number()) fail(node, "must be a body index or a body name");
  const int index = read_int(node);
  if (index < 0 || static_cast<std::size_t>(index) >= bodies.size()) {
    fail(node, "body index " + std::to_string(index) + " is out of range (the scene has " +
                   count_of(bodies.size(), "body", "bodies") + ")");
  }
  return index;
}

int read_node_index(const JsonNode& node, const BodyDef& body) {
  const int index = read_int(node);
  if (index < 0 || index >= node_count(body)) {
    fail(node, "node " + std::to_string(index) + " is out of range: body '" + body.name + "' has " +
                   std::to_string(node_count(body)) + " nodes (2 + rings * segments)");
  }
  return index;
}

Vec2 read_material_point(const JsonNode& node) {
  const Vec2 uv = read_vec2(node);
  require_in_range(element(node, 0), uv[0], -std::numbers::pi / 2, std::numbers::pi / 2);
  require_in_range(element(node, 1), uv[1], -std::numbers::pi, std::numbers::pi);
  return uv;
}

std::vector<Keyframe> read_keyframes(const FieldFormat& format, const JsonNode& node) {
  const std::size_t n = require_array(node);
  if (n == 0) fail(node, "must have at least one key [time, value]");
  if (static_cast<Real>(n) > format.limit) {
    fail(node,
         "must have at most " + bound_text(format.limit) + " keys (got " + std::to_string(n) + ")");
  }
  std::vector<Keyframe> keys;
  keys.reserve(n);
  for (std::size_t j = 0; j < n; ++j) {
    const JsonNode key = element(node, j);
    if (!key.value->is_array() || key.value->size() != 2) {
      fail(key, "must be a [time, value] pair of numbers");
    }
    const Vec2 time_value = read_vec2(key);
    if (j > 0 && !(time_value[0] > keys.back().time)) {
      fail(key, "time " + format_real(time_value[0]) +
                    " must be greater than the previous key's time " +
                    format_real(keys.back().time));
    }
    keys.push_back(Keyframe{.time = time_value[0], .value = time_value[1]});
  }
  return keys;
}

OrderedJson keyframes_json(const std::vector<Keyframe>& keys) {
  OrderedJson out = OrderedJson::array();
  for (const Keyframe& key : keys) out.push_back({key.time, key.value});
  return out;
}

}  // namespace pbm
