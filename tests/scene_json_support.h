// What the scene-file tests (tests/test_scene_*.cpp) share: a scene using every section and
// both forms of every choice, a field-by-field comparison of two scenes, and the check that
// parsing fails at an exact JSON path with a given message.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/scene_json.h"

namespace pbm::scene_test {

using nlohmann::json;

inline const std::string kFile = "test.json";

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every section and both forms of every choice (named and array q_s, node and material point,
// plane and box), with values chosen so that defaults and normalization are visible.
inline json full_scene() {
  json scene = json::parse(R"({
    "name": "jello-ball",
    "gravity": [0, 0, -9.81],
    "camera": {"position": [0, -10, 3], "target": [0, 0, 1], "up": [0, 0, 2], "fov": 35},
    "solver": {"dt": 0.031, "integrator": "rk45", "tolerance": 1e-5, "fps": 24, "duration": 3,
               "contact_step_reduction": true, "contact_dt_factor": 0.5, "max_retries": 6,
               "energy_growth_bound": 2, "constraint_alpha": 7, "constraint_solver": "sparse",
               "body_collisions": false, "self_collision": true, "body_friction": 0.7,
               "body_elasticity": 250, "collision_margin": 0.03},
    "bodies": [
      {"name": "jello", "level": "global", "order": "first",
       "shape": {"kind": "taper_bend", "q_s": {"a0": 2.0, "eps1": 0.5, "t1": 0.3},
                 "rest": {"t1": 0.1},
                 "stiffness": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11]},
       "position": [1, 2, 3], "orientation": [2, 0, 0, 0], "velocity": [0.5, 0, 0],
       "angular_velocity": [0, 0, 1],
       "tessellation": {"kind": "quads", "rings": 4, "segments": 5},
       "material": {"w0": 10, "w1": 5, "nodal_mass": 0.25, "damping": 0.7, "color": [1, 0.5, 0],
                    "roughness": 0.2}},
      {"orientation": [1, 1, 0, 0], "material": {"mass": 3}}
    ],
    "obstacles": [
      {"name": "floor", "normal": [3, 4, 0], "point": [0, 0, -1], "size": [5, 6], "friction": 1},
      {"kind": "box", "center": [1, 1, 1], "half_extents": [0.5, 1, 2],
       "orientation": [0, 0, 0, 3], "elasticity": 0},
      {"name": "rock", "kind": "mesh", "file": "rock.obj", "position": [2, 0, 0],
       "orientation": [1, 0, 0, 1], "scale": 0.5}
    ],
    "force_fields": [
      {"kind": "force_per_node", "value": [1, 0, 0], "bodies": ["jello", 1]},
      {"value": [0, 0.5, 0]}
    ],
    "springs": [
      {"name": "mouse", "body": "jello", "node": 21, "target": [0, 0, 5], "stiffness": 50,
       "damping": 2, "t_begin": 1, "t_end": 4, "max_force": 30},
      {"body": 1, "material_point": [0.5, -1], "target": [1, 1, 1]}
    ],
    "tracks": [
      {"target": "bodies[0].q_s0.t1", "interpolation": "smooth", "keys": [[0, 0], [1, 0.5]]},
      {"target": "gravity[2]", "keys": [[0, -9.81]]},
      {"target": "springs[0].target[1]", "interpolation": "step", "keys": [[0, 0], [2, 1]]},
      {"target": "springs[1].stiffness", "keys": [[0, 100], [0.5, 200], [1, 100]]}
    ],
    "constraints": [
      {"name": "neck", "a": {"body": "jello", "node": 3},
       "b": {"body": 1, "material_point": [0.2, 0.3]}, "alpha": 20},
      {"a": {"body": 1, "point": [0, 0, 1]}, "b": {"world": [0, 0, 5]}, "beta": 3},
      {"name": "pivot", "kind": "hinge", "a": {"body": 0, "point": [0, 0, 0]},
       "b": {"body": 1, "point": [1, 0, 0]}, "axis": [0, 2, 0], "length": 0.5, "stiffness": 40,
       "rest_angle": 0.1, "damping": 0.5}
    ],
    "figures": [
      {"name": "arm", "restitution": 0.3, "impact_speed": 0.2, "contact_stiffness": 5e4,
       "contact_damping": 50, "self_collisions": false, "figure_collisions": false,
       "body_collisions": false,
       "friction": 0.7, "non_colliding": [{"a": "upper", "b": "segment5"}], "segments": [
        {"name": "base", "joint": {"kind": "free", "position": [0, 0, 1],
                                   "q0": [0, 0, 1, 2, 0, 0, 0], "v0": [0, 0, 1, 0.5, 0, 0]},
         "shape": {"kind": "box", "size": [0.2, 0.1, 0.05]}, "mass": 2},
        {"name": "upper", "parent": "base",
         "joint": {"kind": "revolute", "axis": [0, 2, 0], "position": [0, 0, 0.05],
                   "damping": 0.1, "stiffness": 5, "rest": [0.1], "q0": [0.3], "v0": [1],
                   "lower": [-1], "upper": [1.5], "limit_restitution": 0.25},
         "shape": {"kind": "capsule", "size": [0.04, 0.04, 0.15], "center": [0, 0, 0.2]},
         "density": 900, "color": [0.2, 0.4, 0.6],
         "sites": [{"name": "elbow", "position": [0, 0, 0.4]},
                   {"position": [0, 0.04, 0.2], "orientation": [0, 1, 0, 0]}]},
        {"parent": "upper", "joint": {"kind": "spherical", "position": [0, 0, 0.4],
                                      "stiffness": 2, "rest": [1, 0, 0, 0],
                                      "q0": [2, 0, 0, 0], "swing_limit": 1.2, "twist_limit": 0.8,
                                      "limit_restitution": 0.5},
         "shape": {"kind": "sphere", "size": [0.05, 0.05, 0.05]}},
        {"parent": "upper", "joint": {"kind": "universal", "axis": [1, 0, 0],
                                      "axis2": [0, 0, 3], "q0": [0.1, 0.2]},
         "shape": {"kind": "cylinder", "size": [0.03, 0.03, 0.1], "orientation": [1, 1, 0, 0]}},
        {"parent": "base", "joint": {"kind": "prismatic", "axis": [1, 0, 0],
                                     "orientation": [0, 0, 0, 1]}},
        {"parent": "base", "joint": {"kind": "fixed", "position": [0.2, 0, 0]}}
      ],
       "controllers": [
        {"joint": "upper", "keys": [[0, 0.3], [1, 0.8]], "settling_time": 0.2, "alpha": 5,
         "beta": 1, "max_output": 40},
        {"kind": "pd", "joint": "segment3", "dof": 1, "interpolation": "linear",
         "keys": [[0, 0.2]], "kp": 30, "kd": 2},
        {"kind": "stable_pd", "joint": "segment4", "keys": [[0.5, 0.1], [2, -0.1]],
         "interpolation": "step", "kp": 1e5, "kd": 100}
      ],
       "site_actuators": [
        {"segment": "upper", "site": "elbow", "interpolation": "linear", "x": [[0, 0.1]],
         "y": [[0, 0], [1, 0.2]], "z": [[0, 1.5], [0.5, 1.4], [2, 1.6]], "stiffness": 300,
         "damping": 7, "max_force": 80},
        {"segment": "base", "x": [[0, 0]], "y": [[0, 0]], "z": [[0, 1]]}
      ],
       "impulses": [
        {"time": 0.5, "segment": "upper", "site": "elbow", "impulse": [1, -2, 3],
         "angular": [0.1, 0, 0], "frame": "site"},
        {"time": 0.25, "segment": "base", "impulse": [0, 0, 4]}
      ]}
    ],
    "liquids": [
      {"name": "tank", "domain": {"min": [-1, -0.5, 0], "max": [1, 0.5, 1.5]},
       "resolution": [8, 1, 6],
       "fluid": [{"box": {"min": [-1, -0.5, 0], "max": [0, 0.5, 1]}, "velocity": [0.1, 0, 0]}],
       "solids": [{"min": [0.5, -0.5, 0], "max": [1, 0.5, 0.25]}],
       "inflows": [{"box": {"min": [-1, -0.5, 1.25], "max": [-0.75, 0.5, 1.5]},
                    "velocity": [0.8, 0, 0], "markers_per_second": 500}],
       "outflows": [{"min": [0.75, -0.5, 1.25], "max": [1, 0.5, 1.5]}],
       "density": 900, "viscosity": 0.003, "drag": 1.2, "walls": "no_slip", "surface_pressure": 10,
       "advection": "book", "solver": "relaxation", "surface": "markers", "cfl": 0.3,
       "relaxation": 1.5, "tolerance": 1e-5, "relative_tolerance": 1e-3,
       "max_iterations": 300, "max_substeps": 50, "markers_per_axis": 3, "ghost_fluid": false,
       "volume_correction": 0.1},
      {"resolution": [4, 4, 4], "surface": "height_field", "solver": "mgpcg",
       "fluid": [{"box": {"min": [0, 0, 0], "max": [1, 1, 0.5]}}]}
    ]
  })");
  // Motion capture needs a real clip: the repository's, by its absolute path.
  scene["figures"][0]["mocap"] = {
      {"file", std::string(PBM_SOURCE_DIR) + "/scenes/mocap/wave.bvh"},
      {"scale", 0.02},
      {"position", {0.5, 0, 0}},
      {"orientation", {0.7071067811865476, 0.7071067811865476, 0, 0}},
      {"start", 0.25},
      {"sites", {{{"bvh", "LeftForeArm"}, {"segment", "upper"}, {"site", "elbow"}}}},
      {"controller", "mrac"},
      {"kp", 5},
      {"kd", 0.5},
      {"settling_time", 0.2},
      {"alpha", 3},
      {"beta", 1},
      {"max_output", 30},
      {"stiffness", 250},
      {"damping", 4},
      {"max_force", 60}};
  return scene;
}

