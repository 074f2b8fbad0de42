// The loads on bodies a scene file gives besides gravity (scenes/README.md): "force_fields[i]"
// and "springs[i]" (sec. 6.4's mouse spring).
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

// SpringDef's "active forever" end time and "unlimited" force; not worth writing out.
constexpr Real kForever = 1e300;

constexpr auto kForceFieldFields = std::to_array<Field<ForceFieldDef>>({
    choice<&ForceFieldDef::kind, kForceFieldKindNames>(
        {.key = "kind", .description = "A uniform acceleration, or the same force on every node."}),
    value<&ForceFieldDef::value>(
        {.key = "value", .unit = "m/s^2 or N", .description = "World frame."}),
    {{.key = "bodies",
      .type = ValueType::body_references,
      .description = "Bodies affected, by index or name; empty: every body."},
     [](const FieldFormat&, const JsonNode& node, ForceFieldDef& field,
        const ReadContext& context) {
       const std::size_t n = require_array(node);
       for (std::size_t i = 0; i < n; ++i) {
         field.bodies.push_back(read_body_reference(element(node, i), context.scene.bodies));
       }
     },
     [](const FieldFormat& f, const ForceFieldDef& field, OrderedJson& object) {
       object[f.key] = field.bodies;
     }},
});

}  // namespace

// A wind along x for the studio's "add".
constexpr Section<ForceFieldDef> kForceFieldSection{
    .name = "force_field",
    .noun = "force field",
    .fields = kForceFieldFields,
    .new_item = R"({"kind": "acceleration", "value": [1, 0, 0]})"};

namespace {

const BodyDef& spring_body(const SpringDef& spring, const ReadContext& context) {
  return context.scene.bodies[static_cast<std::size_t>(spring.body)];
}

// An end time or force limit left out of the file when it is "forever".
template <auto Member>
void write_unless_forever(const FieldFormat& format, const SpringDef& spring, OrderedJson& object) {
  if (spring.*Member < kForever) object[format.key] = spring.*Member;
}

void check_spring(const JsonNode& node, SpringDef& spring, const ReadContext&) {
  if (auto t_end = find_child(node, "t_end"); t_end && !(spring.t_end >= spring.t_begin)) {
    fail(*t_end, "must be >= t_begin (" + format_real(spring.t_begin) + ")");
  }
}

constexpr auto kSpringFields = std::to_array<Field<SpringDef>>({
    value<&SpringDef::name>({.key = "name", .default_note = "spring<i>"}),
    {{.key = "body",
      .type = ValueType::body_reference,
      .description = "The body pulled, by index or name."},
     [](const FieldFormat&, const JsonNode& node, SpringDef& spring, const ReadContext& context) {
       spring.body = read_body_reference(node, context.scene.bodies);
     },
     write_value<&SpringDef::body>},
    {{.key = "node",
      .type = ValueType::node_index,
      .one_of = 1,
      .default_note = "none: give node or material_point",
      .description = "The node the spring pulls, in [0, 2 + rings * segments)."},
     [](const FieldFormat&, const JsonNode& node, SpringDef& spring, const ReadContext& context) {
       spring.node = read_node_index(node, spring_body(spring, context));
     },
     [](const FieldFormat& f, const SpringDef& spring, OrderedJson& object) {
       if (spring.node >= 0 || !spring.material_point) object[f.key] = spring.node;
     }},
    {{.key = "material_point",
      .type = ValueType::material_point,
      .unit = "rad",
      .one_of = 1,
      .default_note = "none: give node or material_point",
      .description = "(u, v), u in [-pi/2, pi/2], v in [-pi, pi], resolved to the nearest "
                     "node."},
     [](const FieldFormat&, const JsonNode& node, SpringDef& spring, const ReadContext&) {
       spring.material_point = read_material_point(node);
     },
     [](const FieldFormat& f, const SpringDef& spring, OrderedJson& object) {
       if (!(spring.node >= 0 || !spring.material_point)) {
         object[f.key] = to_array(*spring.material_point);
       }
     }},
    value<&SpringDef::target>(
        {.key = "target", .unit = "m", .description = "The other end of the spring, world frame."}),
    value<&SpringDef::stiffness>({.key = "stiffness", .unit = "N/m", .range = kNonNegative}),
    value<&SpringDef::damping>({.key = "damping", .unit = "N s/m", .range = kNonNegative}),
    value<&SpringDef::t_begin>(
        {.key = "t_begin", .unit = "s", .description = "Start of the active interval."}),
    {{.key = "t_end",
      .type = ValueType::number,
      .unit = "s",
      .default_note = "forever",
      .description = "End of the active interval, >= t_begin."},
     read_value<&SpringDef::t_end>,
     write_unless_forever<&SpringDef::t_end>},
    {{.key = "max_force",
      .type = ValueType::number,
      .unit = "N",
      .range = kPositive,
      .default_note = "unlimited",
      .description = "The force's magnitude is clamped to it (studio drags)."},
     read_value<&SpringDef::max_force>,
     write_unless_forever<&SpringDef::max_force>},
});

}  // namespace

constexpr Section<SpringDef> kSpringSection{.name = "spring",
                                            .noun = "spring",
                                            .fields = kSpringFields,
                                            .init =
                                                [](SpringDef& spring, const ReadContext& context) {
                                                  spring.name =
                                                      "spring" + std::to_string(context.index);
                                                },
                                            .check = check_spring};

}  // namespace pbm
