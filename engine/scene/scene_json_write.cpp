// Writing scene files: the inverse of parse_scene (scene_json.cpp). Every field is written, so a
// saved file shows all the knobs; keys follow scenes/README.md.
#include <filesystem>
#include <fstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "deform/reference_shape.h"
#include "scene/json_reader.h"
#include "scene/scene_enum_names.h"
#include "scene/scene_json.h"

namespace pbm {

namespace {

using Json = nlohmann::ordered_json;  // keeps keys in the documented order

// SpringDef's "active forever" end time; not worth writing out.
constexpr Real kDefaultSpringEnd = 1e300;

template <typename Vector>
Json to_array(const Vector& v) {
  Json array = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) array.push_back(v[i]);
  return array;
}

// q_s-like vectors by parameter name; an array if the size does not match the kind (the reader
// will then say so), nothing if empty (the reader's defaults apply).
void write_shape_vector(Json& shape, const char* key, ShapeKind kind, const VecX& values) {
  if (values.size() == 0) return;
  if (values.size() != shape_parameter_count(kind)) {
    shape[key] = to_array(values);
    return;
  }
  Json named = Json::object();
  for (int i = 0; i < values.size(); ++i) named[shape_parameter_name(kind, i)] = values[i];
  shape[key] = std::move(named);
}

Json write_body(const BodyDef& body) {
  Json shape;
  shape["kind"] = enum_name(body.shape, kShapeKindNames);
  write_shape_vector(shape, "q_s", body.shape, body.q_s);
  write_shape_vector(shape, "rest", body.shape, body.q_s0);
  write_shape_vector(shape, "stiffness", body.shape, body.k_s);

  Json material;
  material["w0"] = body.material.w0;
  material["w1"] = body.material.w1;
  if (body.material.mass > 0) {
    material["mass"] = body.material.mass;
  } else {
    material["nodal_mass"] = body.material.nodal_mass;
  }
  material["damping"] = body.material.damping;
  material["color"] = to_array(body.material.color);
  material["roughness"] = body.material.roughness;

  Json j;
  j["name"] = body.name;
  j["level"] = enum_name(body.level, kDeformLevelNames);
  j["order"] = enum_name(body.order, kDynamicsOrderNames);
  j["shape"] = std::move(shape);
  j["position"] = to_array(body.position);
  j["orientation"] = to_array(body.orientation);
  j["velocity"] = to_array(body.velocity);
  j["angular_velocity"] = to_array(body.angular_velocity);
  j["tessellation"] = {{"kind", enum_name(body.tessellation.kind, kTessellationKindNames)},
                       {"rings", body.tessellation.rings},
                       {"segments", body.tessellation.segments}};
  j["material"] = std::move(material);
  return j;
}

Json write_obstacle(const ObstacleDef& obstacle) {
  Json j;
  j["name"] = obstacle.name;
  j["kind"] = enum_name(obstacle.kind, kObstacleKindNames);
  if (obstacle.kind == ObstacleKind::plane) {
    j["point"] = to_array(obstacle.point);
    j["normal"] = to_array(obstacle.normal);
    j["size"] = to_array(obstacle.size);
  } else if (obstacle.kind == ObstacleKind::box) {
    j["center"] = to_array(obstacle.point);
    j["half_extents"] = to_array(obstacle.half_extents);
    j["orientation"] = to_array(obstacle.orientation);
  } else {
    j["file"] = obstacle.file;
    j["position"] = to_array(obstacle.point);
    j["orientation"] = to_array(obstacle.orientation);
    j["scale"] = obstacle.scale;
  }
  j["elasticity"] = obstacle.elasticity;
  j["friction"] = obstacle.friction;
  return j;
}

Json write_spring(const SpringDef& spring) {
  Json j;
  j["name"] = spring.name;
  j["body"] = spring.body;
  if (spring.node >= 0 || !spring.material_point) {
    j["node"] = spring.node;
  } else {
    j["material_point"] = to_array(*spring.material_point);
  }
  j["target"] = to_array(spring.target);
  j["stiffness"] = spring.stiffness;
  j["damping"] = spring.damping;
  j["t_begin"] = spring.t_begin;
  if (spring.t_end < kDefaultSpringEnd) j["t_end"] = spring.t_end;
  if (spring.max_force < kDefaultSpringEnd) j["max_force"] = spring.max_force;
  return j;
}

Json write_constraint_end(const ConstraintEndDef& end) {
  Json j;
  if (end.body < 0) {
    j["world"] = to_array(end.world);
    return j;
  }
  j["body"] = end.body;
  if (end.point) {
    j["point"] = to_array(*end.point);
  } else if (end.node >= 0 || !end.material_point) {
    j["node"] = end.node;
  } else {
    j["material_point"] = to_array(*end.material_point);
  }
  return j;
}

Json write_constraint(const ConstraintDef& c) {
  Json j;
  j["name"] = c.name;
  j["kind"] = enum_name(c.kind, kConstraintKindNames);
  j["a"] = write_constraint_end(c.a);
  j["b"] = write_constraint_end(c.b);
  if (c.alpha) j["alpha"] = *c.alpha;
  if (c.beta) j["beta"] = *c.beta;
  if (c.kind == ConstraintKind::hinge) {
    j["axis"] = to_array(c.axis);
    j["length"] = c.length;
    j["stiffness"] = c.stiffness;
    j["rest_angle"] = c.rest_angle;
    j["damping"] = c.damping;
  }
  return j;
}

Json write_solver(const SolverDef& solver) {
  Json j;
  j["dt"] = solver.dt;
  j["integrator"] = enum_name(solver.integrator, kIntegratorKindNames);
  j["tolerance"] = solver.tolerance;
  j["fps"] = solver.fps;
  j["duration"] = solver.duration;
  j["contact_step_reduction"] = solver.contact_step_reduction;
  j["contact_dt_factor"] = solver.contact_dt_factor;
  j["max_retries"] = solver.max_retries;
  j["energy_growth_bound"] = solver.energy_growth_bound;
  j["constraint_alpha"] = solver.constraint_alpha;
  if (solver.constraint_beta) j["constraint_beta"] = *solver.constraint_beta;
  j["constraint_solver"] = enum_name(solver.constraint_solver, kConstraintSolverKindNames);
  j["body_collisions"] = solver.body_collisions;
  j["self_collision"] = solver.self_collision;
  j["body_friction"] = solver.body_friction;
  j["body_elasticity"] = solver.body_elasticity;
  j["collision_margin"] = solver.collision_margin;
  return j;
}

}  // namespace

