// The constant geometry every Snapshot of a Model shares (docs/architecture.md, "Snapshot"):
// each body's triangles and element edges, each mesh obstacle's vertices at its load placement
// and its triangles, in the renderer's float types. Built once with the Model (build_model), so
// make_snapshot copies no triangles and a renderer can keep what it uploaded for a topology as
// long as the pointer lives.
#pragma once

#include <memory>
#include <vector>

#include "collide/obstacle_model.h"
#include "deform/body_model.h"
#include "draw/snapshot.h"

namespace pbm {

struct SnapshotGeometry {
  // One per body: Tessellation::triangles and ::edges.
  std::vector<std::shared_ptr<const draw::MeshTopology>> body_topology;
  // One per obstacle; null but for mesh obstacles: MeshObstacle::vertices (world, at the load
  // placement MeshObstacle::rotation / position) and its triangles (no edges).
  std::vector<std::shared_ptr<const std::vector<draw::Vec3f>>> obstacle_positions;
  std::vector<std::shared_ptr<const draw::MeshTopology>> obstacle_topology;
};

SnapshotGeometry build_snapshot_geometry(const std::vector<BodyModel>& bodies,
                                         const std::vector<ObstacleModel>& obstacles);

}  // namespace pbm
