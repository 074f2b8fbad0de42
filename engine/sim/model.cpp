#include "sim/model.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>

#include "core/error.h"
#include "deform/body_dynamics.h"
#include "deform/reference_shape.h"
#include "sim/state.h"

namespace pbm {
namespace {

std::string body_path(int b) {
  return "bodies[" + std::to_string(b) + "]";
}

// Where obstacles push a local body (collide/rigid_contact.h): material points in each surface
// triangle (three: barycentric 2/3, 1/6, 1/6, Strang-Fix's degree-2 rule), each with its share of
// the triangle's area on the initial shape times the book's stiffness per area, sum K_ii / area.
// Nodes alone would carry a K_ii each: densest where the (u, v) grid crowds (the poles), and few
// enough in a contact patch that a resting ball's depth would change as one enters or leaves.
// The points lie on the exact surface s(u, v): on the flat triangles, the equator's larger
// chords would sit deeper than the poles' and a ball would roll toward its deepest orientation.
void build_contact_samples(BodyModel& body) {
  const Tessellation& t = body.tessellation;
  body.contact_samples.clear();
  body.contact_samples.reserve(kContactSamplesPerTriangle * t.triangles.size());
  body.contact_triangle_reach.clear();
  body.sample_grid_u.clear();
  body.sample_grid_v.clear();
  std::map<Real, int> u_index, v_index;  // the samples' distinct latitudes and longitudes
  Real total_area = 0, gap = 0;
  for (const std::array<int, 3>& tri : t.triangles) {
    const Vec3& p0 = body.s_fixed[tri[0]];
    const Real area = 0.5 * (body.s_fixed[tri[1]] - p0).cross(body.s_fixed[tri[2]] - p0).norm();
    total_area += area;
    Real reach = 0;
    // v of a pole is arbitrary: the point's v comes from the triangle's other nodes, unwrapped
    // across the seam.
    Real v_ref = 0;
    for (int k = 0; k < 3; ++k) {
      if (tri[k] != t.south_pole && tri[k] != t.north_pole) v_ref = t.uv[tri[k]].y();
    }
    for (int k = 0; k < kContactSamplesPerTriangle; ++k) {
      ContactSample sample;
      sample.nodes = tri;
      if (kContactSamplesPerTriangle == 1) {
        sample.weights.setConstant(1.0 / 3.0);
      } else {
        sample.weights.setConstant(1.0 / 6.0);
        sample.weights[k] = 2.0 / 3.0;
      }
      sample.stiffness = area / kContactSamplesPerTriangle;
      Real u = 0, v = 0, v_weight = 0;
      Vec3 blended = Vec3::Zero();
      for (int m = 0; m < 3; ++m) {
        const Vec2& uv = t.uv[tri[m]];
        u += sample.weights[m] * uv.x();
        blended += sample.weights[m] * body.s_fixed[tri[m]];
        if (tri[m] == t.south_pole || tri[m] == t.north_pole) continue;
        const Real unwrapped = v_ref + std::remainder(uv.y() - v_ref, 2 * std::numbers::pi);
        v += sample.weights[m] * unwrapped;
        v_weight += sample.weights[m];
      }
      v = std::remainder(v / v_weight, 2 * std::numbers::pi);
      sample.angles = superquadric_angles(u, v);
      auto [u_it, u_new] = u_index.emplace(u, static_cast<int>(body.sample_grid_u.size()));
      if (u_new) body.sample_grid_u.push_back(superquadric_angles(u, 0.0));
      auto [v_it, v_new] = v_index.emplace(v, static_cast<int>(body.sample_grid_v.size()));
      if (v_new) body.sample_grid_v.push_back(superquadric_angles(0.0, v));
      sample.grid = {u_it->second, v_it->second};
      Vec3 exact;
      evaluate_reference_shape(body.shape, body.q_s_fixed, sample.angles, 1.0, exact, nullptr);
      gap = std::max(gap, (exact - blended).norm());
      for (int m = 0; m < 3; ++m) reach = std::max(reach, (exact - body.s_fixed[tri[m]]).norm());
      body.contact_samples.push_back(sample);
    }
    body.contact_triangle_reach.push_back(reach);
  }
  const Real per_area = membrane_stiffness_diagonal(t, body.stiffness).sum() / total_area;
  for (ContactSample& sample : body.contact_samples) sample.stiffness *= per_area;
  body.contact_sample_gap = gap;
}

BodyModel build_body(const Scene& scene, int b) {
  const BodyDef& def = scene.bodies[b];
  BodyModel body;
  body.name = def.name;
  body.level = def.level;
  body.order = def.order;
  body.shape = def.shape;
  body.n_shape = shape_parameter_count(def.shape);
  body.n_s = def.level == DeformLevel::rigid ? 0 : body.n_shape;
  body.has_local = def.level == DeformLevel::local;
  body.tessellation = tessellate(def.tessellation);
  const int n = body.tessellation.node_count();
  const Real nodal_mass =
      def.material.nodal_mass > 0 ? def.material.nodal_mass : def.material.mass / n;
  if (!(nodal_mass > 0) || !std::isfinite(nodal_mass)) {
    throw Error(scene.file, body_path(b) + ".material", "needs nodal_mass > 0 or mass > 0");
  }
  body.node_mass = VecX::Constant(n, nodal_mass);
  body.mass = nodal_mass * n;
  body.damping = def.material.damping;
  if (def.order == DynamicsOrder::first && !(body.damping > 0)) {
    throw Error(scene.file, body_path(b) + ".material.damping",
                "must be > 0 for a first-order body (3.51 divides by D)");
  }
  body.w0 = def.material.w0;
  body.w1 = def.material.w1;
  body.color = def.material.color;
  body.q_s_fixed = def.q_s.size() ? def.q_s : default_shape_parameters(def.shape);
  body.q_s0 = def.q_s0.size() ? def.q_s0 : body.q_s_fixed;
  body.k_s = def.k_s.size() ? def.k_s : VecX::Zero(body.n_shape);
  if (body.has_local) {
    body.stiffness = build_membrane_stiffness(body.tessellation, body.w0, body.w1);
  }
  // Reference shape at the initial parameters: the shape of a rigid body.
  body.s_fixed.resize(n);
  body.node_angles.resize(n);
  {
    std::map<Real, int> u_index, v_index;
    body.node_grid.resize(n);
    for (int i = 0; i < n; ++i) {
      const Vec2& uv = body.tessellation.uv[i];
      auto [u_it, u_new] = u_index.emplace(uv.x(), static_cast<int>(body.grid_u.size()));
      if (u_new) body.grid_u.push_back(superquadric_angles(uv.x(), 0.0));
      auto [v_it, v_new] = v_index.emplace(uv.y(), static_cast<int>(body.grid_v.size()));
      if (v_new) body.grid_v.push_back(superquadric_angles(0.0, uv.y()));
      body.node_grid[i] = {u_it->second, v_it->second};
    }
  }
  for (int i = 0; i < n; ++i) {
    const Vec2& uv = body.tessellation.uv[i];
    body.node_angles[i] = superquadric_angles(uv.x(), uv.y());
    evaluate_reference_shape(def.shape, body.q_s_fixed, body.node_angles[i], 1.0, body.s_fixed[i],
                             nullptr);
  }
  if (body.has_local) build_contact_samples(body);
  // Inertia of the gauge direction n (deform/body_dynamics.h): omega = sqrt(n^T K_ss n / eta)
  // at most 1 / (4 dt), and at least 1% of the mass times a0^2 so it is never negligible.
  // Parameters whose mass vanishes at some shapes (a bend's location and range weigh nothing
  // while its amount is 0) get the floor eta_i = k_i dt^2, so omega_i dt <= 1 everywhere.
  body.parameter_inertia_floor = body.k_s.head(body.n_s) * scene.solver.dt * scene.solver.dt;
  if (body.n_s >= 4) {
    const VecX n_gauge = gauge_direction(body.q_s_fixed);
    const Real k_gauge = n_gauge.dot(body.k_s.cwiseProduct(n_gauge));
    const Real dt = scene.solver.dt;
    body.parameter_inertia = std::max(16.0 * k_gauge * dt * dt,
                                      1e-2 * body.mass * body.q_s_fixed[0] * body.q_s_fixed[0]);
  }
  if (body.level != DeformLevel::rigid) body.s_fixed.clear();
  body.q_size = 7 + body.n_s + (body.has_local ? 3 * n : 0);
  body.v_size = 6 + body.n_s + (body.has_local ? 3 * n : 0);
  return body;
}

ObstacleModel build_obstacle(const Scene& scene, std::size_t index) {
  const ObstacleDef& def = scene.obstacles[index];
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
    std::filesystem::path path = def.file;
    if (path.is_relative() && !scene.file.empty()) {
      path = std::filesystem::path(scene.file).parent_path() / path;
    }
    try {
      o.mesh = load_mesh_obstacle(path.string(), o.rotation, def.point, def.scale);
    } catch (const std::exception& e) {
      throw Error(scene.file, "obstacles[" + std::to_string(index) + "].file",
                  "cannot use mesh '" + path.string() + "': " + e.what());
    }
  }
  return o;
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

int nearest_node(const Tessellation& t, const Vec2& uv) {
  int best = 0;
  Real best_d = 1e300;
  for (int i = 0; i < t.node_count(); ++i) {
    Real du = t.uv[i].x() - uv.x();
    Real dv = std::remainder(t.uv[i].y() - uv.y(), 2 * std::numbers::pi);
    // At the poles v is arbitrary (fig. 4.1): only u counts there.
    if (i == t.south_pole || i == t.north_pole) dv = 0;
    const Real d = du * du + dv * dv * std::cos(uv.x()) * std::cos(uv.x());
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

Model build_model(const Scene& scene) {
  Model model;
  model.scene = scene;
  model.gravity = scene.gravity;
  model.solver = scene.solver;
  if (scene.bodies.empty()) throw Error(scene.file, "bodies", "needs at least one body");
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
    BodyModel body = build_body(scene, b);
    body.q_offset = model.n_q;
    body.v_offset = model.n_v;
    model.n_q += body.q_size;
    model.n_v += body.v_size;
    model.bodies.push_back(std::move(body));
  }
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
    model.obstacles.push_back(build_obstacle(scene, o));
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
  model.constraints = build_constraints(scene, model.bodies);
  model.body_collisions.enabled = scene.solver.body_collisions;
  model.body_collisions.self_collision = scene.solver.self_collision;
  model.body_collisions.friction = scene.solver.body_friction;
  model.body_collisions.elasticity = scene.solver.body_elasticity;
  model.body_collisions.margin = scene.solver.collision_margin;
  return model;
}

}  // namespace pbm
