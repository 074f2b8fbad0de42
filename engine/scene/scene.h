// Scene: the parsed, validated content of a scene file (scenes/README.md documents the format).
// Plain definitions with defaults (STYLE §10). sim/model.h compiles a Scene into a Model.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/types.h"

namespace pbm {

// What a body pays for (DESIGN §3): its DOF vector holds only these coordinates.
enum class DeformLevel { rigid, global, local };  // q_c,q_theta | + q_s | + q_s, q_d
// Reference shape s(u; q_s): superquadric (2.7, 6 params), taper+bend (2.10, 11 params),
// taper/bend/shear/twist along three axes T2(T1(T3(e))) (2.13-2.27, 39 params).
enum class ShapeKind { superquadric, taper_bend, general };
// Tessellation of (u,v): quads + pole triangles (fig. 4.1) or all triangles (fig. 4.2).
enum class TessellationKind { quads, triangles };
// Second-order Lagrangian model (3.13) for animation, first-order model (3.51) for shaping.
enum class DynamicsOrder { second, first };
enum class IntegratorKind { euler, rk4, rk45 };
enum class ObstacleKind { plane, box, mesh };
enum class ForceFieldKind { acceleration, force_per_node };
// step holds each key's value until the next key (recorded mouse drags).
enum class Interpolation { linear, smooth, step };
// A point-to-point constraint (7.21), or a hinge: two of them on an axis plus a rotational spring.
enum class ConstraintKind { point, hinge };
// How N f_c + r = 0 (7.33) is solved: dense LU, or a sparse LDL^T for loop-free systems.
enum class ConstraintSolverKind { dense, sparse };

// Number of q_s entries for each shape kind.
int shape_parameter_count(ShapeKind kind);

struct TessellationDef {
  TessellationKind kind = TessellationKind::triangles;
  int rings = 16;     // interior latitude rings between the poles (>= 2)
  int segments = 16;  // nodes around each ring (>= 3); nodes = 2 + rings * segments
};

struct MaterialDef {
  Real w0 = 20.0;             // membrane magnitude stiffness w00 (3.34), >= 0
  Real w1 = 15.0;             // membrane variation stiffness w10 = w01 (3.34), >= 0
  Real nodal_mass = 0;        // lumped mass per node [kg]; exactly one of nodal_mass, mass is > 0
  Real mass = 0;              // total mass [kg], spread by lumping (sec. 6.1)
  Real damping = 1.4;         // nu in D = nu M (sec. 6.1) [1/s], >= 0
  Vec3 color{0.8, 0.3, 0.3};  // base colour for the renderer, components in [0, 1]
  Real roughness = 0.5;       // renderer: 0 = mirror-like highlight, 1 = matte
};

struct BodyDef {
  std::string name;
  DeformLevel level = DeformLevel::local;
  DynamicsOrder order = DynamicsOrder::second;
  ShapeKind shape = ShapeKind::superquadric;
  VecX q_s;   // initial global parameters (size shape_parameter_count(shape)), (2.8)/(2.11)/(2.27)
  VecX q_s0;  // rest values of q_s (3.31); defaults to q_s
  VecX k_s;   // stiffness per global parameter (3.32), >= 0; defaults to 0
  Vec3 position = Vec3::Zero();          // q_c [m]
  Vec4 orientation{1, 0, 0, 0};          // q_theta quaternion (w, x, y, z), normalized on load
  Vec3 velocity = Vec3::Zero();          // c-dot [m/s], world frame
  Vec3 angular_velocity = Vec3::Zero();  // omega [rad/s], world frame
  TessellationDef tessellation;
  MaterialDef material;
};

struct ObstacleDef {
  std::string name;
  ObstacleKind kind = ObstacleKind::plane;
  Vec3 point = Vec3::Zero();     // plane: a point on it; box: its centre; mesh: its origin [m]
  Vec3 normal{0, 0, 1};          // plane: outward normal (normalized on load)
  Vec3 half_extents{1, 1, 1};    // box: half sizes along its axes [m], > 0
  Vec4 orientation{1, 0, 0, 0};  // box, mesh: quaternion (w, x, y, z)
  Vec2 size{20, 20};             // plane: drawn extent for the renderer [m]
  std::string file;              // mesh: any file assimp reads, relative to the scene file
  Real scale = 1;                // mesh: uniform scale of the file's coordinates, > 0
  Real elasticity = 670.0;       // a in f_n = a (f_i . n) n (5.11), >= 0
  Real friction = 0.3;           // beta_f in (5.12), in [0, 1]
};

struct ForceFieldDef {
  ForceFieldKind kind = ForceFieldKind::acceleration;
  Vec3 value = Vec3::Zero();  // acceleration [m/s^2] or force on each node [N]
  std::vector<int> bodies;    // indices into Scene::bodies; empty = every body
};

// A spring from a surface point of a body to a target point (sec. 6.4's mouse spring).
// The point is a node index, or material coordinates (u, v) resolved to the nearest node.
struct SpringDef {
  std::string name;
  int body = 0;
  int node = -1;                       // >= 0: node index
  std::optional<Vec2> material_point;  // (u, v) in radians when node < 0
  Vec3 target = Vec3::Zero();          // [m], world frame
  Real stiffness = 100.0;              // [N/m], >= 0
  Real damping = 1.0;                  // [N s/m], >= 0
  Real t_begin = 0.0;                  // active interval [s]
  Real t_end = 1e300;
  Real max_force = 1e300;  // [N], > 0: the force's magnitude is clamped to it
};

// One end of a constraint: a point of a body (a node, a material point (u, v) resolved to the
// nearest node like springs, or a point fixed in the body frame), or a fixed world anchor.
struct ConstraintEndDef {
  int body = -1;                       // index into Scene::bodies; < 0: the world anchor `world`
  int node = -1;                       // >= 0: node index
  std::optional<Vec2> material_point;  // (u, v) in radians
  std::optional<Vec3> point;           // body frame [m]
  Vec3 world = Vec3::Zero();           // world frame [m], when body < 0
};

// Holonomic constraint between two ends (7.1), stabilized by Baumgarte's (7.14).
struct ConstraintDef {
  std::string name;
  ConstraintKind kind = ConstraintKind::point;
  ConstraintEndDef a, b;      // a is always a body
  std::optional<Real> alpha;  // overrides solver.constraint_alpha [1/s], >= 0
  std::optional<Real> beta;   // overrides solver.constraint_beta [1/s], >= 0
  Vec3 axis{0, 1, 0};         // hinge: axis at the initial state, world frame (normalized on load)
  Real length = 0.2;          // hinge: distance between its two point constraints [m], > 0
  Real stiffness = 0;         // hinge: rotational spring [N m/rad], >= 0 (sec. 6.4's see-saw)
  Real rest_angle = 0;        // hinge: angle of a relative to b where the spring is slack [rad]
  Real damping = 0;           // hinge: rotational damper [N m s/rad], >= 0
};

struct Keyframe {
  Real time = 0;
  Real value = 0;
};

// A keyframed value. target is a scene path: "bodies[i].q_s0[k]", "gravity[k]",
// "springs[i].target[k]", "springs[i].stiffness".
struct TrackDef {
  std::string target;
  Interpolation interpolation = Interpolation::linear;
  std::vector<Keyframe> keys;  // strictly increasing times, at least one
};

struct SolverDef {
  Real dt = 0.001;  // substep [s], > 0
  IntegratorKind integrator = IntegratorKind::euler;
  Real tolerance = 1e-6;                // rk45 local error tolerance, > 0
  Real fps = 30.0;                      // frames per second of the timeline, > 0
  Real duration = 10.0;                 // default length of a run [s], > 0
  bool contact_step_reduction = false;  // end of sec. 5.2.2
  Real contact_dt_factor = 0.25;        // dt multiplier while in contact, (0, 1]
  int max_retries = 4;                  // stability guard: halvings per frame
  Real energy_growth_bound = 10.0;      // max (E_after / E_before) for one frame
  Real constraint_alpha = 10.0;         // Baumgarte alpha of (7.14) [1/s], >= 0
  std::optional<Real> constraint_beta;  // Baumgarte beta [1/s], >= 0; absent: = alpha (7.16)
  ConstraintSolverKind constraint_solver = ConstraintSolverKind::dense;
  // Collisions between bodies (sec. 5.2.2); parts joined by a constraint never collide.
  bool body_collisions = true;
  bool self_collision = false;   // a local body with itself (collide/self_collision.h)
  Real body_friction = 0.3;      // b_f of (5.13) between bodies, in [0, 1]
  Real body_elasticity = 0;      // a of (5.11) between bodies, >= 0; 0: inelastic impulses only
  Real collision_margin = 0.02;  // contact band [m], > 0
};

// Where the renderer looks from (position, target, up) and its vertical field of view. Scenes
// without one are framed automatically.
struct CameraDef {
  Vec3 position{6, -8, 4};
  Vec3 target = Vec3::Zero();
  Vec3 up{0, 0, 1};
  Real fov = 40;  // vertical field of view [degrees], in (0, 180)
};

struct Scene {
  std::string file;  // where it was loaded from (for messages)
  std::string name;
  Vec3 gravity{0, 0, -9.81};
  SolverDef solver;
  std::vector<BodyDef> bodies;
  std::vector<ObstacleDef> obstacles;
  std::vector<ForceFieldDef> force_fields;
  std::vector<SpringDef> springs;
  std::vector<TrackDef> tracks;
  std::vector<ConstraintDef> constraints;
  std::optional<CameraDef> camera;
};

}  // namespace pbm
