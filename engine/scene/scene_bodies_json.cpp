// The "bodies[i]" section of a scene file with its "shape", "tessellation" and "material"
// (scenes/README.md).
#include <cstdint>

#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

// Every node costs the Model about 1.4 KB and its share of every step: these keep what a file can
// ask for below 150 MB and half a second to load (scenes/README.md, "Limits"), six times the
// largest body of `pbm bench deform`.
constexpr Real kMaxRingsOrSegments = 4096;
constexpr std::int64_t kMaxNodesPerScene = 100000;

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

// q_s-like vectors by parameter name; an array if the size does not match the kind (the reader
// will then say so), nothing if empty (the reader's defaults apply).
void write_shape_vector(const FieldFormat& format, ShapeKind kind, const VecX& values,
                        OrderedJson& shape) {
  if (values.size() == 0) return;
  if (values.size() != shape_parameter_count(kind)) {
    shape[format.key] = to_array(values);
    return;
  }
  OrderedJson named = OrderedJson::object();
  for (int i = 0; i < values.size(); ++i) named[shape_parameter_name(kind, i)] = values[i];
  shape[format.key] = std::move(named);
}

// The parameters' fallbacks chain: q_s falls back on the kind's defaults, rest on q_s (3.31),
// stiffness on 0. Absent vectors are filled in by check_body once every key is read.
constexpr auto kShapeFields = std::to_array<Field<BodyDef>>({
    choice<&BodyDef::shape, kShapeKindNames>(
        {.key = "kind",
         .description = "(2.7) with 6 parameters, (2.10) with 11, (2.13)-(2.27) with 39."}),
    {{.key = "q_s",
      .type = ValueType::shape_vector,
      .default_note = "the kind's defaults (the unit sphere)",
      .description = "Initial global parameters q_s; missing names take the kind's defaults."},
     [](const FieldFormat&, const JsonNode& node, BodyDef& body, const ReadContext&) {
       body.q_s = read_shape_vector(node, body.shape, default_shape_parameters(body.shape),
                                    ShapeVectorRole::shape);
     },
     [](const FieldFormat& f, const BodyDef& body, OrderedJson& shape) {
       write_shape_vector(f, body.shape, body.q_s, shape);
     }},
    {{.key = "rest",
      .type = ValueType::shape_vector,
      .default_note = "q_s",
      .description = "Rest values q_s0 of the global stiffness (3.31); missing names take q_s."},
     [](const FieldFormat&, const JsonNode& node, BodyDef& body, const ReadContext&) {
       const VecX fallback = body.q_s.size() > 0 ? body.q_s : default_shape_parameters(body.shape);
       body.q_s0 = read_shape_vector(node, body.shape, fallback, ShapeVectorRole::shape);
     },
     [](const FieldFormat& f, const BodyDef& body, OrderedJson& shape) {
       write_shape_vector(f, body.shape, body.q_s0, shape);
     }},
    {{.key = "stiffness",
      .type = ValueType::shape_vector,
      .unit = "N/m per unit of the parameter",
      .default_note = "all 0",
      .description = "k_s per parameter (3.32), each >= 0; missing names take 0."},
     [](const FieldFormat&, const JsonNode& node, BodyDef& body, const ReadContext&) {
       const VecX none = VecX::Zero(shape_parameter_count(body.shape));
       body.k_s = read_shape_vector(node, body.shape, none, ShapeVectorRole::stiffness);
     },
     [](const FieldFormat& f, const BodyDef& body, OrderedJson& shape) {
       write_shape_vector(f, body.shape, body.k_s, shape);
     }},
});

}  // namespace

constexpr Section<BodyDef> kShapeSection{.name = "shape", .noun = "shape", .fields = kShapeFields};

