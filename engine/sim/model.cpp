#include "sim/model.h"

#include <cstdio>

#include "core/error.h"

namespace pbm {
namespace {

std::string body_path(int b) {
  return "bodies[" + std::to_string(b) + "]";
}

TrackModel build_track(const Scene& scene, int t) {
  const TrackDef& def = scene.tracks[t];
  const std::string path = "tracks[" + std::to_string(t) + "].target";
  TrackModel track;
  track.interpolation = def.interpolation;
  track.keys = def.keys;
  int a = 0, k = 0;
  char tail = 0;
  const char* s = def.target.c_str();
  if (std::sscanf(s, "bodies[%d].q_s0[%d]%c", &a, &k, &tail) == 2) {
    track.target = TrackTarget::body_rest_parameter;
    if (a < 0 || a >= static_cast<int>(scene.bodies.size()) || k < 0 ||
        k >= shape_parameter_count(scene.bodies[a].shape)) {
      throw Error(scene.file, path, "no such body parameter '" + def.target + "'");
    }
  } else if (std::sscanf(s, "gravity[%d]%c", &k, &tail) == 1) {
    track.target = TrackTarget::gravity;
    if (k < 0 || k > 2) throw Error(scene.file, path, "gravity has components 0..2");
  } else if (std::sscanf(s, "springs[%d].target[%d]%c", &a, &k, &tail) == 2) {
    track.target = TrackTarget::spring_target;
    if (a < 0 || a >= static_cast<int>(scene.springs.size()) || k < 0 || k > 2) {
      throw Error(scene.file, path, "no such spring target '" + def.target + "'");
    }
  } else if (std::sscanf(s, "springs[%d].stiffness%c", &a, &tail) == 1) {
    track.target = TrackTarget::spring_stiffness;
    if (a < 0 || a >= static_cast<int>(scene.springs.size())) {
      throw Error(scene.file, path, "no such spring '" + def.target + "'");
    }
  } else if (std::sscanf(s, "camera.position[%d]%c", &k, &tail) == 1 && k >= 0 && k <= 2 &&
             scene.camera) {
    track.target = TrackTarget::camera_position;
  } else if (std::sscanf(s, "camera.target[%d]%c", &k, &tail) == 1 && k >= 0 && k <= 2 &&
             scene.camera) {
    track.target = TrackTarget::camera_target;
  } else if (def.target == "camera.fov" && scene.camera) {
    track.target = TrackTarget::camera_fov;
  } else if (std::sscanf(s, "obstacles[%d].point[%d]%c", &a, &k, &tail) == 2 ||
             std::sscanf(s, "obstacles[%d].rotation[%d]%c", &a, &k, &tail) == 2) {
    track.target = def.target.find(".point[") != std::string::npos ? TrackTarget::obstacle_point
                                                                   : TrackTarget::obstacle_rotation;
    if (a < 0 || a >= static_cast<int>(scene.obstacles.size()) || k < 0 || k > 2) {
      throw Error(scene.file, path, "no such obstacle component '" + def.target + "'");
    }
  } else {
    throw Error(scene.file, path, "unknown track target '" + def.target + "'");
  }
  track.object = a;
  track.index = k;
  if (track.keys.empty())
    throw Error(scene.file, "tracks[" + std::to_string(t) + "].keys",
                "needs at least one keyframe");
  return track;
}

}  // namespace

Model build_model(const Scene& scene) {
  Model model;
  model.scene = scene;
  model.gravity = scene.gravity;
  model.solver = scene.solver;
  if (scene.bodies.empty()) throw Error(scene.file, "bodies", "needs at least one body");
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
    BodyModel body = build_body_model(scene.bodies[b], scene.solver.dt, scene.file, body_path(b));
    body.q_offset = model.n_q;
    body.v_offset = model.n_v;
    model.n_q += body.q_size;
    model.n_v += body.v_size;
    model.bodies.push_back(std::move(body));
  }
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
    model.obstacles.push_back(build_obstacle_model(scene.obstacles[o], scene.file,
                                                   "obstacles[" + std::to_string(o) + "]"));
  }
  model.force_fields = scene.force_fields;
  for (int s = 0; s < static_cast<int>(scene.springs.size()); ++s) {
    const SpringDef& def = scene.springs[s];
    const std::string path = "springs[" + std::to_string(s) + "]";
    if (def.body < 0 || def.body >= static_cast<int>(model.bodies.size())) {
      throw Error(scene.file, path + ".body", "no such body");
    }
    const BodyModel& body = model.bodies[def.body];
    SpringModel spring;
    spring.name = def.name;
    spring.body = def.body;
    if (def.node >= 0) {
      if (def.node >= body.n_nodes()) throw Error(scene.file, path + ".node", "no such node");
      spring.node = def.node;
    } else if (def.material_point) {
      spring.node = nearest_node(body.tessellation, *def.material_point);
    } else {
      throw Error(scene.file, path, "needs node or material_point");
    }
    spring.target = def.target;
    spring.stiffness = def.stiffness;
    spring.damping = def.damping;
    spring.t_begin = def.t_begin;
    spring.t_end = def.t_end;
    spring.max_force = def.max_force;
    model.springs.push_back(spring);
  }
  for (int t = 0; t < static_cast<int>(scene.tracks.size()); ++t) {
    model.tracks.push_back(build_track(scene, t));
    const TrackModel& track = model.tracks.back();
    if (track.target == TrackTarget::obstacle_point ||
        track.target == TrackTarget::obstacle_rotation) {
      model.obstacles[track.object].moving = true;
    }
  }
  model.constraints = build_constraints(scene.constraints, scene.bodies, model.bodies,
                                        {.alpha = scene.solver.constraint_alpha,
                                         .beta = scene.solver.constraint_beta,
                                         .solver = scene.solver.constraint_solver,
                                         .integrator = scene.solver.integrator,
                                         .dt = scene.solver.dt},
                                        scene.file);
  BodyCollisionOptions& options = model.body_collisions.options;
  options.enabled = scene.solver.body_collisions;
  options.self_collision = scene.solver.self_collision;
  options.friction = scene.solver.body_friction;
  options.elasticity = scene.solver.body_elasticity;
  options.margin = scene.solver.collision_margin;
  for (const std::string& note : model.constraints.notes) {
    model.notes += (model.notes.empty() ? "" : "; ") + note;
  }
  model.body_collisions.constrained.assign(model.bodies.size(), 0);
  for (const PointConstraintModel& c : model.constraints.points) {
    const int a = c.ends[0].body, b = c.ends[1].body;
    if (a >= 0 && b >= 0) model.body_collisions.joined.push_back({a, b});
    for (const ConstraintPoint& end : c.ends) {
      if (end.body >= 0) model.body_collisions.constrained[end.body] = 1;
    }
  }
  model.snapshot_geometry = build_snapshot_geometry(model.bodies, model.obstacles);
  return model;
}

}  // namespace pbm
