#include "collide/obstacle_model.h"

#include <filesystem>

#include "core/error.h"
#include "core/quaternion.h"

namespace pbm {

ObstacleModel build_obstacle_model(const ObstacleDef& def, const std::string& file,
                                   const std::string& path) {
  ObstacleModel o;
  o.name = def.name;
  o.kind = def.kind;
  o.point = def.point;
  o.normal = def.normal.normalized();
  o.rotation = rotation_from_quaternion(def.orientation);
  o.half_extents = def.half_extents;
  o.size = def.size;
  o.elasticity = def.elasticity;
  o.friction = def.friction;
  if (def.kind == ObstacleKind::mesh) {
    std::filesystem::path mesh_path = def.file;
    if (mesh_path.is_relative() && !file.empty()) {
      mesh_path = std::filesystem::path(file).parent_path() / mesh_path;
    }
    try {
      o.mesh = load_mesh_obstacle(mesh_path.string(), o.rotation, def.point, def.scale);
    } catch (const std::exception& e) {
      throw Error(file, path + ".file",
                  "cannot use mesh '" + mesh_path.string() + "': " + e.what());
    }
  }
  return o;
}

}  // namespace pbm
