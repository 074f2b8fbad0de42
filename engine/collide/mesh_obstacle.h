// Triangle-mesh obstacles from any file assimp reads (OBJ, glTF, FBX, PLY, STL), placed by a
// position, orientation and scale. Collisions (sec. 5.2.1) need a signed distance and a normal
// at every node each step; a closed mesh's exact distance costs a pass over its triangles, so it
// is sampled once, at load, on a grid around the mesh (sign by the generalized winding number,
// which also tolerates small holes), and read back by trilinear interpolation: distances within
// about one cell of the surface, the normal the interpolant's gradient.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"

namespace pbm {

struct MeshObstacle {
  std::vector<Vec3> vertices;  // world [m]
  std::vector<std::array<int, 3>> triangles;
  Vec3 grid_origin = Vec3::Zero();  // world position of sample (0, 0, 0)
  Real cell = 1;                    // grid spacing [m]
  std::array<int, 3> samples{0, 0, 0};
  std::vector<Real> distance;                       // x fastest; > 0 outside
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();  // bounds of the vertices
  // The placement the world vertices and the grid were made at: a moved mesh obstacle reads its
  // field at x mapped back by the rigid motion between this placement and its current one.
  Mat3 rotation = Mat3::Identity();
  Vec3 position = Vec3::Zero();
};

// Loads and places the mesh; throws std::runtime_error saying why (unreadable, no triangles,
// too large).
std::shared_ptr<const MeshObstacle> load_mesh_obstacle(const std::string& path,
                                                       const Mat3& rotation, const Vec3& position,
                                                       Real scale);

// Signed distance (> 0 outside) and outward unit normal at x.
Real mesh_signed_distance(const MeshObstacle& mesh, const Vec3& x, Vec3& normal);

// Exact signed distance by a pass over every triangle (for tests and the grid itself).
Real mesh_exact_signed_distance(const MeshObstacle& mesh, const Vec3& x);

}  // namespace pbm
