#include "collide/obstacle.h"

#include "collide/mesh_obstacle.h"

#include <algorithm>
#include <cmath>

namespace pbm {

Real solid_signed_distance(const ObstacleModel& o, const Vec3& x, Vec3& normal) {
  switch (o.kind) {
    case ObstacleKind::plane:
      return signed_distance(o, x, normal);
    case ObstacleKind::mesh: {
      const MeshObstacle& mesh = *o.mesh;
      // Where the scene put it (bit for bit: static meshes read x directly), or moved by tracks.
      if (o.point == mesh.position && o.rotation == mesh.rotation) {
        return mesh_signed_distance(mesh, x, normal);
      }
      // x taken back by the rigid motion from the load placement (R0, p0) to (R, p):
      // x0 = p0 + R0 R^T (x - p); the normal comes forward by R R0^T.
      const Mat3 back = mesh.rotation * o.rotation.transpose();
      Vec3 n0;
      const Real d = mesh_signed_distance(mesh, mesh.position + back * (x - o.point), n0);
      normal = back.transpose() * n0;
      return d;
    }
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