inline void expect_same_keys(const std::vector<Keyframe>& a, const std::vector<Keyframe>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t j = 0; j < a.size(); ++j) {
    EXPECT_EQ(a[j].time, b[j].time);
    EXPECT_EQ(a[j].value, b[j].value);
  }
}

inline void expect_same_box(const LiquidBoxDef& a, const LiquidBoxDef& b) {
  EXPECT_EQ(a.min, b.min);
  EXPECT_EQ(a.max, b.max);
}

inline void expect_same_liquid(const LiquidDef& x, const LiquidDef& y) {
  EXPECT_EQ(x.name, y.name);
  expect_same_box(x.domain, y.domain);
  EXPECT_EQ(x.resolution, y.resolution);
  ASSERT_EQ(x.fluid.size(), y.fluid.size());
  for (std::size_t k = 0; k < x.fluid.size(); ++k) {
    expect_same_box(x.fluid[k].box, y.fluid[k].box);
    EXPECT_EQ(x.fluid[k].velocity, y.fluid[k].velocity);
  }
  ASSERT_EQ(x.solids.size(), y.solids.size());
  for (std::size_t k = 0; k < x.solids.size(); ++k) expect_same_box(x.solids[k], y.solids[k]);
  ASSERT_EQ(x.inflows.size(), y.inflows.size());
  for (std::size_t k = 0; k < x.inflows.size(); ++k) {
    expect_same_box(x.inflows[k].box, y.inflows[k].box);
    EXPECT_EQ(x.inflows[k].velocity, y.inflows[k].velocity);
    EXPECT_EQ(x.inflows[k].markers_per_second, y.inflows[k].markers_per_second);
  }
  ASSERT_EQ(x.outflows.size(), y.outflows.size());
  for (std::size_t k = 0; k < x.outflows.size(); ++k) {
    expect_same_box(x.outflows[k], y.outflows[k]);
  }
  EXPECT_EQ(x.density, y.density);
  EXPECT_EQ(x.viscosity, y.viscosity);
  EXPECT_EQ(x.drag, y.drag);
  EXPECT_EQ(x.walls, y.walls);
  EXPECT_EQ(x.surface_pressure, y.surface_pressure);
  EXPECT_EQ(x.advection, y.advection);
  EXPECT_EQ(x.solver, y.solver);
  EXPECT_EQ(x.surface, y.surface);
  EXPECT_EQ(x.cfl, y.cfl);
  EXPECT_EQ(x.relaxation, y.relaxation);
  EXPECT_EQ(x.tolerance, y.tolerance);
  EXPECT_EQ(x.relative_tolerance, y.relative_tolerance);
  EXPECT_EQ(x.max_iterations, y.max_iterations);
  EXPECT_EQ(x.max_substeps, y.max_substeps);
  EXPECT_EQ(x.markers_per_axis, y.markers_per_axis);
  EXPECT_EQ(x.ghost_fluid, y.ghost_fluid);
  EXPECT_EQ(x.volume_correction, y.volume_correction);
}

