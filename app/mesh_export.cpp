#include "mesh_export.h"

#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

namespace pbm {

std::optional<MeshFormat> parse_mesh_format(const std::string& s) {
  if (s == "obj") return MeshFormat::obj;
  if (s == "gltf") return MeshFormat::gltf;
  if (s == "ply") return MeshFormat::ply;
  return std::nullopt;
}

const char* mesh_format_extension(MeshFormat f) {
  switch (f) {
    case MeshFormat::obj:
      return ".obj";
    case MeshFormat::gltf:
      return ".gltf";
    case MeshFormat::ply:
      return ".ply";
  }
  return "";
}

namespace {

// assimp's exporter ids: "objnomtl" because a material file would name itself after the
// temporary path; "plyb" because a binary PLY of a mesh sequence is a third the size of ASCII.
const char* assimp_format_id(MeshFormat f) {
  switch (f) {
    case MeshFormat::obj:
      return "objnomtl";
    case MeshFormat::gltf:
      return "gltf2";
    case MeshFormat::ply:
      return "plyb";
  }
  return "";
}

void check_mesh(const MeshData& mesh, std::size_t index) {
  const std::string field = "meshes[" + std::to_string(index) + "]";
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    throw std::invalid_argument(field + ".normals: " + std::to_string(mesh.normals.size()) +
                                " normals for " + std::to_string(mesh.positions.size()) +
                                " positions");
  }
  const auto n_vertices = static_cast<int>(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const int i : mesh.triangles[t]) {
      if (i < 0 || i >= n_vertices) {
        throw std::invalid_argument(field + ".triangles[" + std::to_string(t) + "]: index " +
                                    std::to_string(i) + " outside [0, " +
                                    std::to_string(n_vertices) + ")");
      }
    }
  }
}

// Smooth vertex normals: the sum over a vertex's triangles of (x1 - x0) x (x2 - x0), which is
// twice the triangle's area times its unit normal, so big triangles weigh more; then normalised.
// A vertex in no triangle (or only degenerate ones) keeps a zero normal: it has no surface.
std::vector<Vec3> compute_area_weighted_normals(const MeshData& mesh) {
  std::vector<Vec3> n(mesh.positions.size(), Vec3::Zero());
  for (const auto& [i0, i1, i2] : mesh.triangles) {
    const Vec3& x0 = mesh.positions[static_cast<std::size_t>(i0)];
    const Vec3 area_normal = (mesh.positions[static_cast<std::size_t>(i1)] - x0)
                                 .cross(mesh.positions[static_cast<std::size_t>(i2)] - x0);
    for (const int i : {i0, i1, i2}) n[static_cast<std::size_t>(i)] += area_normal;
  }
  for (Vec3& n_i : n) {
    const Real length = n_i.norm();
    if (length > 0) n_i /= length;
  }
  return n;
}

aiVector3D to_ai(const Vec3& v) {
  return {static_cast<ai_real>(v.x()), static_cast<ai_real>(v.y()), static_cast<ai_real>(v.z())};
}

// The aiScene owns every array below and frees them with delete[] in its destructor.
aiMesh* make_ai_mesh(const MeshData& mesh, std::size_t index) {
  auto* m = new aiMesh;
  m->mName = mesh.name.empty() ? "mesh" + std::to_string(index) : mesh.name;
  m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m->mMaterialIndex = 0;
  m->mNumVertices = static_cast<unsigned>(mesh.positions.size());
  m->mVertices = new aiVector3D[m->mNumVertices];
  m->mNormals = new aiVector3D[m->mNumVertices];
  const std::vector<Vec3> computed =
      mesh.normals.empty() ? compute_area_weighted_normals(mesh) : std::vector<Vec3>{};
  const std::vector<Vec3>& normals = mesh.normals.empty() ? computed : mesh.normals;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    m->mVertices[i] = to_ai(mesh.positions[i]);
    m->mNormals[i] = to_ai(normals[i]);
  }
  m->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  m->mFaces = new aiFace[m->mNumFaces];
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    aiFace& face = m->mFaces[t];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (std::size_t k = 0; k < 3; ++k)
      face.mIndices[k] = static_cast<unsigned>(mesh.triangles[t][k]);
  }
  return m;
}

