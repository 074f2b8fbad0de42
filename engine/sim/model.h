// Model: everything constant while time runs (DESIGN §1), compiled once from a Scene.
// State layout: every body owns a slice of State::q and State::v (see BodyModel offsets).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "collide/body_collision_options.h"
#include "collide/mesh_obstacle.h"
#include "constrain/constraint_model.h"
#include "core/types.h"
#include "deform/membrane_stiffness.h"
#include "deform/superquadric.h"
#include "deform/tessellation.h"
#include "scene/scene.h"

namespace pbm {

// One deformable superquadric. Its DOF vector holds only what its level pays for:
//   q = (q_c (3), q_theta (4, quaternion w,x,y,z), q_s (n_s), q_d (3 n_nodes))       (3.5)
//   v = (c-dot (3, world), omega (3, BODY frame), q_s-dot (n_s), q_d-dot (3 n_nodes))
// The angular velocity, not theta-dot, is the rotational velocity coordinate: with the
// quaternion's 4 rates M_theta,theta = int mu B^T B is singular (G q_theta = 0), so the
// quaternion is integrated kinematically, q_theta-dot = 1/2 q_theta (x) (0, omega), and
// renormalized after every step (sec. 6.1).
// A material point of the global surface where obstacles push (5.11), inside a surface triangle:
// its (u, v), the triangle's nodes and its barycentric weights there (for a cheap first test and
// for velocities), and its share of the contact stiffness before the obstacle's a [N/m].
// Three points per surface triangle, not one: with the centroid alone a ball on the ground still
// creeps toward its deepest orientation (8e-3 m/s against 5e-4 m/s after 10 s).
inline constexpr int kContactSamplesPerTriangle = 3;

struct ContactSample {
  std::array<int, 3> nodes{};
  Vec3 weights = Vec3::Zero();
  SuperquadricAngles angles;
  std::array<int, 2> grid{};  // its latitude and longitude in BodyModel::sample_grid_u / _v
  Real stiffness = 0;
};

struct BodyModel {
  std::string name;
  DeformLevel level = DeformLevel::local;
  DynamicsOrder order = DynamicsOrder::second;
  ShapeKind shape = ShapeKind::superquadric;
  int n_s = 0;                   // global DOFs in the State (0 for rigid bodies)
  int n_shape = 0;               // shape_parameter_count(shape): size of q_s whether dynamic or not
  bool has_local = false;        // q_d present
  VecX q_s_fixed;                // shape of a rigid body (n_shape)
  VecX q_s0;                     // rest values (3.31), before tracks (n_shape)
  VecX k_s;                      // global stiffness diag (3.32) (n_shape)
  Real parameter_inertia = 0;    // eta of the gauge direction, see deform/body_dynamics.h
  VecX parameter_inertia_floor;  // eta_i = k_s,i dt^2 added to M_ss's diagonal (n_s)
  std::vector<Vec3> s_fixed;     // rigid bodies: reference shape at each node (constant)
  Tessellation tessellation;
  std::vector<SuperquadricAngles> node_angles;  // superquadric_angles(u_i, v_i) per node
  // The distinct latitudes and longitudes of the nodes (angles of (u, 0) and (0, v)) and, per
  // node, its pair of indices into them: see SignedPowers.
  std::vector<SuperquadricAngles> grid_u, grid_v;
  std::vector<std::array<int, 2>> node_grid;
  MembraneStiffness stiffness;                 // K_dd element matrices, local bodies only
  std::vector<ContactSample> contact_samples;  // local bodies, 3 per surface triangle, in order
  Real contact_sample_gap = 0;  // bound on |exact - blended| sample position on the initial shape
  // Per surface triangle: how far its samples lie from its nodes on the initial shape, at most.
  std::vector<Real> contact_triangle_reach;
  std::vector<SuperquadricAngles> sample_grid_u, sample_grid_v;  // distinct sample u and v
  Real w0 = 0, w1 = 0;
  VecX node_mass;    // lumped mass per node [kg] (sec. 6.1, footnote 2)
  Real mass = 0;     // sum of node_mass
  Real damping = 0;  // nu, D = nu M
  Vec3 color{0.8, 0.3, 0.3};
  int q_offset = 0, q_size = 0;  // slice of State::q
  int v_offset = 0, v_size = 0;  // slice of State::v
  int n_nodes() const { return static_cast<int>(node_mass.size()); }
  int n_generalized() const { return 6 + n_s; }  // rigid + global velocity block size k
};

// An obstacle as the scene places it. Tracks may move it (kinematic obstacles): Drive::obstacles
// holds a copy placed at the drive's time, with the velocity of its material; the Model's copy
// stays where the scene put it, with zero velocity.
struct ObstacleModel {
  std::string name;
  ObstacleKind kind = ObstacleKind::plane;
  Vec3 point = Vec3::Zero();         // plane point, box centre or mesh origin [m], world
  Vec3 normal{0, 0, 1};              // plane normal (unit)
  Mat3 rotation = Mat3::Identity();  // box and mesh axes in world
  Vec3 half_extents{1, 1, 1};
  Vec2 size{20, 20};
  Real elasticity = 0;                       // a (5.11)
  Real friction = 0;                         // beta_f (5.12)
  std::shared_ptr<const MeshObstacle> mesh;  // mesh obstacles: placed triangles and their field
  bool moving = false;                       // some track drives its point or rotation
  Vec3 velocity = Vec3::Zero();              // of the material at `point` [m/s], world
  Vec3 angular_velocity = Vec3::Zero();      // [rad/s], world
  // Velocity of the obstacle's material at x (rigid motion about `point`) [m/s].
  Vec3 velocity_at(const Vec3& x) const { return velocity + angular_velocity.cross(x - point); }
};

struct SpringModel {
  std::string name;
  int body = 0;
  int node = 0;
  Vec3 target = Vec3::Zero();
  Real stiffness = 0, damping = 0;
  Real t_begin = 0, t_end = 1e300;
  Real max_force = 1e300;
};

enum class TrackTarget {
  body_rest_parameter,
  gravity,
  spring_target,
  spring_stiffness,
  camera_position,
  camera_target,
  camera_fov,
  obstacle_point,    // obstacles[i].point[k]: plane point, box centre, mesh origin
  obstacle_rotation  // obstacles[i].rotation[k]: rotation vector applied before the orientation
};
struct TrackModel {
  TrackTarget target = TrackTarget::gravity;
  int object = 0;  // body, spring or obstacle index
  int index = 0;   // parameter or vector component
  Interpolation interpolation = Interpolation::linear;
  std::vector<Keyframe> keys;
};

struct Model {
  Scene scene;  // the source, kept for saving and for messages
  Vec3 gravity{0, 0, -9.81};
  SolverDef solver;
  std::vector<BodyModel> bodies;
  std::vector<ObstacleModel> obstacles;
  std::vector<ForceFieldDef> force_fields;
  std::vector<SpringModel> springs;
  std::vector<TrackModel> tracks;
  ConstraintSystemModel constraints;     // ch. 7
  BodyCollisionOptions body_collisions;  // 5.2.2, from the solver's keys
  int n_q = 0, n_v = 0;
};

// The node nearest to material coordinates (u, v) (v wraps at the seam): where springs and
// constraints given by a material point act.
int nearest_node(const Tessellation& t, const Vec2& uv);

// Throws pbm::Error (file, path) when the scene cannot be compiled.
Model build_model(const Scene& scene);

}  // namespace pbm