// Every field of a and b equal, bit for bit.
inline void expect_same_scene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.liquids.size(), b.liquids.size());
  for (std::size_t i = 0; i < a.liquids.size(); ++i) expect_same_liquid(a.liquids[i], b.liquids[i]);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.solver.dt, b.solver.dt);
  EXPECT_EQ(a.solver.integrator, b.solver.integrator);
  EXPECT_EQ(a.solver.tolerance, b.solver.tolerance);
  EXPECT_EQ(a.solver.fps, b.solver.fps);
  EXPECT_EQ(a.solver.duration, b.solver.duration);
  EXPECT_EQ(a.solver.contact_step_reduction, b.solver.contact_step_reduction);
  EXPECT_EQ(a.solver.contact_dt_factor, b.solver.contact_dt_factor);
  EXPECT_EQ(a.solver.max_retries, b.solver.max_retries);
  EXPECT_EQ(a.solver.energy_growth_bound, b.solver.energy_growth_bound);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyDef& x = a.bodies[i];
    const BodyDef& y = b.bodies[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.level, y.level);
    EXPECT_EQ(x.order, y.order);
    EXPECT_EQ(x.shape, y.shape);
    ASSERT_EQ(x.q_s.size(), y.q_s.size());
    ASSERT_EQ(x.q_s0.size(), y.q_s0.size());
    ASSERT_EQ(x.k_s.size(), y.k_s.size());
    EXPECT_EQ(x.q_s, y.q_s);
    EXPECT_EQ(x.q_s0, y.q_s0);
    EXPECT_EQ(x.k_s, y.k_s);
    EXPECT_EQ(x.position, y.position);
    EXPECT_EQ(x.orientation, y.orientation);  // bit-exact: no renormalization drift
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.angular_velocity, y.angular_velocity);
    EXPECT_EQ(x.tessellation.kind, y.tessellation.kind);
    EXPECT_EQ(x.tessellation.rings, y.tessellation.rings);
    EXPECT_EQ(x.tessellation.segments, y.tessellation.segments);
    EXPECT_EQ(x.material.w0, y.material.w0);
    EXPECT_EQ(x.material.w1, y.material.w1);
    EXPECT_EQ(x.material.nodal_mass, y.material.nodal_mass);
    EXPECT_EQ(x.material.mass, y.material.mass);
    EXPECT_EQ(x.material.damping, y.material.damping);
    EXPECT_EQ(x.material.color, y.material.color);
    EXPECT_EQ(x.material.roughness, y.material.roughness);
  }
  ASSERT_EQ(a.obstacles.size(), b.obstacles.size());
  for (std::size_t i = 0; i < a.obstacles.size(); ++i) {
    const ObstacleDef& x = a.obstacles[i];
    const ObstacleDef& y = b.obstacles[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.point, y.point);
    EXPECT_EQ(x.normal, y.normal);
    EXPECT_EQ(x.half_extents, y.half_extents);
    EXPECT_EQ(x.orientation, y.orientation);
    EXPECT_EQ(x.size, y.size);
    EXPECT_EQ(x.file, y.file);
    EXPECT_EQ(x.scale, y.scale);
    EXPECT_EQ(x.elasticity, y.elasticity);
    EXPECT_EQ(x.friction, y.friction);
  }
  ASSERT_EQ(a.camera.has_value(), b.camera.has_value());
  if (a.camera) {
    EXPECT_EQ(a.camera->position, b.camera->position);
    EXPECT_EQ(a.camera->target, b.camera->target);
    EXPECT_EQ(a.camera->up, b.camera->up);
    EXPECT_EQ(a.camera->fov, b.camera->fov);
  }
  ASSERT_EQ(a.force_fields.size(), b.force_fields.size());
  for (std::size_t i = 0; i < a.force_fields.size(); ++i) {
    EXPECT_EQ(a.force_fields[i].kind, b.force_fields[i].kind);
    EXPECT_EQ(a.force_fields[i].value, b.force_fields[i].value);
    EXPECT_EQ(a.force_fields[i].bodies, b.force_fields[i].bodies);
  }
  ASSERT_EQ(a.springs.size(), b.springs.size());
  for (std::size_t i = 0; i < a.springs.size(); ++i) {
    const SpringDef& x = a.springs[i];
    const SpringDef& y = b.springs[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.body, y.body);
    EXPECT_EQ(x.node, y.node);
    ASSERT_EQ(x.material_point.has_value(), y.material_point.has_value());
    if (x.material_point) {
      EXPECT_EQ(*x.material_point, *y.material_point);
    }
    EXPECT_EQ(x.target, y.target);
    EXPECT_EQ(x.stiffness, y.stiffness);
    EXPECT_EQ(x.damping, y.damping);
    EXPECT_EQ(x.t_begin, y.t_begin);
    EXPECT_EQ(x.t_end, y.t_end);
    EXPECT_EQ(x.max_force, y.max_force);
  }
  EXPECT_EQ(a.solver.constraint_alpha, b.solver.constraint_alpha);
  EXPECT_EQ(a.solver.constraint_beta, b.solver.constraint_beta);
  EXPECT_EQ(a.solver.constraint_solver, b.solver.constraint_solver);
  EXPECT_EQ(a.solver.body_collisions, b.solver.body_collisions);
  EXPECT_EQ(a.solver.self_collision, b.solver.self_collision);
  EXPECT_EQ(a.solver.body_friction, b.solver.body_friction);
  EXPECT_EQ(a.solver.body_elasticity, b.solver.body_elasticity);
  EXPECT_EQ(a.solver.collision_margin, b.solver.collision_margin);
  ASSERT_EQ(a.constraints.size(), b.constraints.size());
  for (std::size_t i = 0; i < a.constraints.size(); ++i) {
    const ConstraintDef& x = a.constraints[i];
    const ConstraintDef& y = b.constraints[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.kind, y.kind);
    for (const auto& [u, w] : {std::pair{&x.a, &y.a}, std::pair{&x.b, &y.b}}) {
      EXPECT_EQ(u->body, w->body);
      EXPECT_EQ(u->node, w->node);
      EXPECT_EQ(u->material_point, w->material_point);
      EXPECT_EQ(u->point, w->point);
      EXPECT_EQ(u->world, w->world);
    }
    EXPECT_EQ(x.alpha, y.alpha);
    EXPECT_EQ(x.beta, y.beta);
    EXPECT_EQ(x.axis, y.axis);
    EXPECT_EQ(x.length, y.length);
    EXPECT_EQ(x.stiffness, y.stiffness);
    EXPECT_EQ(x.rest_angle, y.rest_angle);
    EXPECT_EQ(x.damping, y.damping);
  }
  ASSERT_EQ(a.tracks.size(), b.tracks.size());
  for (std::size_t i = 0; i < a.tracks.size(); ++i) {
    EXPECT_EQ(a.tracks[i].target, b.tracks[i].target);
    EXPECT_EQ(a.tracks[i].interpolation, b.tracks[i].interpolation);
    expect_same_keys(a.tracks[i].keys, b.tracks[i].keys);
  }
  ASSERT_EQ(a.figures.size(), b.figures.size());
  for (std::size_t f = 0; f < a.figures.size(); ++f) {
    EXPECT_EQ(a.figures[f].name, b.figures[f].name);
    EXPECT_EQ(a.figures[f].restitution, b.figures[f].restitution);
    EXPECT_EQ(a.figures[f].impact_speed, b.figures[f].impact_speed);
    EXPECT_EQ(a.figures[f].contact_stiffness, b.figures[f].contact_stiffness);
    EXPECT_EQ(a.figures[f].contact_damping, b.figures[f].contact_damping);
    EXPECT_EQ(a.figures[f].self_collisions, b.figures[f].self_collisions);
    EXPECT_EQ(a.figures[f].figure_collisions, b.figures[f].figure_collisions);
    EXPECT_EQ(a.figures[f].body_collisions, b.figures[f].body_collisions);
    EXPECT_EQ(a.figures[f].friction, b.figures[f].friction);
    ASSERT_EQ(a.figures[f].non_colliding.size(), b.figures[f].non_colliding.size());
    for (std::size_t k = 0; k < a.figures[f].non_colliding.size(); ++k) {
      EXPECT_EQ(a.figures[f].non_colliding[k].a, b.figures[f].non_colliding[k].a);
      EXPECT_EQ(a.figures[f].non_colliding[k].b, b.figures[f].non_colliding[k].b);
    }
    ASSERT_EQ(a.figures[f].segments.size(), b.figures[f].segments.size());
    for (std::size_t i = 0; i < a.figures[f].segments.size(); ++i) {
      const SegmentDef& x = a.figures[f].segments[i];
      const SegmentDef& y = b.figures[f].segments[i];
      EXPECT_EQ(x.name, y.name);
      EXPECT_EQ(x.parent, y.parent);
      EXPECT_EQ(x.joint.kind, y.joint.kind);
      EXPECT_EQ(x.joint.axis, y.joint.axis);
      EXPECT_EQ(x.joint.axis2, y.joint.axis2);
      EXPECT_EQ(x.joint.position, y.joint.position);
      EXPECT_EQ(x.joint.orientation, y.joint.orientation);
      EXPECT_EQ(x.joint.damping, y.joint.damping);
      EXPECT_EQ(x.joint.stiffness, y.joint.stiffness);
      EXPECT_EQ(x.joint.rest, y.joint.rest);
      EXPECT_EQ(x.joint.lower, y.joint.lower);
      EXPECT_EQ(x.joint.upper, y.joint.upper);
      EXPECT_EQ(x.joint.limit_restitution, y.joint.limit_restitution);
      EXPECT_EQ(x.joint.swing_limit, y.joint.swing_limit);
      EXPECT_EQ(x.joint.twist_limit, y.joint.twist_limit);
      EXPECT_EQ(x.joint.q0, y.joint.q0);
      EXPECT_EQ(x.joint.v0, y.joint.v0);
      EXPECT_EQ(x.shape.kind, y.shape.kind);
      EXPECT_EQ(x.shape.size, y.shape.size);
      EXPECT_EQ(x.shape.center, y.shape.center);
      EXPECT_EQ(x.shape.orientation, y.shape.orientation);
      EXPECT_EQ(x.mass, y.mass);
      EXPECT_EQ(x.density, y.density);
      EXPECT_EQ(x.color, y.color);
      ASSERT_EQ(x.sites.size(), y.sites.size());
      for (std::size_t k = 0; k < x.sites.size(); ++k) {
        EXPECT_EQ(x.sites[k].name, y.sites[k].name);
        EXPECT_EQ(x.sites[k].position, y.sites[k].position);
        EXPECT_EQ(x.sites[k].orientation, y.sites[k].orientation);
      }
    }
    ASSERT_EQ(a.figures[f].controllers.size(), b.figures[f].controllers.size());
    for (std::size_t k = 0; k < a.figures[f].controllers.size(); ++k) {
      const ControllerDef& x = a.figures[f].controllers[k];
      const ControllerDef& y = b.figures[f].controllers[k];
      EXPECT_EQ(x.kind, y.kind);
      EXPECT_EQ(x.joint, y.joint);
      EXPECT_EQ(x.dof, y.dof);
      EXPECT_EQ(x.interpolation, y.interpolation);
      expect_same_keys(x.keys, y.keys);
      EXPECT_EQ(x.settling_time, y.settling_time);
      EXPECT_EQ(x.alpha, y.alpha);
      EXPECT_EQ(x.beta, y.beta);
      EXPECT_EQ(x.kp, y.kp);
      EXPECT_EQ(x.kd, y.kd);
      EXPECT_EQ(x.max_output, y.max_output);
    }
    ASSERT_EQ(a.figures[f].site_actuators.size(), b.figures[f].site_actuators.size());
    for (std::size_t k = 0; k < a.figures[f].site_actuators.size(); ++k) {
      const SiteActuatorDef& x = a.figures[f].site_actuators[k];
      const SiteActuatorDef& y = b.figures[f].site_actuators[k];
      EXPECT_EQ(x.segment, y.segment);
      EXPECT_EQ(x.site, y.site);
      EXPECT_EQ(x.interpolation, y.interpolation);
      expect_same_keys(x.x, y.x);
      expect_same_keys(x.y, y.y);
      expect_same_keys(x.z, y.z);
      EXPECT_EQ(x.stiffness, y.stiffness);
      EXPECT_EQ(x.damping, y.damping);
      EXPECT_EQ(x.max_force, y.max_force);
    }
    ASSERT_EQ(a.figures[f].mocap.has_value(), b.figures[f].mocap.has_value());
    if (a.figures[f].mocap) {
      const MocapDef& x = *a.figures[f].mocap;
      const MocapDef& y = *b.figures[f].mocap;
      EXPECT_EQ(x.file, y.file);
      EXPECT_EQ(x.scale, y.scale);
      EXPECT_EQ(x.position, y.position);
      EXPECT_EQ(x.orientation, y.orientation);
      EXPECT_EQ(x.start, y.start);
      ASSERT_EQ(x.joints.size(), y.joints.size());
      for (std::size_t k = 0; k < x.joints.size(); ++k) {
        EXPECT_EQ(x.joints[k].bvh, y.joints[k].bvh);
        EXPECT_EQ(x.joints[k].joint, y.joints[k].joint);
      }
      ASSERT_EQ(x.sites.size(), y.sites.size());
      for (std::size_t k = 0; k < x.sites.size(); ++k) {
        EXPECT_EQ(x.sites[k].bvh, y.sites[k].bvh);
        EXPECT_EQ(x.sites[k].segment, y.sites[k].segment);
        EXPECT_EQ(x.sites[k].site, y.sites[k].site);
      }
      EXPECT_EQ(x.controller, y.controller);
      EXPECT_EQ(x.kp, y.kp);
      EXPECT_EQ(x.kd, y.kd);
      EXPECT_EQ(x.settling_time, y.settling_time);
      EXPECT_EQ(x.alpha, y.alpha);
      EXPECT_EQ(x.beta, y.beta);
      EXPECT_EQ(x.max_output, y.max_output);
      EXPECT_EQ(x.stiffness, y.stiffness);
      EXPECT_EQ(x.damping, y.damping);
      EXPECT_EQ(x.max_force, y.max_force);
    }
    ASSERT_EQ(a.figures[f].impulses.size(), b.figures[f].impulses.size());
    for (std::size_t k = 0; k < a.figures[f].impulses.size(); ++k) {
      const ImpulseDef& x = a.figures[f].impulses[k];
      const ImpulseDef& y = b.figures[f].impulses[k];
      EXPECT_EQ(x.time, y.time);
      EXPECT_EQ(x.segment, y.segment);
      EXPECT_EQ(x.site, y.site);
      EXPECT_EQ(x.linear, y.linear);
      EXPECT_EQ(x.angular, y.angular);
      EXPECT_EQ(x.frame, y.frame);
    }
  }
}

// Parses `text`, expects pbm::Error at exactly `path`, with `message` in what().
inline void expect_text_error(const std::string& text, const std::string& path,
                              const std::string& message) {
  try {
    parse_scene(text, kFile);
    ADD_FAILURE() << "expected an error at '" << path << "'";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), kFile) << what;
    EXPECT_EQ(e.path(), path) << what;
    EXPECT_NE(what.find(kFile + ": "), std::string::npos) << what;
    if (!path.empty()) {
      EXPECT_NE(what.find(path + ": "), std::string::npos) << what;
    }
    EXPECT_NE(what.find(message), std::string::npos) << what << "\n  expected: " << message;
  }
}

inline void expect_error(const json& j, const std::string& path, const std::string& message) {
  expect_text_error(j.dump(), path, message);
}

}  // namespace pbm::scene_test
