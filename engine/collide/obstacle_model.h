// ObstacleModel: a rigid obstacle as the collision stages see it (sec. 5.2.1), compiled once from
// its ObstacleDef. Tracks may move it (kinematic obstacles): the drive holds a copy placed at its
// time, with the velocity of its material (sim/tracks.h); the Model's copy stays where the scene
// put it, with zero velocity.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "collide/mesh_obstacle.h"
#include "collide/obstacle_def.h"
#include "core/types.h"

namespace pbm {

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

// The obstacles placed at one time (the drive's, or the Model's where none moves).
using Obstacles = std::span<const ObstacleModel>;

// Compiles one obstacle; a mesh file is read relative to the scene file's folder. Throws
// pbm::Error(file, path + ".file") when the mesh cannot be used.
ObstacleModel build_obstacle_model(const ObstacleDef& def, const std::string& file,
                                   const std::string& path);

}  // namespace pbm