// True if a vertex is a corner of more than one triangle: what assimp calls the "non-verbose"
// format. Claiming it for a mesh without sharing makes assimp's OBJ export throw (its normal step
// refuses the flag, and the exporter only turns the data verbose when it sees sharing).
bool shares_vertices(const MeshData& mesh) {
  std::vector<bool> used(mesh.positions.size(), false);
  for (const auto& triangle : mesh.triangles) {
    for (const int i : triangle) {
      if (used[static_cast<std::size_t>(i)]) return true;
      used[static_cast<std::size_t>(i)] = true;
    }
  }
  return false;
}

// One node per mesh under a root, so glTF and OBJ keep each body as its own named object.
std::unique_ptr<aiScene> make_ai_scene(const std::vector<MeshData>& meshes) {
  auto scene = std::make_unique<aiScene>();
  if (std::any_of(meshes.begin(), meshes.end(), shares_vertices)) {
    scene->mFlags |= AI_SCENE_FLAGS_NON_VERBOSE_FORMAT;
  }
  // Every assimp mesh refers to a material by index, so bare geometry still gets a default one.
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1];
  scene->mMaterials[0] = new aiMaterial;
  const aiString material_name("default");
  scene->mMaterials[0]->AddProperty(&material_name, AI_MATKEY_NAME);

  scene->mNumMeshes = static_cast<unsigned>(meshes.size());
  scene->mMeshes = new aiMesh*[scene->mNumMeshes];
  scene->mRootNode = new aiNode("root");
  scene->mRootNode->mNumChildren = scene->mNumMeshes;
  scene->mRootNode->mChildren = new aiNode*[scene->mNumMeshes];
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    scene->mMeshes[i] = make_ai_mesh(meshes[i], i);
    auto* node = new aiNode(scene->mMeshes[i]->mName.C_Str());
    node->mParent = scene->mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{static_cast<unsigned>(i)};
    scene->mRootNode->mChildren[i] = node;
  }
  return scene;
}

[[noreturn]] void throw_write_error(const std::string& path, const std::string& why) {
  // assimp leaves its error string empty when a non-export exception escapes an exporter.
  throw std::runtime_error("cannot write mesh file '" + path +
                           "': " + (why.empty() ? "assimp gave no reason" : why));
}

}  // namespace

void write_mesh(const std::string& path, MeshFormat format, const std::vector<MeshData>& meshes) {
  if (meshes.empty()) throw std::invalid_argument("meshes: no mesh to write to '" + path + "'");
  for (std::size_t i = 0; i < meshes.size(); ++i) check_mesh(meshes[i], i);
  const std::unique_ptr<aiScene> scene = make_ai_scene(meshes);

  Assimp::Exporter exporter;
  const char* format_id = assimp_format_id(format);
  if (format == MeshFormat::gltf) {
    // The .gltf names its .bin after itself, so a temporary name would leak into the file.
    if (exporter.Export(scene.get(), format_id, path) != aiReturn_SUCCESS) {
      throw_write_error(path, exporter.GetErrorString());
    }
    return;
  }
  const std::string tmp_path = path + ".tmp";
  if (exporter.Export(scene.get(), format_id, tmp_path) != aiReturn_SUCCESS) {
    std::error_code ignored;
    std::filesystem::remove(tmp_path, ignored);
    throw_write_error(path, exporter.GetErrorString());
  }
  std::error_code error;
  std::filesystem::rename(tmp_path, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(tmp_path, ignored);
    throw_write_error(path, error.message());
  }
}

}  // namespace pbm
