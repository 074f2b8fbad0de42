// What a scene file says of rigid obstacles (scenes/README.md, section "obstacles"): plain
// definitions with defaults, validated by the scene reader and compiled into an ObstacleModel
// (collide/obstacle_model.h). Data only.
#pragma once

#include <string>

#include "core/types.h"

namespace pbm {

enum class ObstacleKind { plane, box, mesh };

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

}  // namespace pbm
