// Reading and validating scene files (format: scenes/README.md). Each parse_* function reads one
// JSON object into its Def, checking keys, types and ranges, and throws pbm::Error at the first
// bad value; parse_scene only returns a Scene once every part has been read.
#include "scene/scene_json.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string_view>

#include "deform/reference_shape.h"
#include "scene/json_reader.h"
#include "scene/scene_enum_names.h"

namespace pbm {

namespace {

// Quaternions and normals are rescaled only when visibly off unit length, so that a vector
// written by scene_to_json (already unit to within rounding) reads back bit-identical.
constexpr Real kUnitLengthSlack = 1e-14;
// Below this length a quaternion or normal carries no direction.
constexpr Real kMinimumDirectionLength = 1e-12;
constexpr std::int64_t kMaxNodesPerBody = 1000000;
constexpr int kMaxRetriesLimit = 20;

// "1 body", "2 bodies".
std::string count_of(std::size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

// A unit vector from `value` read at `node`; zero length is an error.
template <typename Vector>
Vector normalized_direction(const JsonNode& node, const Vector& value, const std::string& what) {
  const Real length = value.norm();
  if (!(length > kMinimumDirectionLength)) fail(node, "must be a nonzero " + what);
  if (std::abs(length - 1) <= kUnitLengthSlack) return value;
  return value / length;
}

// ---- shape parameters q_s (2.8), (2.11), (2.27) ---------------------------------------------

std::string shape_parameter_list(ShapeKind kind) {
  std::string names;
  for (int i = 0; i < shape_parameter_count(kind); ++i) {
    names += (i ? ", " : "") + shape_parameter_name(kind, i);
  }
  return names;
}

// Index of the parameter called `name`, or -1.
int find_shape_parameter(ShapeKind kind, std::string_view name) {
  for (int i = 0; i < shape_parameter_count(kind); ++i) {
    if (shape_parameter_name(kind, i) == name) return i;
  }
  return -1;
}

enum class ShapeVectorRole { shape, stiffness };

void check_shape_entry(const JsonNode& node, ShapeKind kind, int index, Real value,
                       ShapeVectorRole role) {
  if (role == ShapeVectorRole::stiffness) {
    require_non_negative(node, value);
    return;
  }
  const std::string problem = check_shape_parameter(kind, index, value);
  if (!problem.empty()) fail(node, problem);
}

// A vector over the shape's parameters, written either as an array of all n_s numbers or as an
// object {name: value} whose missing names keep `fallback`.
VecX read_shape_vector(const JsonNode& node, ShapeKind kind, const VecX& fallback,
                       ShapeVectorRole role) {
  const int n_s = shape_parameter_count(kind);
  const std::string kind_name = enum_name(kind, kShapeKindNames);
  VecX values = fallback;
  if (node.value->is_array()) {
    if (node.value->size() != static_cast<std::size_t>(n_s)) {
      fail(node, "must have " + std::to_string(n_s) + " entries for a " + kind_name + " shape (" +
                     shape_parameter_list(kind) + "), got " + std::to_string(node.value->size()));
    }
    for (int i = 0; i < n_s; ++i) {
      const JsonNode entry = element(node, static_cast<std::size_t>(i));
      values[i] = read_real(entry);
      check_shape_entry(entry, kind, i, values[i], role);
    }
    return values;
  }
  if (!node.value->is_object()) {
    fail(node, "must be an array of " + std::to_string(n_s) +
                   " numbers or an object of named parameters");
  }
  for (const auto& item : node.value->items()) {
    const JsonNode entry{&item.value(), child_path(node.path, item.key()), node.file};
    const int index = find_shape_parameter(kind, item.key());
    if (index < 0) {
      fail(entry, "unknown shape parameter '" + item.key() + "' for a " + kind_name +
                      " shape (expected one of " + shape_parameter_list(kind) + ")");
    }
    values[index] = read_real(entry);
    check_shape_entry(entry, kind, index, values[index], role);
  }
  return values;
}

void parse_shape(const JsonNode& body_node, BodyDef& body) {
  const std::optional<JsonNode> node = find_child(body_node, "shape");
  std::optional<JsonNode> q_s, rest, stiffness;
  if (node) {
    require_object(*node, {"kind", "q_s", "rest", "stiffness"});
    if (auto kind = find_child(*node, "kind")) body.shape = read_enum(*kind, kShapeKindNames);
    q_s = find_child(*node, "q_s");
    rest = find_child(*node, "rest");
    stiffness = find_child(*node, "stiffness");
  }
  const VecX defaults = default_shape_parameters(body.shape);
  body.q_s = q_s ? read_shape_vector(*q_s, body.shape, defaults, ShapeVectorRole::shape) : defaults;
  // Rest shape q_s0 of the global stiffness (3.31)-(3.32): by default the initial shape.
  body.q_s0 =
      rest ? read_shape_vector(*rest, body.shape, body.q_s, ShapeVectorRole::shape) : body.q_s;
  const VecX no_stiffness = VecX::Zero(defaults.size());
  body.k_s = stiffness ? read_shape_vector(*stiffness, body.shape, no_stiffness,
                                           ShapeVectorRole::stiffness)
                       : no_stiffness;
}

// ---- bodies ------------------------------------------------------------------------------------

TessellationDef parse_tessellation(const JsonNode& node) {
  TessellationDef tessellation;
  require_object(node, {"kind", "rings", "segments"});
  if (auto kind = find_child(node, "kind"))
    tessellation.kind = read_enum(*kind, kTessellationKindNames);
  if (auto rings = find_child(node, "rings")) {
    tessellation.rings = read_int(*rings);
    if (tessellation.rings < 2) fail(*rings, "must be >= 2");
  }
  if (auto segments = find_child(node, "segments")) {
    tessellation.segments = read_int(*segments);
    if (tessellation.segments < 3) fail(*segments, "must be >= 3");
  }
  const std::int64_t product =
      static_cast<std::int64_t>(tessellation.rings) * tessellation.segments;
  if (product > kMaxNodesPerBody) {
    fail(node, "rings * segments must be <= " + std::to_string(kMaxNodesPerBody) + " (got " +
                   std::to_string(product) + ")");
  }
  return tessellation;
}

MaterialDef parse_material(const JsonNode& body_node) {
  MaterialDef material;
  const JsonNode node = require_child(body_node, "material");
  require_object(node, {"w0", "w1", "nodal_mass", "mass", "damping", "color", "roughness"});
  if (auto w0 = find_child(node, "w0")) material.w0 = require_non_negative(*w0, read_real(*w0));
  if (auto w1 = find_child(node, "w1")) material.w1 = require_non_negative(*w1, read_real(*w1));
  const std::optional<JsonNode> nodal_mass = find_child(node, "nodal_mass");
  const std::optional<JsonNode> mass = find_child(node, "mass");
  if (nodal_mass.has_value() == mass.has_value()) {
    fail(node, "give exactly one of 'mass' (total, kg) and 'nodal_mass' (per node, kg)");
  }
  if (nodal_mass) material.nodal_mass = require_positive(*nodal_mass, read_real(*nodal_mass));
  if (mass) material.mass = require_positive(*mass, read_real(*mass));
  if (auto damping = find_child(node, "damping")) {
    material.damping = require_non_negative(*damping, read_real(*damping));
  }
  if (auto color = find_child(node, "color")) {
    material.color = read_vec3(*color);
    for (int k = 0; k < 3; ++k) require_in_range(element(*color, k), material.color[k], 0, 1);
  }
  if (auto roughness = find_child(node, "roughness")) {
    material.roughness = read_real(*roughness);
    require_in_range(*roughness, material.roughness, 0, 1);
  }
  return material;
}

BodyDef parse_body(const JsonNode& node, std::size_t index) {
  require_object(node, {"name", "level", "order", "shape", "position", "orientation", "velocity",
                        "angular_velocity", "tessellation", "material"});
  BodyDef body;
  body.name = "body" + std::to_string(index);
  if (auto name = find_child(node, "name")) {
    body.name = read_string(*name);
    if (body.name.empty()) fail(*name, "must not be empty");
  }
  if (auto level = find_child(node, "level")) body.level = read_enum(*level, kDeformLevelNames);
  if (auto order = find_child(node, "order")) body.order = read_enum(*order, kDynamicsOrderNames);
  parse_shape(node, body);
  if (auto position = find_child(node, "position")) body.position = read_vec3(*position);
  if (auto orientation = find_child(node, "orientation")) {
    body.orientation = normalized_direction(*orientation, read_vec4(*orientation), "quaternion");
  }
  if (auto velocity = find_child(node, "velocity")) body.velocity = read_vec3(*velocity);
  if (auto omega = find_child(node, "angular_velocity")) body.angular_velocity = read_vec3(*omega);
  if (auto tessellation = find_child(node, "tessellation")) {
    body.tessellation = parse_tessellation(*tessellation);
  }
  body.material = parse_material(node);
  return body;
}

int node_count(const BodyDef& body) {
  return 2 + body.tessellation.rings * body.tessellation.segments;
}

// A body given by index (0) or by name ("jello").
int parse_body_reference(const JsonNode& node, const std::vector<BodyDef>& bodies) {
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

// ---- obstacles, force fields, springs ----------------------------------------------------------

ObstacleDef parse_obstacle(const JsonNode& node, std::size_t index) {
  require_object(node, {"name", "kind", "point", "normal", "size", "center", "half_extents",
                        "orientation", "file", "position", "scale", "elasticity", "friction"});
  ObstacleDef obstacle;
  obstacle.name = "obstacle" + std::to_string(index);
  if (auto name = find_child(node, "name")) obstacle.name = read_string(*name);
  if (auto kind = find_child(node, "kind")) obstacle.kind = read_enum(*kind, kObstacleKindNames);
  // Keys of another kind would be silently ignored, which hides typos like a plane's "center".
  const std::string kind_name(enum_name(obstacle.kind, kObstacleKindNames));
  const std::vector<std::string_view> own =
      obstacle.kind == ObstacleKind::plane
          ? std::vector<std::string_view>{"point", "normal", "size"}
      : obstacle.kind == ObstacleKind::box
          ? std::vector<std::string_view>{"center", "half_extents", "orientation"}
          : std::vector<std::string_view>{"file", "position", "orientation", "scale"};
  for (const std::string_view key : {"point", "normal", "size", "center", "half_extents",
                                     "orientation", "file", "position", "scale"}) {
    if (std::find(own.begin(), own.end(), key) != own.end()) continue;
    if (auto misplaced = find_child(node, key)) {
      fail(*misplaced,
           "key '" + std::string(key) + "' is not valid for a " + kind_name + " obstacle");
    }
  }
  if (obstacle.kind == ObstacleKind::plane) {
    if (auto point = find_child(node, "point")) obstacle.point = read_vec3(*point);
    if (auto normal = find_child(node, "normal")) {
      obstacle.normal = normalized_direction(*normal, read_vec3(*normal), "vector");
    }
    if (auto size = find_child(node, "size")) {
      obstacle.size = read_vec2(*size);
      for (int k = 0; k < 2; ++k) require_positive(element(*size, k), obstacle.size[k]);
    }
  } else if (obstacle.kind == ObstacleKind::box) {
    if (auto center = find_child(node, "center")) obstacle.point = read_vec3(*center);
    if (auto half_extents = find_child(node, "half_extents")) {
      obstacle.half_extents = read_vec3(*half_extents);
      for (int k = 0; k < 3; ++k) {
        require_positive(element(*half_extents, k), obstacle.half_extents[k]);
      }
    }
  } else {
    const JsonNode file = require_child(node, "file");
    obstacle.file = read_string(file);
    if (obstacle.file.empty()) fail(file, "must name a mesh file");
    if (auto position = find_child(node, "position")) obstacle.point = read_vec3(*position);
    if (auto scale = find_child(node, "scale")) {
      obstacle.scale = require_positive(*scale, read_real(*scale));
    }
  }
  if (obstacle.kind != ObstacleKind::plane) {
    if (auto orientation = find_child(node, "orientation")) {
      obstacle.orientation =
          normalized_direction(*orientation, read_vec4(*orientation), "quaternion");
    }
  }
  if (auto elasticity = find_child(node, "elasticity")) {
    obstacle.elasticity = require_non_negative(*elasticity, read_real(*elasticity));
  }
  if (auto friction = find_child(node, "friction")) {
    obstacle.friction = require_in_range(*friction, read_real(*friction), 0, 1);
  }
  return obstacle;
}

ForceFieldDef parse_force_field(const JsonNode& node, const std::vector<BodyDef>& bodies) {
  require_object(node, {"kind", "value", "bodies"});
  ForceFieldDef field;
  if (auto kind = find_child(node, "kind")) field.kind = read_enum(*kind, kForceFieldKindNames);
  if (auto value = find_child(node, "value")) field.value = read_vec3(*value);
  if (auto list = find_child(node, "bodies")) {
    const std::size_t n = require_array(*list);
    for (std::size_t i = 0; i < n; ++i) {
      field.bodies.push_back(parse_body_reference(element(*list, i), bodies));
    }
  }
  return field;
}

// A node of `body` (springs, constraint ends).
int read_node_index(const JsonNode& node, const BodyDef& body) {
  const int index = read_int(node);
  if (index < 0 || index >= node_count(body)) {
    fail(node, "node " + std::to_string(index) + " is out of range: body '" + body.name + "' has " +
                   std::to_string(node_count(body)) + " nodes (2 + rings * segments)");
  }
  return index;
}

// Material coordinates (u, v) within the ranges of (2.7): -pi/2 <= u <= pi/2, -pi <= v <= pi.
Vec2 read_material_point(const JsonNode& node) {
  const Vec2 uv = read_vec2(node);
  require_in_range(element(node, 0), uv[0], -std::numbers::pi / 2, std::numbers::pi / 2);
  require_in_range(element(node, 1), uv[1], -std::numbers::pi, std::numbers::pi);
  return uv;
}

SpringDef parse_spring(const JsonNode& node, std::size_t index,
                       const std::vector<BodyDef>& bodies) {
  require_object(node, {"name", "body", "node", "material_point", "target", "stiffness", "damping",
                        "t_begin", "t_end", "max_force"});
  SpringDef spring;
  spring.name = "spring" + std::to_string(index);
  if (auto name = find_child(node, "name")) spring.name = read_string(*name);
  if (auto body = find_child(node, "body")) spring.body = parse_body_reference(*body, bodies);
  const BodyDef& body = bodies[static_cast<std::size_t>(spring.body)];
  const std::optional<JsonNode> node_index = find_child(node, "node");
  const std::optional<JsonNode> material_point = find_child(node, "material_point");
  if (node_index.has_value() == material_point.has_value()) {
    fail(node, "give exactly one of 'node' and 'material_point'");
  }
  if (node_index) spring.node = read_node_index(*node_index, body);
  if (material_point) spring.material_point = read_material_point(*material_point);
  if (auto target = find_child(node, "target")) spring.target = read_vec3(*target);
  if (auto stiffness = find_child(node, "stiffness")) {
    spring.stiffness = require_non_negative(*stiffness, read_real(*stiffness));
  }
  if (auto damping = find_child(node, "damping")) {
    spring.damping = require_non_negative(*damping, read_real(*damping));
  }
  if (auto t_begin = find_child(node, "t_begin")) spring.t_begin = read_real(*t_begin);
  if (auto t_end = find_child(node, "t_end")) {
    spring.t_end = read_real(*t_end);
    if (!(spring.t_end >= spring.t_begin)) {
      fail(*t_end, "must be >= t_begin (" + format_real(spring.t_begin) + ")");
    }
  }
  if (auto max_force = find_child(node, "max_force")) {
    spring.max_force = require_positive(*max_force, read_real(*max_force));
  }
  return spring;
}

// ---- constraints (ch. 7) -----------------------------------------------------------------------

// "a" or "b" of a constraint: {"world": [x, y, z]} (b only), or {"body", one of "node",
// "material_point", "point"}; a hinge's body ends need "point" (its axis runs through them).
ConstraintEndDef parse_constraint_end(const JsonNode& node, const std::vector<BodyDef>& bodies,
                                      bool world_allowed, bool hinge) {
  require_object(node, {"body", "node", "material_point", "point", "world"});
  ConstraintEndDef end;
  if (auto world = find_child(node, "world")) {
    if (!world_allowed) fail(*world, "the first end of a constraint must be a body point");
    for (const char* key : {"body", "node", "material_point", "point"}) {
      if (auto other = find_child(node, key)) {
        fail(*other, std::string("key '") + key + "' is not valid with 'world'");
      }
    }
    end.world = read_vec3(*world);
    return end;
  }
  end.body = parse_body_reference(require_child(node, "body"), bodies);
  const BodyDef& body = bodies[static_cast<std::size_t>(end.body)];
  const std::optional<JsonNode> node_index = find_child(node, "node");
  const std::optional<JsonNode> material_point = find_child(node, "material_point");
  const std::optional<JsonNode> point = find_child(node, "point");
  const int given =
      int(node_index.has_value()) + int(material_point.has_value()) + int(point.has_value());
  if (given != 1) fail(node, "give exactly one of 'node', 'material_point' and 'point'");
  if (hinge && !point) fail(node, "a hinge's body ends need 'point' (body frame, on its axis)");
  if (node_index) end.node = read_node_index(*node_index, body);
  if (material_point) end.material_point = read_material_point(*material_point);
  if (point) end.point = read_vec3(*point);
  return end;
}

ConstraintDef parse_constraint(const JsonNode& node, std::size_t index,
                               const std::vector<BodyDef>& bodies) {
  require_object(node, {"name", "kind", "a", "b", "alpha", "beta", "axis", "length", "stiffness",
                        "rest_angle", "damping"});
  ConstraintDef c;
  c.name = "constraint" + std::to_string(index);
  if (auto name = find_child(node, "name")) c.name = read_string(*name);
  if (auto kind = find_child(node, "kind")) c.kind = read_enum(*kind, kConstraintKindNames);
  const bool hinge = c.kind == ConstraintKind::hinge;
  if (!hinge) {
    for (const char* key : {"axis", "length", "stiffness", "rest_angle", "damping"}) {
      if (auto other = find_child(node, key)) {
        fail(*other, std::string("key '") + key + "' is only valid for a hinge");
      }
    }
  }
  c.a = parse_constraint_end(require_child(node, "a"), bodies, false, hinge);
  c.b = parse_constraint_end(require_child(node, "b"), bodies, true, hinge);
  if (auto alpha = find_child(node, "alpha"))
    c.alpha = require_non_negative(*alpha, read_real(*alpha));
  if (auto beta = find_child(node, "beta")) c.beta = require_non_negative(*beta, read_real(*beta));
  if (auto axis = find_child(node, "axis"))
    c.axis = normalized_direction(*axis, read_vec3(*axis), "axis");
  if (auto length = find_child(node, "length"))
    c.length = require_positive(*length, read_real(*length));
  if (auto stiffness = find_child(node, "stiffness")) {
    c.stiffness = require_non_negative(*stiffness, read_real(*stiffness));
  }
  if (auto rest = find_child(node, "rest_angle")) c.rest_angle = read_real(*rest);
  if (auto damping = find_child(node, "damping")) {
    c.damping = require_non_negative(*damping, read_real(*damping));
  }
  if (c.b.body == c.a.body && c.b.node == c.a.node && c.a.node >= 0) {
    fail(node, "both ends are node " + std::to_string(c.a.node) + " of the same body");
  }
  if (hinge && c.b.body == c.a.body) fail(node, "a hinge must join two different bodies");
  return c;
}

// ---- tracks ------------------------------------------------------------------------------------

// Consumes `token` at the front of `text`.
bool consume(std::string_view& text, std::string_view token) {
  if (!text.starts_with(token)) return false;
  text.remove_prefix(token.size());
  return true;
}

// Consumes "[<decimal digits>]" at the front of `text`.
bool consume_index(std::string_view& text, int& index) {
  std::string_view rest = text;
  if (!consume(rest, "[")) return false;
  std::size_t digits = 0;
  std::int64_t value = 0;
  while (digits < rest.size() && rest[digits] >= '0' && rest[digits] <= '9' && digits < 9) {
    value = value * 10 + (rest[digits] - '0');
    ++digits;
  }
  if (digits == 0) return false;
  rest.remove_prefix(digits);
  if (!consume(rest, "]")) return false;
  index = static_cast<int>(value);
  text = rest;
  return true;
}

void require_index_below(const JsonNode& node, int index, std::size_t count,
                         const std::string& what) {
  if (static_cast<std::size_t>(index) >= count) {
    fail(node, what + " index " + std::to_string(index) + " is out of range (" +
                   std::to_string(count) + " available)");
  }
}

// Checks a track target against the scene and returns it in index form: "bodies[i].q_s0[k]",
// "gravity[k]", "springs[i].target[k]", "springs[i].stiffness", "camera.position[k]",
// "camera.target[k]", "camera.fov", "obstacles[i].point[k]" or "obstacles[i].rotation[k]";
// "bodies[i].q_s0.<name>" and an obstacle's own position key ("obstacles[i].center[k]") are
// accepted and rewritten to the index form.
std::string resolve_track_target(const JsonNode& node, const Scene& scene) {
  const std::string target = read_string(node);
  std::string_view rest = target;
  int i = 0, k = 0;
  if (consume(rest, "gravity") && consume_index(rest, k) && rest.empty()) {
    require_index_below(node, k, 3, "gravity component");
    return target;
  }
  rest = target;
  if (consume(rest, "bodies") && consume_index(rest, i) && consume(rest, ".q_s0")) {
    require_index_below(node, i, scene.bodies.size(), "body");
    const BodyDef& body = scene.bodies[static_cast<std::size_t>(i)];
    const int n_s = shape_parameter_count(body.shape);
    if (consume(rest, ".") && !rest.empty()) {
      k = find_shape_parameter(body.shape, rest);
      if (k < 0) {
        fail(node, "unknown shape parameter '" + std::string(rest) + "' for body '" + body.name +
                       "' (expected one of " + shape_parameter_list(body.shape) + ")");
      }
    } else if (!(consume_index(rest, k) && rest.empty())) {
      fail(node, "expected bodies[i].q_s0[k] or bodies[i].q_s0.<parameter name>");
    }
    require_index_below(node, k, static_cast<std::size_t>(n_s), "shape parameter");
    return element_path("bodies[" + std::to_string(i) + "].q_s0", static_cast<std::size_t>(k));
  }
  rest = target;
  if (consume(rest, "springs") && consume_index(rest, i)) {
    require_index_below(node, i, scene.springs.size(), "spring");
    if (rest == ".stiffness") return target;
    if (consume(rest, ".target") && consume_index(rest, k) && rest.empty()) {
      require_index_below(node, k, 3, "target component");
      return target;
    }
  }
  rest = target;
  if (consume(rest, "obstacles") && consume_index(rest, i)) {
    require_index_below(node, i, scene.obstacles.size(), "obstacle");
    const ObstacleDef& obstacle = scene.obstacles[static_cast<std::size_t>(i)];
    // Its position under the kind's own key ("center" of a box, "position" of a mesh) or
    // "point" for every kind; stored as point.
    const std::string_view own = obstacle.kind == ObstacleKind::box    ? ".center"
                                 : obstacle.kind == ObstacleKind::mesh ? ".position"
                                                                       : ".point";
    std::string_view field = rest;
    if ((consume(field, ".point") || consume(field, own)) && consume_index(field, k) &&
        field.empty()) {
      require_index_below(node, k, 3, "point component");
      return element_path("obstacles[" + std::to_string(i) + "].point",
                          static_cast<std::size_t>(k));
    }
    field = rest;
    if (consume(field, ".rotation") && consume_index(field, k) && field.empty()) {
      require_index_below(node, k, 3, "rotation component");
      return target;
    }
    fail(node, "unknown obstacle track target '" + target + "' for obstacle '" + obstacle.name +
                   "' (expected obstacles[i].point[k] or obstacles[i].rotation[k])");
  }
  rest = target;
  if (consume(rest, "camera.")) {
    if (!scene.camera) fail(node, "camera tracks need a 'camera' in the scene");
    if (rest == "fov") return target;
    if ((consume(rest, "position") || consume(rest, "target")) && consume_index(rest, k) &&
        rest.empty()) {
      require_index_below(node, k, 3, "camera component");
      return target;
    }
  }
  fail(node, "unknown track target '" + target +
                 "' (expected bodies[i].q_s0[k], bodies[i].q_s0.<name>, gravity[k], "
                 "springs[i].target[k], springs[i].stiffness, camera.position[k], "
                 "camera.target[k], camera.fov, obstacles[i].point[k] or "
                 "obstacles[i].rotation[k])");
}

TrackDef parse_track(const JsonNode& node, const Scene& scene) {
  require_object(node, {"target", "interpolation", "keys"});
  TrackDef track;
  track.target = resolve_track_target(require_child(node, "target"), scene);
  if (auto interpolation = find_child(node, "interpolation")) {
    track.interpolation = read_enum(*interpolation, kInterpolationNames);
  }
  const JsonNode keys = require_child(node, "keys");
  const std::size_t n = require_array(keys);
  if (n == 0) fail(keys, "must have at least one key [time, value]");
  for (std::size_t j = 0; j < n; ++j) {
    const JsonNode key = element(keys, j);
    if (!key.value->is_array() || key.value->size() != 2) {
      fail(key, "must be a [time, value] pair of numbers");
    }
    const Vec2 time_value = read_vec2(key);
    if (j > 0 && !(time_value[0] > track.keys.back().time)) {
      fail(key, "time " + format_real(time_value[0]) +
                    " must be greater than the previous key's time " +
                    format_real(track.keys.back().time));
    }
    track.keys.push_back(Keyframe{.time = time_value[0], .value = time_value[1]});
  }
  return track;
}

// ---- solver and the whole scene ----------------------------------------------------------------

SolverDef parse_solver(const JsonNode& node) {
  require_object(node,
                 {"dt", "integrator", "tolerance", "fps", "duration", "contact_step_reduction",
                  "contact_dt_factor", "max_retries", "energy_growth_bound", "constraint_alpha",
                  "constraint_beta", "constraint_solver", "body_collisions", "self_collision",
                  "body_friction", "body_elasticity", "collision_margin"});
  SolverDef solver;
  if (auto dt = find_child(node, "dt")) solver.dt = require_positive(*dt, read_real(*dt));
  if (auto integrator = find_child(node, "integrator")) {
    solver.integrator = read_enum(*integrator, kIntegratorKindNames);
  }
  if (auto tolerance = find_child(node, "tolerance")) {
    solver.tolerance = require_positive(*tolerance, read_real(*tolerance));
  }
  if (auto fps = find_child(node, "fps")) solver.fps = require_positive(*fps, read_real(*fps));
  if (auto duration = find_child(node, "duration")) {
    solver.duration = require_positive(*duration, read_real(*duration));
  }
  if (auto reduction = find_child(node, "contact_step_reduction")) {
    solver.contact_step_reduction = read_bool(*reduction);
  }
  if (auto factor = find_child(node, "contact_dt_factor")) {
    solver.contact_dt_factor = read_real(*factor);
    if (!(solver.contact_dt_factor > 0 && solver.contact_dt_factor <= 1)) {
      fail(*factor, "must be in (0, 1]");
    }
  }
  if (auto retries = find_child(node, "max_retries")) {
    solver.max_retries = read_int(*retries);
    if (solver.max_retries < 0 || solver.max_retries > kMaxRetriesLimit) {
      fail(*retries, "must be in [0, " + std::to_string(kMaxRetriesLimit) + "]");
    }
  }
  if (auto bound = find_child(node, "energy_growth_bound")) {
    // A bound below 1 would reject frames that merely conserve energy.
    solver.energy_growth_bound = read_real(*bound);
    if (!(solver.energy_growth_bound >= 1)) fail(*bound, "must be >= 1");
  }
  if (auto alpha = find_child(node, "constraint_alpha")) {
    solver.constraint_alpha = require_non_negative(*alpha, read_real(*alpha));
  }
  if (auto beta = find_child(node, "constraint_beta")) {
    solver.constraint_beta = require_non_negative(*beta, read_real(*beta));
  }
  if (auto kind = find_child(node, "constraint_solver")) {
    solver.constraint_solver = read_enum(*kind, kConstraintSolverKindNames);
  }
  if (auto on = find_child(node, "body_collisions")) solver.body_collisions = read_bool(*on);
  if (auto on = find_child(node, "self_collision")) solver.self_collision = read_bool(*on);
  if (auto friction = find_child(node, "body_friction")) {
    solver.body_friction = require_in_range(*friction, read_real(*friction), 0, 1);
  }
  if (auto elasticity = find_child(node, "body_elasticity")) {
    solver.body_elasticity = require_non_negative(*elasticity, read_real(*elasticity));
  }
  if (auto margin = find_child(node, "collision_margin")) {
    solver.collision_margin = require_positive(*margin, read_real(*margin));
  }
  return solver;
}

// Calls parse(element, index) for each element of the optional array `key`.
template <typename Def, typename Parse>
std::vector<Def> parse_list(const JsonNode& root, std::string_view key, Parse parse) {
  std::vector<Def> defs;
  if (auto list = find_child(root, key)) {
    const std::size_t n = require_array(*list);
    defs.reserve(n);
    for (std::size_t i = 0; i < n; ++i) defs.push_back(parse(element(*list, i), i));
  }
  return defs;
}

}  // namespace

CameraDef parse_camera(const JsonNode& node) {
  require_object(node, {"position", "target", "up", "fov"});
  CameraDef camera;
  if (auto position = find_child(node, "position")) camera.position = read_vec3(*position);
  if (auto target = find_child(node, "target")) camera.target = read_vec3(*target);
  if (auto up = find_child(node, "up")) camera.up = normalized_direction(*up, read_vec3(*up), "up");
  if (auto fov = find_child(node, "fov")) {
    camera.fov = read_real(*fov);
    if (!(camera.fov > 0 && camera.fov < 180)) fail(*fov, "must be in (0, 180) degrees");
  }
  if ((camera.target - camera.position).norm() < 1e-9) {
    fail(node, "position and target must differ");
  }
  if ((camera.target - camera.position).normalized().cross(camera.up).norm() < 1e-6) {
    fail(node, "up must not be parallel to the viewing direction");
  }
  return camera;
}

Scene parse_scene(const std::string& json_text, const std::string& file_for_messages) {
  const nlohmann::json document = parse_json_text(json_text, file_for_messages);
  const JsonNode root = root_node(document, file_for_messages);
  require_object(root, {"name", "gravity", "solver", "bodies", "obstacles", "force_fields",
                        "springs", "tracks", "constraints", "camera"});
  Scene scene;
  scene.file = file_for_messages;
  if (auto name = find_child(root, "name")) scene.name = read_string(*name);
  if (auto gravity = find_child(root, "gravity")) scene.gravity = read_vec3(*gravity);
  if (auto solver = find_child(root, "solver")) scene.solver = parse_solver(*solver);
  if (auto camera = find_child(root, "camera")) scene.camera = parse_camera(*camera);

  // Bodies first: every other list refers to them.
  const JsonNode bodies = require_child(root, "bodies");
  const std::size_t n_bodies = require_array(bodies);
  if (n_bodies == 0) fail(bodies, "must have at least one body");
  for (std::size_t i = 0; i < n_bodies; ++i) {
    const JsonNode body_node = element(bodies, i);
    BodyDef body = parse_body(body_node, i);
    for (std::size_t j = 0; j < i; ++j) {
      if (scene.bodies[j].name == body.name) {
        fail(JsonNode{body_node.value, child_path(body_node.path, "name"), body_node.file},
             "duplicate body name '" + body.name + "' (also bodies[" + std::to_string(j) + "])");
      }
    }
    scene.bodies.push_back(std::move(body));
  }
  scene.obstacles = parse_list<ObstacleDef>(root, "obstacles", parse_obstacle);
  scene.force_fields = parse_list<ForceFieldDef>(
      root, "force_fields",
      [&](const JsonNode& node, std::size_t) { return parse_force_field(node, scene.bodies); });
  scene.springs = parse_list<SpringDef>(root, "springs", [&](const JsonNode& node, std::size_t i) {
    return parse_spring(node, i, scene.bodies);
  });
  scene.constraints = parse_list<ConstraintDef>(
      root, "constraints",
      [&](const JsonNode& node, std::size_t i) { return parse_constraint(node, i, scene.bodies); });
  // Tracks last: their targets refer to bodies and springs.
  scene.tracks = parse_list<TrackDef>(
      root, "tracks", [&](const JsonNode& node, std::size_t) { return parse_track(node, scene); });
  for (std::size_t i = 0; i < scene.tracks.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (scene.tracks[j].target == scene.tracks[i].target) {
        throw Error(file_for_messages, "tracks[" + std::to_string(i) + "].target",
                    "'" + scene.tracks[i].target + "' is already driven by tracks[" +
                        std::to_string(j) + "]");
      }
    }
  }
  return scene;
}

Scene load_scene(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw Error(path, "", "cannot open file: it is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "", "cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path, "", "cannot read file");
  return parse_scene(text.str(), path);
}

}  // namespace pbm
