// Scene files: parsing with defaults and normalization, exact round trips through scene_to_json and
// save_scene, one error per kind of bad input with its exact JSON path, and the schema and README
// agreeing with the parser.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "deform/reference_shape.h"
#include "scene/scene_json.h"

namespace pbm {
namespace {

using nlohmann::json;

const std::string kFile = "test.json";

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every section and both forms of every choice (named and array q_s, node and material point,
// plane and box), with values chosen so that defaults and normalization are visible.
json full_scene() {
  return json::parse(R"({
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
    ]
  })");
}

TEST(SceneJson, FullSceneParsesWithValuesDefaultsAndNormalization) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  EXPECT_EQ(s.file, kFile);
  EXPECT_EQ(s.name, "jello-ball");
  EXPECT_EQ(s.gravity, Vec3(0, 0, -9.81));
  EXPECT_EQ(s.solver.dt, 0.031);
  EXPECT_EQ(s.solver.integrator, IntegratorKind::rk45);
  EXPECT_EQ(s.solver.fps, 24);
  EXPECT_EQ(s.solver.body_elasticity, 250);
  EXPECT_EQ(s.solver.body_friction, 0.7);
  EXPECT_TRUE(s.solver.contact_step_reduction);
  EXPECT_EQ(s.solver.max_retries, 6);
  EXPECT_EQ(s.solver.energy_growth_bound, 2);

  ASSERT_EQ(s.bodies.size(), 2u);
  const BodyDef& jello = s.bodies[0];
  EXPECT_EQ(jello.name, "jello");
  EXPECT_EQ(jello.level, DeformLevel::global);
  EXPECT_EQ(jello.order, DynamicsOrder::first);
  EXPECT_EQ(jello.shape, ShapeKind::taper_bend);
  // Named q_s: a0 (index 0), eps1 (4) and t1 (6) of (2.11) are set, the rest keep the defaults.
  VecX q_s = default_shape_parameters(ShapeKind::taper_bend);
  q_s[0] = 2.0;
  q_s[4] = 0.5;
  q_s[6] = 0.3;
  ASSERT_EQ(jello.q_s.size(), 11);
  EXPECT_EQ(jello.q_s, q_s);
  // rest: names not given take q_s, not the kind's defaults.
  VecX q_s0 = q_s;
  q_s0[6] = 0.1;
  EXPECT_EQ(jello.q_s0, q_s0);
  EXPECT_EQ(jello.k_s, (VecX::LinSpaced(11, 1, 11)));
  EXPECT_EQ(jello.position, Vec3(1, 2, 3));
  EXPECT_EQ(jello.orientation, Vec4(1, 0, 0, 0));  // [2,0,0,0] / 2
  EXPECT_EQ(jello.tessellation.kind, TessellationKind::quads);
  EXPECT_EQ(jello.tessellation.rings, 4);
  EXPECT_EQ(jello.tessellation.segments, 5);
  EXPECT_EQ(jello.material.nodal_mass, 0.25);
  EXPECT_EQ(jello.material.mass, 0);
  EXPECT_EQ(jello.material.w1, 5);
  EXPECT_EQ(jello.material.color, Vec3(1, 0.5, 0));

