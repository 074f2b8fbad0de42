// Writes triangle meshes (one per body, one file per frame) through assimp's Exporter, so a
// simulated mesh sequence opens in Blender, MeshLab or any glTF viewer.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"

namespace pbm {

// obj: Wavefront OBJ without a material file, one object per mesh.
// gltf: glTF 2.0, a .gltf (JSON) beside a .bin holding the buffers; one node per mesh.
// ply: binary little-endian Stanford PLY; the format holds one mesh, so several are merged.
enum class MeshFormat { obj, gltf, ply };

// "obj", "gltf" or "ply" (exactly); anything else gives nullopt.
std::optional<MeshFormat> parse_mesh_format(const std::string& s);

// ".obj", ".gltf" or ".ply".
const char* mesh_format_extension(MeshFormat f);

// One triangle mesh in world coordinates (m).
struct MeshData {
  std::vector<Vec3> positions;  // n_vertices
  // n_vertices unit normals, or empty: then each vertex gets the area-weighted mean of the
  // normals of its triangles (smooth shading).
  std::vector<Vec3> normals;
  // n_triangles, vertex indices counter-clockwise seen from outside.
  std::vector<std::array<int, 3>> triangles;
  std::string name;  // object/node name; empty gives "mesh<index>"
};

// Writes `meshes` (at least one) to `path` in `format`, as single precision. OBJ and PLY are
// written to path + ".tmp" and renamed, so a failed write never leaves a partial file at path;
// glTF writes path and its .bin directly. Throws std::invalid_argument naming the field if a
// mesh is malformed (index out of range, normals of the wrong count), and std::runtime_error
// with the path and assimp's error string if writing fails.
void write_mesh(const std::string& path, MeshFormat format, const std::vector<MeshData>& meshes);

}  // namespace pbm
