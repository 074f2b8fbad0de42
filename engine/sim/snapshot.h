// What a renderer needs of one moment (DESIGN §4): deformed node positions with their triangles,
// materials, obstacles and springs. Plain data in float, copyable across threads; no engine
// internals, so the renderer depends on this header alone.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/world.h"

namespace pbm {

using Vec3f = Eigen::Vector3f;

struct BodySnapshot {
  std::string name;
  std::vector<Vec3f> positions;               // world, one per node [m]
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<std::array<int, 2>> edges;      // of the finite elements (fig. 4.1 / 4.2)
  Vec3f color{0.8f, 0.3f, 0.3f};
  float roughness = 0.5f;
};

struct ObstacleSnapshot {
  ObstacleKind kind = ObstacleKind::plane;
  Vec3f point = Vec3f::Zero();                             // plane point / box centre, now
  Vec3f normal{0, 0, 1};                                   // plane
  Eigen::Vector2f size{20, 20};                            // plane: drawn extent
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();  // box axes
  Vec3f half_extents{1, 1, 1};
  std::shared_ptr<const MeshObstacle> mesh;  // mesh obstacles: world triangles at load
  // Mesh obstacles moved by tracks: draw each vertex x0 of `mesh` at mesh_rotation x0 +
  // mesh_offset.
  Eigen::Matrix3f mesh_rotation = Eigen::Matrix3f::Identity();
  Vec3f mesh_offset = Vec3f::Zero();
};

struct SpringSnapshot {
  Vec3f from = Vec3f::Zero(), to = Vec3f::Zero();  // body point, target
};

// A point-to-point constraint (ch. 7) between its two current points; violation = |C| [m].
struct ConstraintSnapshot {
  Vec3f a = Vec3f::Zero(), b = Vec3f::Zero();
  float violation = 0;
  int source = 0;  // index into Scene::constraints (a hinge's two points share one)
};

struct Snapshot {
  double time = 0;
  std::vector<BodySnapshot> bodies;
  std::vector<ObstacleSnapshot> obstacles;
  std::vector<SpringSnapshot> springs;
  std::vector<ConstraintSnapshot> constraints;
  // Axis-aligned bounds of the bodies [m].
  Vec3f bodies_min() const;
  Vec3f bodies_max() const;
};

// The snapshot of state. Computes the kinematics in ws (its caches stay valid).
Snapshot make_snapshot(const Model& model, const State& state, const Inputs& inputs, Workspace& ws);

}  // namespace pbm
