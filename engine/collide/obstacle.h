// Rigid obstacles (sec. 5.2.1): signed distance and outward normal of a point.
#pragma once

#include "collide/obstacle_model.h"
#include "core/types.h"

namespace pbm {

// Box and mesh obstacles: see signed_distance.
Real solid_signed_distance(const ObstacleModel& box, const Vec3& x, Vec3& normal);

// Signed distance from x to the obstacle's surface (> 0 outside) and the outward unit normal of
// the collision plane (the tangent plane at the closest surface point, footnote 4 of sec. 5.2.1).
// Inline: contact tests call it for every node and surface sample at every step.
inline Real signed_distance(const ObstacleModel& obstacle, const Vec3& x, Vec3& normal) {
  if (obstacle.kind == ObstacleKind::plane) {
    // Sign of the inner product of the normal and (node - point on the plane) (sec. 5.2.1).
    normal = obstacle.normal;
    return obstacle.normal.dot(x - obstacle.point);
  }
  return solid_signed_distance(obstacle, x, normal);
}

}  // namespace pbm
