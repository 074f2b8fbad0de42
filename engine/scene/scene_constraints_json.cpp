// The "constraints[i]" section of a scene file and its ends "a" and "b" (scenes/README.md, ch. 7).
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

constexpr std::uint32_t kHinge = kind_bit(ConstraintKind::hinge);

// Which of an end's keys the writer writes: "world" alone for an anchor, else "body" and the one
// of "point", "node", "material_point" that locates the body point.
enum class EndForm { world, point, node, material_point };

EndForm form_of(const ConstraintEndDef& end) {
  if (end.body < 0) return EndForm::world;
  if (end.point) return EndForm::point;
  if (end.node >= 0 || !end.material_point) return EndForm::node;
  return EndForm::material_point;
}

const BodyDef& end_body(const ConstraintEndDef& end, const ReadContext& context) {
  return context.scene.bodies[static_cast<std::size_t>(end.body)];
}

constexpr auto kEndFields = std::to_array<Field<ConstraintEndDef>>({
    {{.key = "body",
      .type = ValueType::body_reference,
      .default_note = "none",
      .description = "The body, by index or name (not with world)."},
     [](const FieldFormat&, const JsonNode& node, ConstraintEndDef& end,
        const ReadContext& context) { end.body = read_body_reference(node, context.scene.bodies); },
     [](const FieldFormat& f, const ConstraintEndDef& end, OrderedJson& object) {
       if (form_of(end) != EndForm::world) object[f.key] = end.body;
     }},
    {{.key = "node",
      .type = ValueType::node_index,
      .one_of = 1,
      .default_note = "none",
      .description = "A node, in [0, 2 + rings * segments)."},
     [](const FieldFormat&, const JsonNode& node, ConstraintEndDef& end,
        const ReadContext& context) { end.node = read_node_index(node, end_body(end, context)); },
     [](const FieldFormat& f, const ConstraintEndDef& end, OrderedJson& object) {
       if (form_of(end) == EndForm::node) object[f.key] = end.node;
     }},
    {{.key = "material_point",
      .type = ValueType::material_point,
      .unit = "rad",
      .one_of = 1,
      .default_note = "none",
      .description = "(u, v), resolved to the nearest node like springs."},
     [](const FieldFormat&, const JsonNode& node, ConstraintEndDef& end, const ReadContext&) {
       end.material_point = read_material_point(node);
     },
     [](const FieldFormat& f, const ConstraintEndDef& end, OrderedJson& object) {
       if (form_of(end) == EndForm::material_point) object[f.key] = to_array(*end.material_point);
     }},
    {{.key = "point",
      .type = ValueType::vector,
      .unit = "m",
      .size = 3,
      .one_of = 1,
      .default_note = "none",
      .description = "A point fixed in the body frame (x = c + R p)."},
     [](const FieldFormat&, const JsonNode& node, ConstraintEndDef& end, const ReadContext&) {
       end.point = read_vec3(node);
     },
     [](const FieldFormat& f, const ConstraintEndDef& end, OrderedJson& object) {
       if (form_of(end) == EndForm::point) object[f.key] = to_array(*end.point);
     }},
    {{.key = "world",
      .type = ValueType::vector,
      .unit = "m",
      .size = 3,
      .default_note = "none",
      .description = "A fixed anchor, world frame (end b only, alone)."},
     read_value<&ConstraintEndDef::world>,
     [](const FieldFormat& f, const ConstraintEndDef& end, OrderedJson& object) {
       if (form_of(end) == EndForm::world) object[f.key] = to_array(end.world);
     }},
});

}  // namespace

constexpr Section<ConstraintEndDef> kConstraintEndSection{
    .name = "constraint_end", .noun = "constraint end", .fields = kEndFields};

