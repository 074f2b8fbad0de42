#include "sim/snapshot_geometry.h"

namespace pbm {

SnapshotGeometry build_snapshot_geometry(const std::vector<BodyModel>& bodies,
                                         const std::vector<ObstacleModel>& obstacles) {
  SnapshotGeometry g;
  for (const BodyModel& body : bodies) {
    auto topology = std::make_shared<draw::MeshTopology>();
    topology->triangles = body.tessellation.triangles;
    topology->edges = body.tessellation.edges;
    g.body_topology.push_back(std::move(topology));
  }
  for (const ObstacleModel& o : obstacles) {
    if (!o.mesh) {
      g.obstacle_positions.emplace_back();
      g.obstacle_topology.emplace_back();
      continue;
    }
    auto positions = std::make_shared<std::vector<draw::Vec3f>>();
    positions->reserve(o.mesh->vertices.size());
    for (const Vec3& x : o.mesh->vertices) positions->push_back(x.cast<float>());
    auto topology = std::make_shared<draw::MeshTopology>();
    topology->triangles = o.mesh->triangles;
    g.obstacle_positions.push_back(std::move(positions));
    g.obstacle_topology.push_back(std::move(topology));
  }
  return g;
}

}  // namespace pbm
