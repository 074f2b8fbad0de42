// Rigid obstacles (sec. 5.2.1): signed distance and outward normal of a point.
#pragma once

#include "core/types.h"
#include "sim/model.h"

namespace pbm {

// Signed distance from x to the obstacle's surface (> 0 outside) and the outward unit normal of
// the collision plane (the tangent plane at the closest surface point, footnote 4 of sec. 5.2.1).
Real signed_distance(const ObstacleModel& obstacle, const Vec3& x, Vec3& normal);

}  // namespace pbm