namespace {

// "a" or "b" of a constraint: {"world": [x, y, z]} (b only), or {"body", one of "node",
// "material_point", "point"}; a hinge's body ends need "point" (its axis runs through them).
ConstraintEndDef read_end(const JsonNode& node, const ReadContext& context, bool world_allowed,
                          bool hinge) {
  require_section_keys(kConstraintEndSection, node);
  ConstraintEndDef end;
  if (auto world = find_child(node, "world")) {
    if (!world_allowed) fail(*world, "the first end of a constraint must be a body point");
    for (const char* key : {"body", "node", "material_point", "point"}) {
      if (auto other = find_child(node, key)) {
        fail(*other, std::string("key '") + key + "' is not valid with 'world'");
      }
    }
    read_key(kConstraintEndSection, "world", node, end, context);
    return end;
  }
  require_child(node, "body");
  read_key(kConstraintEndSection, "body", node, end, context);
  require_one_of(kConstraintEndSection, node, 1);
  if (hinge && !find_child(node, "point"))
    fail(node, "a hinge's body ends need 'point' (body frame, on its axis)");
  for (const char* key : {"node", "material_point", "point"}) {
    read_key(kConstraintEndSection, key, node, end, context);
  }
  return end;
}

void check_constraint(const JsonNode& node, ConstraintDef& c, const ReadContext&) {
  if (c.b.body == c.a.body && c.b.node == c.a.node && c.a.node >= 0) {
    fail(node, "both ends are node " + std::to_string(c.a.node) + " of the same body");
  }
  if (c.kind == ConstraintKind::hinge && c.b.body == c.a.body) {
    fail(node, "a hinge must join two different bodies");
  }
}

constexpr auto kConstraintFields = std::to_array<Field<ConstraintDef>>({
    value<&ConstraintDef::name>({.key = "name", .default_note = "constraint<i>"}),
    choice<&ConstraintDef::kind, kConstraintKindNames>(
        {.key = "kind", .description = "A point-to-point constraint, or a hinge."}),
    {{.key = "a",
      .type = ValueType::object,
      .required = true,
      .section = "constraint_end",
      .description = "First end, a body point (\"one\" of sec. 7.3.2)."},
     [](const FieldFormat&, const JsonNode& node, ConstraintDef& c, const ReadContext& context) {
       c.a = read_end(node, context, false, c.kind == ConstraintKind::hinge);
     },
     [](const FieldFormat& f, const ConstraintDef& c, OrderedJson& object) {
       object[f.key] = write_section(kConstraintEndSection, c.a);
     }},
    {{.key = "b",
      .type = ValueType::object,
      .required = true,
      .section = "constraint_end",
      .description = "Second end, a body point or a world anchor (\"two\")."},
     [](const FieldFormat&, const JsonNode& node, ConstraintDef& c, const ReadContext& context) {
       c.b = read_end(node, context, true, c.kind == ConstraintKind::hinge);
     },
     [](const FieldFormat& f, const ConstraintDef& c, OrderedJson& object) {
       object[f.key] = write_section(kConstraintEndSection, c.b);
     }},
    value<&ConstraintDef::alpha>({.key = "alpha",
                                  .unit = "1/s",
                                  .range = kNonNegative,
                                  .default_note = "solver.constraint_alpha",
                                  .description = "This constraint's Baumgarte alpha."}),
    value<&ConstraintDef::beta>({.key = "beta",
                                 .unit = "1/s",
                                 .range = kNonNegative,
                                 .default_note = "this alpha if given, else the solver's beta",
                                 .description = "This constraint's Baumgarte beta."}),
    unit_vector<&ConstraintDef::axis>(
        {.key = "axis",
         .kinds = kHinge,
         .description = "Hinge: its axis at the initial state, world frame (normalized on "
                        "load)."}),
    value<&ConstraintDef::length>(
        {.key = "length",
         .unit = "m",
         .range = kPositive,
         .kinds = kHinge,
         .description = "Hinge: distance between its two point constraints on the axis."}),
    value<&ConstraintDef::stiffness>(
        {.key = "stiffness",
         .unit = "N m/rad",
         .range = kNonNegative,
         .kinds = kHinge,
         .description = "Hinge: rotational spring E = 1/2 k (theta - theta_0)^2."}),
    value<&ConstraintDef::rest_angle>(
        {.key = "rest_angle",
         .unit = "rad",
         .kinds = kHinge,
         .description = "Hinge: theta_0, the angle of a relative to b (0 at the start)."}),
    value<&ConstraintDef::damping>({.key = "damping",
                                    .unit = "N m s/rad",
                                    .range = kNonNegative,
                                    .kinds = kHinge,
                                    .description = "Hinge: rotational damper."}),
});

}  // namespace

constexpr Section<ConstraintDef> kConstraintSection{
    .name = "constraint",
    .noun = "constraint",
    .fields = kConstraintFields,
    .kind_of = [](const ConstraintDef& c) { return static_cast<int>(c.kind); },
    .kind_names = kNameList<kConstraintKindNames>,
    .init =
        [](ConstraintDef& c, const ReadContext& context) {
          c.name = "constraint" + std::to_string(context.index);
        },
    .check = check_constraint};

}  // namespace pbm
