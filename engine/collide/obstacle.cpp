#include "collide/obstacle.h"

#include "collide/mesh_obstacle.h"

#include <algorithm>
#include <cmath>

namespace pbm {

Real solid_signed_distance(const ObstacleModel& o, const Vec3& x, Vec3& normal) {
  switch (o.kind) {
    case ObstacleKind::plane:
      return signed_distance(o, x, normal);
    case ObstacleKind::mesh:
      return mesh_signed_distance(*o.mesh, x, normal);
    case ObstacleKind::box: {
      const Vec3 local = o.rotation.transpose() * (x - o.point);
      const Vec3 excess = local.cwiseAbs() - o.half_extents;
      if (excess.maxCoeff() <= 0) {
        // Inside: the nearest face decides the projection direction.
        int axis = 0;
        excess.maxCoeff(&axis);
        Vec3 n_local = Vec3::Zero();
        n_local[axis] = local[axis] >= 0 ? 1.0 : -1.0;
        normal = o.rotation * n_local;
        return excess[axis];
      }
      const Vec3 outside = excess.cwiseMax(0.0);
      Vec3 n_local = outside.cwiseProduct(local.cwiseSign());
      const Real d = n_local.norm();
      normal = o.rotation * (n_local / d);
      return d;
    }
  }
  normal = Vec3::UnitZ();
  return 1e300;
}

}  // namespace pbm