namespace {

// ---- tessellation, material --------------------------------------------------------------------

constexpr auto kTessellationFields = std::to_array<Field<TessellationDef>>({
    choice<&TessellationDef::kind, kTessellationKindNames>(
        {.key = "kind",
         .description = "Quads with pole triangles (fig. 4.1) or all triangles (fig. 4.2)."}),
    value<&TessellationDef::rings>({.key = "rings",
                                    .range = {.lo = 2},
                                    .limit = kMaxRingsOrSegments,
                                    .description = "Latitude rings between the poles."}),
    value<&TessellationDef::segments>({.key = "segments",
                                       .range = {.lo = 3},
                                       .limit = kMaxRingsOrSegments,
                                       .description = "Nodes around each ring; the body has 2 + "
                                                      "rings * segments nodes."}),
    choice<&TessellationDef::contact, kContactQuadratureNames>(
        {.key = "contact",
         .description = "Where obstacles push on each surface triangle: three points, or the "
                        "centroid alone (a third of the contact's cost; a resting ball creeps "
                        "toward its deepest orientation)."}),
});

}  // namespace

constexpr Section<TessellationDef> kTessellationSection{
    .name = "tessellation", .noun = "tessellation", .fields = kTessellationFields};

namespace {

constexpr auto kMaterialFields = std::to_array<Field<MaterialDef>>({
    value<&MaterialDef::w0>({.key = "w0",
                             .range = kNonNegative,
                             .description = "Membrane magnitude stiffness w00 (3.34)."}),
    value<&MaterialDef::w1>({.key = "w1",
                             .range = kNonNegative,
                             .description = "Membrane variation stiffness w10 = w01 (3.34)."}),
    // Only the given mass is written; a material made in code with none writes nodal_mass.
    {{.key = "mass",
      .type = ValueType::number,
      .unit = "kg",
      .range = kPositive,
      .one_of = 1,
      .default_note = "none: give mass, density or nodal_mass",
      .description = "Total mass, spread over the nodes by their areas on the initial surface."},
     read_value<&MaterialDef::mass>,
     [](const FieldFormat& f, const MaterialDef& material, OrderedJson& object) {
       if (material.mass > 0) object[f.key] = material.mass;
     }},
    {{.key = "density",
      .type = ValueType::number,
      .unit = "kg/m^2",
      .range = kPositive,
      .one_of = 1,
      .default_note = "none: give mass, density or nodal_mass",
      .description = "Areal density of the initial surface, spread over the nodes by their areas."},
     read_value<&MaterialDef::density>,
     [](const FieldFormat& f, const MaterialDef& material, OrderedJson& object) {
       if (material.density > 0 && !(material.mass > 0)) object[f.key] = material.density;
     }},
    {{.key = "nodal_mass",
      .type = ValueType::number,
      .unit = "kg",
      .range = kPositive,
      .one_of = 1,
      .default_note = "none: give mass, density or nodal_mass",
      .description =
          "Lumped mass of each node (the book's; the body's mass grows with its nodes)."},
     read_value<&MaterialDef::nodal_mass>,
     [](const FieldFormat& f, const MaterialDef& material, OrderedJson& object) {
       if (!(material.mass > 0) && !(material.density > 0)) object[f.key] = material.nodal_mass;
     }},
    value<&MaterialDef::contact_stiffness>(
        {.key = "contact_stiffness",
         .unit = "N/m^3",
         .range = kNonNegative,
         .description =
             "Contact pressure per metre of dent, times the obstacle's elasticity; 0: "
             "the book's (5.10), the nodes' K_ii per area, which grows with the nodes."}),
    value<&MaterialDef::damping>({.key = "damping",
                                  .unit = "1/s",
                                  .range = kNonNegative,
                                  .description = "nu in D = nu M (sec. 6.1)."}),
    value<&MaterialDef::color>({.key = "color",
                                .range = kUnitInterval,
                                .description = "Base colour (r, g, b) for the renderer."}),
    value<&MaterialDef::roughness>({.key = "roughness",
                                    .range = kUnitInterval,
                                    .description = "Renderer: 0 = sharp highlight, 1 = matte."}),
});

}  // namespace

