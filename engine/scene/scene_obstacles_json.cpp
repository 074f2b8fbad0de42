// The "obstacles[i]" section of a scene file (scenes/README.md): planes, boxes and meshes, each
// kind with its own keys.
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

constexpr std::uint32_t kPlane = kind_bit(ObstacleKind::plane);
constexpr std::uint32_t kBox = kind_bit(ObstacleKind::box);
constexpr std::uint32_t kMesh = kind_bit(ObstacleKind::mesh);

// A plane's "point", a box's "center" and a mesh's "position" are the same member, written under
// the kind's own key; in this order the writer writes each kind's keys as scenes/README.md lists
// them.
constexpr auto kObstacleFields = std::to_array<Field<ObstacleDef>>({
    value<&ObstacleDef::name>({.key = "name", .default_note = "obstacle<i>"}),
    choice<&ObstacleDef::kind, kObstacleKindNames>({.key = "kind"}),
    value<&ObstacleDef::point>(
        {.key = "point", .unit = "m", .kinds = kPlane, .description = "Plane: a point on it."}),
    unit_vector<&ObstacleDef::normal>(
        {.key = "normal",
         .kinds = kPlane,
         .description = "Plane: outward normal, nonzero, normalized on load."}),
    value<&ObstacleDef::size>({.key = "size",
                               .unit = "m",
                               .range = kPositive,
                               .kinds = kPlane,
                               .description = "Plane: drawn extent (the plane is infinite)."}),
    value<&ObstacleDef::point>(
        {.key = "center", .unit = "m", .kinds = kBox, .description = "Box: centre."}),
    value<&ObstacleDef::half_extents>({.key = "half_extents",
                                       .unit = "m",
                                       .range = kPositive,
                                       .kinds = kBox,
                                       .description = "Box: half sizes along its axes."}),
    value<&ObstacleDef::file>(
        {.key = "file",
         .required = true,
         .non_empty = true,
         .kinds = kMesh,
         .description = "Mesh: a file assimp reads (OBJ, glTF, FBX, PLY, STL), relative to the "
                        "scene file; at most 20,000 triangles."}),
    value<&ObstacleDef::point>({.key = "position",
                                .unit = "m",
                                .kinds = kMesh,
                                .description = "Mesh: where its file's origin goes."}),
    unit_vector<&ObstacleDef::orientation>(
        {.key = "orientation",
         .kinds = kBox | kMesh,
         .description = "Box or mesh orientation (w, x, y, z), normalized on load."}),
    value<&ObstacleDef::scale>({.key = "scale",
                                .range = kPositive,
                                .kinds = kMesh,
                                .description = "Mesh: uniform scale of its file's coordinates."}),
    value<&ObstacleDef::elasticity>(
        {.key = "elasticity",
         .range = kNonNegative,
         .description = "a in f_n = a (f_i . n) n (5.11): a spring a K per area of the global "
                        "surface inside the obstacle."}),
    value<&ObstacleDef::friction>(
        {.key = "friction", .range = kUnitInterval, .description = "beta_f in (5.12)."}),
});

}  // namespace

constexpr Section<ObstacleDef> kObstacleSection{
    .name = "obstacle",
    .noun = "obstacle",
    .fields = kObstacleFields,
    .kind_of = [](const ObstacleDef& obstacle) { return static_cast<int>(obstacle.kind); },
    .kind_names = kNameList<kObstacleKindNames>,
    .init =
        [](ObstacleDef& obstacle, const ReadContext& context) {
          obstacle.name = "obstacle" + std::to_string(context.index);
        },
    // A crate for the studio's "add": 1 m, resting on a floor at z = 0.
    .new_item = R"({"kind": "box", "center": [0, 0, 0.5], "half_extents": [0.5, 0.5, 0.5]})"};

bool obstacle_has_key(ObstacleKind kind, std::string_view key) {
  for (const Field<ObstacleDef>& field : kObstacleFields) {
    if (field.format.key == key) return (field.format.kinds & kind_bit(kind)) != 0;
  }
  return false;
}

}  // namespace pbm