std::string scene_to_json(const Scene& scene) {
  Json j;
  j["name"] = scene.name;
  j["gravity"] = to_array(scene.gravity);
  j["solver"] = write_solver(scene.solver);
  if (scene.camera) {
    j["camera"] = {{"position", to_array(scene.camera->position)},
                   {"target", to_array(scene.camera->target)},
                   {"up", to_array(scene.camera->up)},
                   {"fov", scene.camera->fov}};
  }
  j["bodies"] = Json::array();
  for (const BodyDef& body : scene.bodies) j["bodies"].push_back(write_body(body));
  j["obstacles"] = Json::array();
  for (const ObstacleDef& obstacle : scene.obstacles) {
    j["obstacles"].push_back(write_obstacle(obstacle));
  }
  j["force_fields"] = Json::array();
  for (const ForceFieldDef& field : scene.force_fields) {
    j["force_fields"].push_back({{"kind", enum_name(field.kind, kForceFieldKindNames)},
                                 {"value", to_array(field.value)},
                                 {"bodies", field.bodies}});
  }
  j["springs"] = Json::array();
  for (const SpringDef& spring : scene.springs) j["springs"].push_back(write_spring(spring));
  j["tracks"] = Json::array();
  for (const TrackDef& track : scene.tracks) {
    Json keys = Json::array();
    for (const Keyframe& key : track.keys) keys.push_back({key.time, key.value});
    j["tracks"].push_back({{"target", track.target},
                           {"interpolation", enum_name(track.interpolation, kInterpolationNames)},
                           {"keys", std::move(keys)}});
  }
  j["constraints"] = Json::array();
  for (const ConstraintDef& c : scene.constraints) j["constraints"].push_back(write_constraint(c));
  return j.dump(2) + "\n";
}

void save_scene(const Scene& scene, const std::string& path) {
  const std::string text = scene_to_json(scene);
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path, "", "cannot write file '" + temporary + "'");
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(path, "", "cannot write file '" + temporary + "' (disk full?)");
    }
  }
  // rename() replaces the old file in one step on POSIX file systems.
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw Error(path, "", "cannot replace file: " + error.message());
  }
}

}  // namespace pbm