constexpr Section<MaterialDef> kMaterialSection{
    .name = "material", .noun = "material", .fields = kMaterialFields};

namespace {

// ---- the body ------------------------------------------------------------------------------

std::int64_t node_count(const TessellationDef& tessellation) {
  return 2 + static_cast<std::int64_t>(tessellation.rings) * tessellation.segments;
}

// The scene's nodes so far and this body's must stay within kMaxNodesPerScene.
void check_node_count(const JsonNode& node, const BodyDef& body, const ReadContext& context) {
  std::int64_t before = 0;
  for (std::size_t j = 0; j < context.index && j < context.scene.bodies.size(); ++j) {
    before += node_count(context.scene.bodies[j].tessellation);
  }
  const std::int64_t product = node_count(body.tessellation) - 2;
  if (before + 2 + product > kMaxNodesPerScene) {
    fail(JsonNode{node.value, child_path(node.path, "tessellation"), node.file},
         "rings * segments must be <= " + std::to_string(kMaxNodesPerScene - before - 2) +
             " (got " + std::to_string(product) + "): a scene's bodies have at most " +
             std::to_string(kMaxNodesPerScene) + " nodes, 2 + rings * segments each");
  }
}

void check_body(const JsonNode& node, BodyDef& body, const ReadContext& context) {
  if (body.q_s.size() == 0) body.q_s = default_shape_parameters(body.shape);
  if (body.q_s0.size() == 0) body.q_s0 = body.q_s;
  if (body.k_s.size() == 0) body.k_s = VecX::Zero(body.q_s.size());
  check_node_count(node, body, context);
  const int same = earlier_with(context.scene.bodies, context.index, &BodyDef::name, body.name);
  if (same >= 0) {
    fail(JsonNode{node.value, child_path(node.path, "name"), node.file},
         "duplicate body name '" + body.name + "' (also bodies[" + std::to_string(same) + "])");
  }
}

constexpr auto kBodyFields = std::to_array<Field<BodyDef>>({
    value<&BodyDef::name>({.key = "name",
                           .non_empty = true,
                           .default_note = "body<i>",
                           .description = "Unique; springs, force fields and constraints refer "
                                          "to bodies by it."}),
    choice<&BodyDef::level, kDeformLevelNames>(
        {.key = "level", .description = "DOFs: q_c, q_theta; + q_s; + q_s and q_d."}),
    choice<&BodyDef::order, kDynamicsOrderNames>(
        {.key = "order", .description = "Lagrangian model (3.13) or first-order model (3.51)."}),
    inline_object<kShapeSection, BodyDef>(
        {.key = "shape", .description = "Reference shape s(u; q_s); a unit sphere if absent."}),
    value<&BodyDef::position>({.key = "position", .unit = "m", .description = "q_c, world frame."}),
    unit_vector<&BodyDef::orientation>(
        {.key = "orientation", .description = "q_theta (w, x, y, z), normalized on load."}),
    value<&BodyDef::velocity>(
        {.key = "velocity", .unit = "m/s", .description = "c-dot, world frame."}),
    value<&BodyDef::angular_velocity>(
        {.key = "angular_velocity", .unit = "rad/s", .description = "omega, world frame."}),
    object<&BodyDef::tessellation, kTessellationSection>(
        {.key = "tessellation", .description = "Nodes on (u, v)."}),
    object<&BodyDef::material, kMaterialSection>(
        {.key = "material", .required = true, .description = "Stiffness, mass, damping, colour."}),
});

}  // namespace

constexpr Section<BodyDef> kBodySection{
    .name = "body",
    .noun = "body",
    .fields = kBodyFields,
    .init = [](BodyDef& body,
               const ReadContext& context) { body.name = "body" + std::to_string(context.index); },
    .check = check_body};

}  // namespace pbm