  const BodyDef& plain = s.bodies[1];
  EXPECT_EQ(plain.name, "body1");
  EXPECT_EQ(plain.level, DeformLevel::local);
  EXPECT_EQ(plain.order, DynamicsOrder::second);
  EXPECT_EQ(plain.shape, ShapeKind::superquadric);
  EXPECT_EQ(plain.q_s, default_shape_parameters(ShapeKind::superquadric));
  EXPECT_EQ(plain.q_s0, plain.q_s);
  EXPECT_EQ(plain.k_s, VecX::Zero(6));
  // [1,1,0,0] / sqrt(2): unit length, direction kept.
  EXPECT_NEAR(plain.orientation.norm(), 1.0, 1e-15);
  EXPECT_NEAR(plain.orientation[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(plain.orientation[1], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(plain.tessellation.kind, TessellationKind::triangles);
  EXPECT_EQ(plain.tessellation.rings, 16);
  EXPECT_EQ(plain.material.mass, 3);
  EXPECT_EQ(plain.material.nodal_mass, 0);
  EXPECT_EQ(plain.material.w0, 20.0);
  EXPECT_EQ(plain.material.damping, 1.4);

  ASSERT_EQ(s.obstacles.size(), 3u);
  const ObstacleDef& floor = s.obstacles[0];
  EXPECT_EQ(floor.kind, ObstacleKind::plane);
  EXPECT_NEAR(floor.normal[0], 0.6, 1e-15);  // (3, 4, 0) / 5
  EXPECT_NEAR(floor.normal[1], 0.8, 1e-15);
  EXPECT_EQ(floor.normal[2], 0);
  EXPECT_EQ(floor.size, Vec2(5, 6));
  EXPECT_EQ(floor.friction, 1);
  EXPECT_EQ(floor.elasticity, 670);
  const ObstacleDef& box = s.obstacles[1];
  EXPECT_EQ(box.name, "obstacle1");
  EXPECT_EQ(box.kind, ObstacleKind::box);
  EXPECT_EQ(box.point, Vec3(1, 1, 1));  // "center" is stored in point
  EXPECT_EQ(box.half_extents, Vec3(0.5, 1, 2));
  EXPECT_EQ(box.orientation, Vec4(0, 0, 0, 1));
  EXPECT_EQ(box.elasticity, 0);
  const ObstacleDef& rock = s.obstacles[2];
  EXPECT_EQ(rock.kind, ObstacleKind::mesh);
  EXPECT_EQ(rock.file, "rock.obj");  // resolved against the scene's folder when the Model loads it
  EXPECT_EQ(rock.point, Vec3(2, 0, 0));
  EXPECT_NEAR(rock.orientation[0], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(rock.scale, 0.5);
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_EQ(s.camera->up, Vec3(0, 0, 1));  // normalized
  EXPECT_EQ(s.camera->fov, 35);
  EXPECT_EQ(s.bodies[0].material.roughness, 0.2);

  ASSERT_EQ(s.force_fields.size(), 2u);
  EXPECT_EQ(s.force_fields[0].kind, ForceFieldKind::force_per_node);
  EXPECT_EQ(s.force_fields[0].bodies, (std::vector<int>{0, 1}));  // "jello" resolved to 0
  EXPECT_EQ(s.force_fields[1].kind, ForceFieldKind::acceleration);
  EXPECT_TRUE(s.force_fields[1].bodies.empty());

  ASSERT_EQ(s.springs.size(), 2u);
  EXPECT_EQ(s.springs[0].body, 0);
  EXPECT_EQ(s.springs[0].node, 21);  // last node of 2 + 4 * 5 = 22
  EXPECT_FALSE(s.springs[0].material_point.has_value());
  EXPECT_EQ(s.springs[0].t_end, 4);
  EXPECT_EQ(s.springs[0].max_force, 30);
  EXPECT_EQ(s.springs[1].max_force, 1e300);
  EXPECT_EQ(s.springs[1].name, "spring1");
  EXPECT_EQ(s.springs[1].node, -1);
  ASSERT_TRUE(s.springs[1].material_point.has_value());
  EXPECT_EQ(*s.springs[1].material_point, Vec2(0.5, -1));
  EXPECT_EQ(s.springs[1].stiffness, 100);
  EXPECT_EQ(s.springs[1].t_end, 1e300);

  ASSERT_EQ(s.tracks.size(), 4u);
  EXPECT_EQ(s.tracks[0].target, "bodies[0].q_s0[6]");  // t1 is entry 6 of (2.11)
  EXPECT_EQ(s.tracks[0].interpolation, Interpolation::smooth);
  ASSERT_EQ(s.tracks[0].keys.size(), 2u);
  EXPECT_EQ(s.tracks[0].keys[1].time, 1);
  EXPECT_EQ(s.tracks[0].keys[1].value, 0.5);
  EXPECT_EQ(s.tracks[1].target, "gravity[2]");
  EXPECT_EQ(s.tracks[1].interpolation, Interpolation::linear);
  EXPECT_EQ(s.tracks[2].interpolation, Interpolation::step);
  EXPECT_EQ(s.tracks[3].target, "springs[1].stiffness");
}

TEST(SceneJson, GeneralShapeByNameAndTrackByName) {
  // The last of the 39 parameters of (2.27), addressed by whatever name reference_shape.h gives it.
  const int n_s = shape_parameter_count(ShapeKind::general);
  ASSERT_EQ(n_s, 39);
  const std::string last = shape_parameter_name(ShapeKind::general, n_s - 1);
  json j = {
      {"bodies",
       {{{"shape", {{"kind", "general"}, {"q_s", {{last, 0.5}}}}}, {"material", {{"mass", 1}}}}}},
      {"tracks", {{{"target", "bodies[0].q_s0." + last}, {"keys", {{0, 0.5}}}}}}};
  ASSERT_TRUE(check_shape_parameter(ShapeKind::general, n_s - 1, 0.5).empty());
  const Scene s = parse_scene(j.dump(), kFile);
  VecX q_s = default_shape_parameters(ShapeKind::general);
  q_s[n_s - 1] = 0.5;
  EXPECT_EQ(s.bodies[0].q_s, q_s);
  EXPECT_EQ(s.tracks[0].target, "bodies[0].q_s0[38]");
}

void expect_same_scene(const Scene& a, const Scene& b) {
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
    ASSERT_EQ(a.tracks[i].keys.size(), b.tracks[i].keys.size());
    for (std::size_t j = 0; j < a.tracks[i].keys.size(); ++j) {
      EXPECT_EQ(a.tracks[i].keys[j].time, b.tracks[i].keys[j].time);
      EXPECT_EQ(a.tracks[i].keys[j].value, b.tracks[i].keys[j].value);
    }
  }
}

TEST(SceneJson, RoundTripThroughSceneToJsonIsExact) {
  // 1/3 and 0.1 have no short decimal form: the writer must print round-trip precision.
  json j = full_scene();
  j["bodies"][0]["position"] = {1.0 / 3.0, 0.1, 2.0 / 7.0};
  j["bodies"][1]["orientation"] = {0.3, -0.2, 0.9, 0.1};
  const Scene s = parse_scene(j.dump(), kFile);
  const std::string text = scene_to_json(s);
  const Scene t = parse_scene(text, "again.json");
  expect_same_scene(s, t);
  EXPECT_EQ(t.file, "again.json");
  // The writer is a fixed point: writing the re-read scene gives the same text.
  EXPECT_EQ(scene_to_json(t), text);
  // Pretty: one key per line, 2-space indent.
  EXPECT_NE(text.find("\n  \"bodies\": ["), std::string::npos);
}

TEST(SceneJson, SaveWritesAtomicallyAndLoadReadsItBack) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pbm_scene_json_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "saved.json").string();
  const Scene s = parse_scene(full_scene().dump(), kFile);
  {
    std::ofstream old(path);
    old << "old contents";
  }
  save_scene(s, path);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Scene t = load_scene(path);
  EXPECT_EQ(t.file, path);
  expect_same_scene(s, t);
  // Saving into a directory that does not exist fails cleanly, naming the file.
  const std::string bad = (dir / "no_such_dir" / "x.json").string();
  try {
    save_scene(s, bad);
    ADD_FAILURE() << "expected pbm::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), bad);
  }
  std::filesystem::remove_all(dir);
}

// Parses `text`, expects pbm::Error at exactly `path`, with `message` in what().
void expect_text_error(const std::string& text, const std::string& path,
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

void expect_error(const json& j, const std::string& path, const std::string& message) {
  expect_text_error(j.dump(), path, message);
}

TEST(SceneJsonErrors, MalformedJsonReportsLineAndByte) {
  // The '}' that should be a value is the 14th character of line 3 and byte 2 + 15 + 14 = 31.
  const std::string text = "{\n  \"name\": \"x\",\n  \"bodies\": [}]\n}\n";
  expect_text_error(text, "", "invalid JSON");
  expect_text_error(text, "", "line 3, column 14");
  expect_text_error(text, "", "byte 31");
  expect_text_error("", "", "invalid JSON");
  expect_text_error("[1, 2]", "", "must be an object");
}

TEST(SceneJsonErrors, UnknownKeysAtEveryLevel) {
  json j = full_scene();
  j["foo"] = 1;
  expect_error(j, "foo", "unknown key 'foo'");
  j = full_scene();
  j["bodies"][0]["material"]["foo"] = 1;
  expect_error(j, "bodies[0].material.foo", "unknown key 'foo'");
  j = full_scene();
  j["solver"]["camera"] = 1;
  expect_error(j, "solver.camera", "unknown key 'camera'");
  j = full_scene();
  j["tracks"][1]["speed"] = 1;
  expect_error(j, "tracks[1].speed", "unknown key 'speed'");
  j = full_scene();
  j["lights"] = json::object();  // not part of this format
  expect_error(j, "lights", "unknown key 'lights'");
  j = full_scene();
  j["camera"] = {{"position", {0, -10, 2}}, {"lens", 35}};
  expect_error(j, "camera.lens", "unknown key 'lens'");
}

TEST(SceneJsonErrors, CameraMustSeeSomething) {
  json j = full_scene();
  j["camera"] = {{"position", {0, -10, 2}}, {"target", {0, 0, 1}}, {"fov", 180}};
  expect_error(j, "camera.fov", "must be in (0, 180)");
  j["camera"] = {{"position", {0, 0, 5}}, {"target", {0, 0, 1}}};  // looking along up
  expect_error(j, "camera", "up must not be parallel");
  j["camera"] = {{"position", {1, 2, 3}}, {"target", {1, 2, 3}}};
  expect_error(j, "camera", "position and target must differ");
  j["camera"] = {{"position", {0, -10, 2}}, {"target", {0, 0, 1}}, {"fov", 50}};
  const Scene scene = parse_scene(j.dump(), kFile);
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_EQ(scene.camera->fov, 50);
  EXPECT_EQ(scene.camera->up, Vec3(0, 0, 1));
}

TEST(SceneJsonErrors, DuplicateKeyNamesItsPath) {
  expect_text_error(R"({"bodies": [{"material": {"mass": 1, "mass": 2}}]})",
                    "bodies[0].material.mass", "duplicate key 'mass'");
  expect_text_error(R"({"name": "a", "bodies": [{"material": {"mass": 1}}], "name": "b"})", "name",
                    "duplicate key");
}

TEST(SceneJsonErrors, RangesNameTheField) {
  json j = full_scene();
  j["solver"]["body_elasticity"] = -1;
  expect_error(j, "solver.body_elasticity", "must be >= 0");
  j = full_scene();
  j["bodies"][0]["material"].erase("nodal_mass");
  j["bodies"][0]["material"]["mass"] = -1;
  expect_error(j, "bodies[0].material.mass", "bodies[0].material.mass: must be > 0");
  j = full_scene();
  j["bodies"][0]["material"]["nodal_mass"] = 0;
  expect_error(j, "bodies[0].material.nodal_mass", "must be > 0");
  j = full_scene();
  j["bodies"][0]["material"]["mass"] = 1;  // both masses
  expect_error(j, "bodies[0].material", "exactly one of 'mass'");
  j = full_scene();
  j["bodies"][1]["material"] = json::object();  // neither
  expect_error(j, "bodies[1].material", "exactly one of 'mass'");
  j = full_scene();
  j["bodies"][0]["material"]["w1"] = -0.5;
  expect_error(j, "bodies[0].material.w1", "bodies[0].material.w1: must be >= 0");
  j = full_scene();
  j["bodies"][0]["material"]["color"] = {0, 1.5, 0};
  expect_error(j, "bodies[0].material.color[1]", "must be in [0, 1]");
  j = full_scene();
  j["obstacles"][0]["friction"] = 1.5;
  expect_error(j, "obstacles[0].friction", "must be in [0, 1]");
  j = full_scene();
  j["obstacles"][1]["elasticity"] = -1;
  expect_error(j, "obstacles[1].elasticity", "must be >= 0");
  j = full_scene();
  j["obstacles"][1]["half_extents"] = {1, 0, 1};
  expect_error(j, "obstacles[1].half_extents[1]", "must be > 0");
  j = full_scene();
  j["solver"]["dt"] = 0;
  expect_error(j, "solver.dt", "must be > 0");
  j = full_scene();
  j["solver"]["contact_dt_factor"] = 0;
  expect_error(j, "solver.contact_dt_factor", "must be in (0, 1]");
  j = full_scene();
  j["solver"]["contact_dt_factor"] = 1;  // upper bound is allowed...
  EXPECT_NO_THROW(parse_scene(j.dump(), kFile));
  j["solver"]["contact_dt_factor"] = 1.0000001;  // ...just above it is not
  expect_error(j, "solver.contact_dt_factor", "must be in (0, 1]");
  j = full_scene();
  j["solver"]["max_retries"] = 21;
  expect_error(j, "solver.max_retries", "must be in [0, 20]");
  j = full_scene();
  j["bodies"][0]["tessellation"]["rings"] = 1;
  expect_error(j, "bodies[0].tessellation.rings", "must be >= 2");
  j = full_scene();
  j["bodies"][0]["tessellation"]["segments"] = 2;
  expect_error(j, "bodies[0].tessellation.segments", "must be >= 3");
  j = full_scene();
  j["bodies"][0]["tessellation"]["rings"] = 1001;
  j["bodies"][0]["tessellation"]["segments"] = 1000;
  expect_error(j, "bodies[0].tessellation", "rings * segments must be <= 1000000");
  j = full_scene();
  j["bodies"][0]["shape"]["stiffness"][3] = -1;
  expect_error(j, "bodies[0].shape.stiffness[3]", "must be >= 0");
  j = full_scene();
  j["bodies"][0]["orientation"] = {0, 0, 0, 0};
  expect_error(j, "bodies[0].orientation", "must be a nonzero quaternion");
  j = full_scene();
  j["obstacles"][0]["normal"] = {0, 0, 0};
  expect_error(j, "obstacles[0].normal", "must be a nonzero vector");
  j = full_scene();
  j["springs"][0]["t_end"] = 0.5;  // before t_begin = 1
  expect_error(j, "springs[0].t_end", "must be >= t_begin");
  j = full_scene();
  j["springs"][0]["max_force"] = 0;
  expect_error(j, "springs[0].max_force", "must be > 0");
}

TEST(SceneJsonErrors, ShapeParametersCheckedByNameAndIndex) {
  json j = full_scene();
  j["bodies"][0]["shape"]["q_s"]["eps1"] = 0;
  expect_error(j, "bodies[0].shape.q_s.eps1", check_shape_parameter(ShapeKind::taper_bend, 4, 0.0));
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"] = {1, 1, 1, 1, -0.2, 1, 0, 0, 0, 0, 1};
  expect_error(j, "bodies[0].shape.q_s[4]", "bodies[0].shape.q_s[4]: must be > 0");
  j = full_scene();
  j["bodies"][0]["shape"]["rest"]["a0"] = -1;
  expect_error(j, "bodies[0].shape.rest.a0", "must be > 0");
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"]["eps3"] = 1;
  expect_error(j, "bodies[0].shape.q_s.eps3", "unknown shape parameter 'eps3'");
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"] = {1, 1, 1, 1, 1, 1};  // 6 entries for an 11-parameter shape
  expect_error(j, "bodies[0].shape.q_s", "must have 11 entries");
  j = full_scene();
  j["bodies"][0]["shape"]["kind"] = "superquadric";  // t1 is not a superquadric parameter
  expect_error(j, "bodies[0].shape.q_s.t1", "unknown shape parameter 't1'");
}

TEST(SceneJsonErrors, WrongTypes) {
  json j = full_scene();
  j["solver"]["dt"] = "fast";
  expect_error(j, "solver.dt", "must be a number");
  j["solver"]["dt"] = nullptr;
  expect_error(j, "solver.dt", "must be a number");
  j = full_scene();
  j["bodies"][0]["material"]["w0"] = true;
  expect_error(j, "bodies[0].material.w0", "must be a number");
  j = full_scene();
  j["bodies"][0]["tessellation"]["rings"] = 16.5;
  expect_error(j, "bodies[0].tessellation.rings", "must be an integer");
  j["bodies"][0]["tessellation"]["rings"] = 4.0;  // integral value written as a float is fine
  EXPECT_NO_THROW(parse_scene(j.dump(), kFile));
  j = full_scene();
  j["bodies"][0]["position"] = {1, 2};
  expect_error(j, "bodies[0].position", "must be an array of 3 numbers");
  j = full_scene();
  j["bodies"][0]["velocity"] = {1, "2", 3};
  expect_error(j, "bodies[0].velocity[1]", "must be a number");
  j = full_scene();
  j["bodies"][0]["orientation"] = {1, 0, 0};
  expect_error(j, "bodies[0].orientation", "must be an array of 4 numbers");
  j = full_scene();
  j["name"] = 5;
  expect_error(j, "name", "must be a string");
  j = full_scene();
  j["bodies"][0]["level"] = "soft";
  expect_error(j, "bodies[0].level", "must be one of \"rigid\", \"global\", \"local\"");
  j = full_scene();
  j["solver"]["contact_step_reduction"] = 1;
  expect_error(j, "solver.contact_step_reduction", "must be true or false");
  j = full_scene();
  j["bodies"] = json::object();
  expect_error(j, "bodies", "must be an array");
  j = full_scene();
  j["bodies"][0]["material"] = 1;
  expect_error(j, "bodies[0].material", "must be an object");
  j = full_scene();
  j["bodies"][0]["shape"]["q_s"] = "round";
  expect_error(j, "bodies[0].shape.q_s", "must be an array of 11 numbers or an object");
}

TEST(SceneJsonErrors, MissingRequiredParts) {
  expect_text_error(R"({"name": "empty"})", "bodies", "is required");
  expect_text_error(R"({"bodies": []})", "bodies", "at least one body");
  expect_text_error(R"({"bodies": [{}]})", "bodies[0].material", "is required");
  json j = full_scene();
  j["tracks"][0].erase("keys");
  expect_error(j, "tracks[0].keys", "is required");
  j = full_scene();
  j["springs"][0].erase("node");
  expect_error(j, "springs[0]", "exactly one of 'node' and 'material_point'");
}

TEST(SceneJsonErrors, TrackKeysMustIncreaseAndTargetsResolve) {
  json j = full_scene();
  j["tracks"][3]["keys"] = {{0, 1}, {0.5, 2}, {0.5, 3}};  // equal times are not increasing
  expect_error(j, "tracks[3].keys[2]", "must be greater than the previous key's time 0.5");
  j["tracks"][3]["keys"] = {{1, 1}, {0, 2}};
  expect_error(j, "tracks[3].keys[1]", "must be greater than");
  j["tracks"][3]["keys"] = json::array();
  expect_error(j, "tracks[3].keys", "at least one key");
  j["tracks"][3]["keys"] = {{1, 1, 1}};
  expect_error(j, "tracks[3].keys[0]", "[time, value] pair");
  j = full_scene();
  j["tracks"][0]["target"] = "bodies[2].q_s0[0]";  // only 2 bodies
  expect_error(j, "tracks[0].target", "body index 2 is out of range");
  j["tracks"][0]["target"] = "bodies[0].q_s0[11]";  // taper_bend has 11 parameters: 0..10
  expect_error(j, "tracks[0].target", "shape parameter index 11 is out of range");
  j["tracks"][0]["target"] = "bodies[0].q_s0[10]";
  EXPECT_NO_THROW(parse_scene(j.dump(), kFile));
  j["tracks"][0]["target"] = "bodies[0].q_s0.tau1";
  expect_error(j, "tracks[0].target", "unknown shape parameter 'tau1'");
  j["tracks"][0]["target"] = "gravity[3]";
  expect_error(j, "tracks[0].target", "out of range");
  j["tracks"][0]["target"] = "springs[2].stiffness";
  expect_error(j, "tracks[0].target", "spring index 2 is out of range");
  j["tracks"][0]["target"] = "bodies[0].position[0]";
  expect_error(j, "tracks[0].target", "unknown track target");
  j["tracks"][0]["target"] = "gravity[2]";  // tracks[1] already drives it
  expect_error(j, "tracks[1].target", "already driven by tracks[0]");
}

TEST(SceneJsonErrors, NodeIndexAndBodyReferences) {
  // Body 0 has 2 + 4 * 5 = 22 nodes: 21 is the last one (accepted in full_scene), 22 is out.
  json j = full_scene();
  j["springs"][0]["node"] = 22;
  expect_error(j, "springs[0].node", "node 22 is out of range: body 'jello' has 22 nodes");
  j["springs"][0]["node"] = -1;
  expect_error(j, "springs[0].node", "out of range");
  j = full_scene();
  j["springs"][1]["material_point"] = {2.0, 0};  // u beyond pi/2
  expect_error(j, "springs[1].material_point[0]", "must be in [");
  j = full_scene();
  j["springs"][0]["body"] = "pudding";
  expect_error(j, "springs[0].body", "unknown body 'pudding'");
  j = full_scene();
  j["force_fields"][0]["bodies"] = {0, 2};
  expect_error(j, "force_fields[0].bodies[1]", "body index 2 is out of range");
  j = full_scene();
  j["bodies"][1]["name"] = "jello";
  expect_error(j, "bodies[1].name", "duplicate body name 'jello'");
}

TEST(SceneJson, ConstraintsParseWithDefaultsAndOverrides) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  EXPECT_EQ(s.solver.constraint_alpha, 7);
  EXPECT_FALSE(s.solver.constraint_beta.has_value());
  EXPECT_EQ(s.solver.constraint_solver, ConstraintSolverKind::sparse);
  ASSERT_EQ(s.constraints.size(), 3u);
  EXPECT_EQ(s.constraints[0].a.body, 0);
  EXPECT_EQ(s.constraints[0].a.node, 3);
  EXPECT_EQ(s.constraints[0].b.material_point, Vec2(0.2, 0.3));
  EXPECT_EQ(s.constraints[0].alpha, 20.0);
  EXPECT_EQ(s.constraints[1].name, "constraint1");
  EXPECT_EQ(s.constraints[1].b.body, -1);
  EXPECT_EQ(s.constraints[1].b.world, Vec3(0, 0, 5));
  EXPECT_EQ(s.constraints[1].beta, 3.0);
  EXPECT_EQ(s.constraints[2].kind, ConstraintKind::hinge);
  EXPECT_EQ(s.constraints[2].axis, Vec3(0, 1, 0));
}

TEST(SceneJsonErrors, ConstraintsNameTheirPath) {
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"a", {{"body", "tail"}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a.body"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"body", 7}, {"node", 0}}}},
       "constraints[0].b.body"},
      {{{"a", {{"world", {0, 0, 0}}}}, {"b", {{"body", 0}, {"node", 0}}}},
       "constraints[0].a.world"},
      {{{"a", {{"body", 0}, {"node", 0}, {"point", {0, 0, 0}}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a"},
      {{{"a", {{"body", 0}, {"node", 999}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a.node"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}, {"body", 0}}}},
       "constraints[0].b.body"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}, {"axis", {0, 0, 1}}},
       "constraints[0].axis"},
      {{{"kind", "hinge"}, {"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}},
       "constraints[0].a"},
      {{{"a", {{"body", 0}, {"node", 0}}}, {"b", {{"world", {0, 0, 0}}}}, {"alpha", -1}},
       "constraints[0].alpha"},
      {{{"a", {{"body", 0}, {"node", 0}}}}, "constraints[0].b"},
  };
  for (const auto& [constraint, path] : cases) {
    json j = {{"bodies", {{{"name", "ball"}, {"material", {{"mass", 1}}}}}},
              {"constraints", {constraint}}};
    try {
      parse_scene(j.dump(), kFile);
      ADD_FAILURE() << "expected an error at " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.path(), path) << e.what();
      EXPECT_EQ(e.file(), kFile);
    }
  }
  json solver = {{"bodies", {{{"material", {{"mass", 1}}}}}},
                 {"solver", {{"constraint_solver", "cholesky"}}}};
  EXPECT_THROW(parse_scene(solver.dump(), kFile), Error);
}

TEST(SceneJsonErrors, ObstacleKeysMustMatchTheKind) {
  json j = full_scene();
  j["obstacles"][0]["half_extents"] = {1, 1, 1};
  expect_error(j, "obstacles[0].half_extents", "not valid for a plane obstacle");
  j = full_scene();
  j["obstacles"][1]["normal"] = {0, 0, 1};
  expect_error(j, "obstacles[1].normal", "not valid for a box obstacle");
}

TEST(SceneJsonErrors, MissingFileNamesTheFile) {
  try {
    load_scene(std::filesystem::temp_directory_path().string());
    ADD_FAILURE() << "expected pbm::Error for a directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos) << e.what();
  }
  const std::string path = "/nonexistent_pbm_dir/missing_scene_42.json";
  try {
    load_scene(path);
    ADD_FAILURE() << "expected pbm::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.path(), "");
    EXPECT_NE(std::string(e.what()).find("missing_scene_42.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cannot open file"), std::string::npos);
  }
}

// ---- schema and README
// ---------------------------------------------------------------------------

// A small validator for the subset of JSON Schema 2020-12 that scene.schema.json uses, enough to
// check that the schema accepts what the parser accepts and rejects unknown keys. Returns "" if
// `value` conforms, else the first problem with its path.
std::string validate(const json& schema, const json& root, const json& value,
                     const std::string& path) {
  if (schema.is_boolean()) return schema.get<bool>() ? "" : path + ": forbidden";
  if (schema.contains("$ref")) {
    const std::string ref = schema["$ref"];
    const std::string prefix = "#/$defs/";
    if (ref.rfind(prefix, 0) != 0) return path + ": unsupported $ref " + ref;
    const std::string problem =
        validate(root["$defs"][ref.substr(prefix.size())], root, value, path);
    if (!problem.empty()) return problem;
  }
  if (schema.contains("type")) {
    const std::string type = schema["type"];
    const bool ok =
        (type == "object" && value.is_object()) || (type == "array" && value.is_array()) ||
        (type == "string" && value.is_string()) || (type == "boolean" && value.is_boolean()) ||
        (type == "number" && value.is_number()) || (type == "integer" && value.is_number_integer());
    if (!ok) return path + ": not " + type;
  }
  if (schema.contains("enum")) {
    bool found = false;
    for (const json& option : schema["enum"]) found = found || option == value;
    if (!found) return path + ": not in enum";
  }
  if (schema.contains("const") && schema["const"] != value) return path + ": not const";
  if (value.is_number()) {
    const double x = value.get<double>();
    if (schema.contains("minimum") && x < schema["minimum"].get<double>()) return path + ": < min";
    if (schema.contains("maximum") && x > schema["maximum"].get<double>()) return path + ": > max";
    if (schema.contains("exclusiveMinimum") && x <= schema["exclusiveMinimum"].get<double>()) {
      return path + ": <= exclusive min";
    }
  }
  if (value.is_string()) {
    const std::string s = value;
    if (schema.contains("minLength") && s.size() < schema["minLength"].get<std::size_t>()) {
      return path + ": too short";
    }
    if (schema.contains("pattern") &&
        !std::regex_search(s, std::regex(schema["pattern"].get<std::string>()))) {
      return path + ": does not match pattern";
    }
  }
  if (value.is_array()) {
    if (schema.contains("minItems") && value.size() < schema["minItems"].get<std::size_t>()) {
      return path + ": too few items";
    }
    if (schema.contains("maxItems") && value.size() > schema["maxItems"].get<std::size_t>()) {
      return path + ": too many items";
    }
    if (schema.contains("items")) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string problem =
            validate(schema["items"], root, value[i], path + "[" + std::to_string(i) + "]");
        if (!problem.empty()) return problem;
      }
    }
  }
  if (value.is_object()) {
    if (schema.contains("required")) {
      for (const json& key : schema["required"]) {
        if (!value.contains(key.get<std::string>())) return path + ": missing " + key.dump();
      }
    }
    for (const auto& [key, member] : value.items()) {
      const std::string member_path = path.empty() ? key : path + "." + key;
      if (schema.contains("properties") && schema["properties"].contains(key)) {
        const std::string problem = validate(schema["properties"][key], root, member, member_path);
        if (!problem.empty()) return problem;
      } else if (schema.contains("additionalProperties")) {
        const std::string problem =
            validate(schema["additionalProperties"], root, member, member_path);
        if (!problem.empty()) return problem;
      }
    }
  }
  if (schema.contains("anyOf") || schema.contains("oneOf")) {
    const bool one = schema.contains("oneOf");
    int matches = 0;
    for (const json& option : schema[one ? "oneOf" : "anyOf"]) {
      matches += validate(option, root, value, path).empty() ? 1 : 0;
    }
    if (matches == 0 || (one && matches != 1)) return path + ": anyOf/oneOf not satisfied";
  }
  if (schema.contains("allOf")) {
    for (const json& part : schema["allOf"]) {
      const std::string problem = validate(part, root, value, path);
      if (!problem.empty()) return problem;
    }
  }
  if (schema.contains("not") && validate(schema["not"], root, value, path).empty()) {
    return path + ": matches 'not'";
  }
  if (schema.contains("if")) {
    const bool condition = validate(schema["if"], root, value, path).empty();
    const char* branch = condition ? "then" : "else";
    if (schema.contains(branch)) {
      const std::string problem = validate(schema[branch], root, value, path);
      if (!problem.empty()) return problem;
    }
  }
  return "";
}

json load_schema() {
  return json::parse(read_text(std::string(PBM_SOURCE_DIR) + "/scenes/scene.schema.json"));
}

TEST(SceneSchema, IsValidJsonListingExactlyTheTopLevelKeys) {
  json schema;
  ASSERT_NO_THROW(schema = load_schema());
  EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
  EXPECT_EQ(schema["type"], "object");
  EXPECT_EQ(schema["additionalProperties"], false);
  std::set<std::string> keys;
  for (const auto& [key, value] : schema["properties"].items()) keys.insert(key);
  EXPECT_EQ(keys,
            (std::set<std::string>{"name", "gravity", "solver", "bodies", "obstacles",
                                   "force_fields", "springs", "tracks", "constraints", "camera"}));
  EXPECT_EQ(schema["required"], json::array({"bodies"}));
  // Every object schema with named properties is closed, like the parser.
  for (const auto& [name, def] : schema["$defs"].items()) {
    if (def.contains("properties")) {
      EXPECT_EQ(def.value("additionalProperties", json(true)), false) << name;
    }
  }
}

TEST(SceneSchema, AcceptsWhatTheParserWritesAndRejectsWhatItRejects) {
  const json schema = load_schema();
  // Everything scene_to_json writes (every key of every section) must be in the schema.
  const json written = json::parse(scene_to_json(parse_scene(full_scene().dump(), kFile)));
  EXPECT_EQ(validate(schema, schema, written, ""), "");
  EXPECT_EQ(validate(schema, schema, full_scene(), ""), "");
  // The validator can fail: each of these is also rejected by parse_scene above.
  json bad = written;
  bad["bodies"][0]["material"]["foo"] = 1;
  EXPECT_EQ(validate(schema, schema, bad, ""), "bodies[0].material.foo: forbidden");
  bad = written;
  bad["lights"] = json::object();
  EXPECT_EQ(validate(schema, schema, bad, ""), "lights: forbidden");
  bad = written;
  bad["obstacles"][0]["half_extents"] = {1, 1, 1};  // box key on a plane
  EXPECT_EQ(validate(schema, schema, bad, ""), "obstacles[0].half_extents: forbidden");
  bad = written;
  bad["obstacles"][0]["friction"] = 1.5;
  EXPECT_EQ(validate(schema, schema, bad, ""), "obstacles[0].friction: > max");
  bad = written;
  bad["bodies"][0]["material"]["mass"] = 1;  // both masses
  EXPECT_EQ(validate(schema, schema, bad, ""), "bodies[0].material: anyOf/oneOf not satisfied");
  bad = written;
  bad["constraints"][0]["axis"] = {0, 0, 1};  // hinge key on a point constraint
  EXPECT_EQ(validate(schema, schema, bad, ""), "constraints[0]: anyOf/oneOf not satisfied");
  bad = written;
  bad["constraints"][1]["b"]["body"] = 0;  // world and body together
  EXPECT_EQ(validate(schema, schema, bad, ""), "constraints[1].b: anyOf/oneOf not satisfied");
  bad = written;
  bad["tracks"][0]["target"] = "bodies[0].position[0]";
  EXPECT_EQ(validate(schema, schema, bad, ""), "tracks[0].target: does not match pattern");
}

TEST(SceneReadme, FullExampleLoadsAndConformsToTheSchema) {
  const std::string readme = read_text(std::string(PBM_SOURCE_DIR) + "/scenes/README.md");
  const std::string open = "```json\n";
  const std::size_t begin = readme.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = readme.find("```", begin + open.size());
  ASSERT_NE(end, std::string::npos);
  const std::string example = readme.substr(begin + open.size(), end - begin - open.size());
  Scene s;
  ASSERT_NO_THROW(s = parse_scene(example, "README.md"));
  EXPECT_EQ(s.bodies.at(0).name, "jello");
  EXPECT_EQ(s.tracks.at(0).target, "bodies[0].q_s0[6]");
  const json schema = load_schema();
  EXPECT_EQ(validate(schema, schema, json::parse(example), ""), "");
  // The README documents every key the writer produces.
  const json written = json::parse(scene_to_json(s));
  std::set<std::string> keys;
  for (const json* object :
       {&written, &written["solver"], &written["bodies"][0], &written["bodies"][0]["shape"],
        &written["bodies"][0]["tessellation"], &written["bodies"][0]["material"],
        &written["obstacles"][0], &written["obstacles"][1], &written["force_fields"][0],
        &written["springs"][0], &written["tracks"][0]}) {
    for (const auto& [key, value] : object->items()) keys.insert(key);
  }
  for (const std::string& key : keys) {
    EXPECT_NE(readme.find("| `" + key + "` |"), std::string::npos) << key;
  }
}

}  // namespace
}  // namespace pbm
