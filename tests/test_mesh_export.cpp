// Mesh export: what write_mesh puts on disk must read back through assimp's own importer with the
// same counts, positions and (area-weighted) normals, in every format.
#include "mesh_export.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <assimp/Importer.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace pbm {
namespace {

namespace fs = std::filesystem;

constexpr double kTol = 1e-5;  // written as single precision
const Vec3 kCentre(0.1, -0.2, 0.3);

// Regular octahedron of circumradius 1 about kCentre: 6 vertices, 8 outward triangles.
MeshData octahedron() {
  MeshData m;
  m.name = "octahedron";
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) m.positions.push_back(kCentre + sign * Vec3::Unit(axis));
  }
  // Indices: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z. Each face (x, y, z) is counter-clockwise seen
  // from outside when sx * sy * sz > 0, else reversed.
  for (const int x : {0, 1}) {
    for (const int y : {2, 3}) {
      for (const int z : {4, 5}) {
        const bool outward = ((x == 0) == (y == 2)) == (z == 4);
        m.triangles.push_back(outward ? std::array{x, y, z} : std::array{x, z, y});
      }
    }
  }
  return m;
}

MeshData tetrahedron() {
  MeshData m;
  m.name = "tetrahedron";
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

class MeshExportTest : public ::testing::TestWithParam<MeshFormat> {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    dir_ =
        fs::temp_directory_path() / ("pbm_mesh_export_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& stem) const {
    return (dir_ / (stem + mesh_format_extension(GetParam()))).string();
  }
  fs::path dir_;
};

// Index of the vertex of `mesh` at x, or -1.
int find_vertex(const aiMesh& mesh, const Vec3& x) {
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D& v = mesh.mVertices[i];
    if ((Vec3(v.x, v.y, v.z) - x).norm() < kTol) return static_cast<int>(i);
  }
  return -1;
}

TEST(MeshFormatTest, ParsesNamesAndGivesExtensions) {
  EXPECT_EQ(parse_mesh_format("obj"), MeshFormat::obj);
  EXPECT_EQ(parse_mesh_format("gltf"), MeshFormat::gltf);
  EXPECT_EQ(parse_mesh_format("ply"), MeshFormat::ply);
  EXPECT_FALSE(parse_mesh_format("stl").has_value());
  EXPECT_FALSE(parse_mesh_format("OBJ").has_value());
  EXPECT_STREQ(mesh_format_extension(MeshFormat::obj), ".obj");
  EXPECT_STREQ(mesh_format_extension(MeshFormat::gltf), ".gltf");
  EXPECT_STREQ(mesh_format_extension(MeshFormat::ply), ".ply");
}

TEST_P(MeshExportTest, OctahedronReadsBackWithPositionsAndSmoothNormals) {
  const std::string file = path("octahedron");
  write_mesh(file, GetParam(), {octahedron()});
  EXPECT_FALSE(fs::exists(file + ".tmp"));

  Assimp::Importer importer;
  // Text formats repeat a vertex per face on import; joining gives back the shared vertices.
  const aiScene* scene = importer.ReadFile(file, aiProcess_JoinIdenticalVertices);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh& mesh = *scene->mMeshes[0];
  EXPECT_EQ(mesh.mNumVertices, 6u);
  ASSERT_EQ(mesh.mNumFaces, 8u);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) EXPECT_EQ(mesh.mFaces[f].mNumIndices, 3u);
  ASSERT_TRUE(mesh.HasNormals());
  for (int axis = 0; axis < 3; ++axis) {
    const int i = find_vertex(mesh, kCentre + Vec3::Unit(axis));
    ASSERT_GE(i, 0) << "vertex on +axis " << axis << " not found";
    // By the octahedron's symmetry the four faces at a vertex have equal area, and their normals
    // (+-1, +-1, 1)/sqrt(3) about that axis sum to the axis itself.
    const aiVector3D& n = mesh.mNormals[i];
    EXPECT_NEAR((Vec3(n.x, n.y, n.z) - Vec3::Unit(axis)).norm(), 0, kTol);
  }
  // Winding survives: every face's geometric normal points away from the centre.
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const unsigned* idx = mesh.mFaces[f].mIndices;
    const auto x = [&](unsigned k) {
      const aiVector3D& v = mesh.mVertices[idx[k]];
      return Vec3(v.x, v.y, v.z);
    };
    EXPECT_GT((x(1) - x(0)).cross(x(2) - x(0)).dot(x(0) - kCentre), 0) << "face " << f;
  }
}

TEST_P(MeshExportTest, LoneTriangleGetsItsRightHandNormal) {
  // No vertex is shared here; assimp's exporters treat that case apart from shared vertices.
  MeshData m;
  m.positions = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0)};
  m.triangles = {{0, 1, 2}};
  const std::string file = path("triangle");
  write_mesh(file, GetParam(), {m});
  if (GetParam() == MeshFormat::gltf) {
    EXPECT_TRUE(fs::exists(dir_ / "triangle.bin"));
  }
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, aiProcess_JoinIdenticalVertices);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh& mesh = *scene->mMeshes[0];
  EXPECT_EQ(mesh.mNumVertices, 3u);
  EXPECT_EQ(mesh.mNumFaces, 1u);
  const int i = find_vertex(mesh, Vec3(0, 3, 0));
  ASSERT_GE(i, 0);
  ASSERT_TRUE(mesh.HasNormals());
  // (x1 - x0) x (x2 - x0) = (2, 0, 0) x (0, 3, 0) = (0, 0, 6): unit normal +z.
  const aiVector3D& n = mesh.mNormals[i];
  EXPECT_NEAR((Vec3(n.x, n.y, n.z) - Vec3::UnitZ()).norm(), 0, kTol);
}

TEST_P(MeshExportTest, GivenNormalsAreWrittenAsGiven) {
  MeshData m = tetrahedron();
  // Deliberately not the geometric normals, so computing them instead would fail the test.
  m.normals.assign(m.positions.size(), Vec3(0.6, 0.0, -0.8));
  const std::string file = path("tetrahedron");
  write_mesh(file, GetParam(), {m});
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, aiProcess_JoinIdenticalVertices);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  const aiMesh& mesh = *scene->mMeshes[0];
  EXPECT_EQ(mesh.mNumVertices, 4u);
  EXPECT_EQ(mesh.mNumFaces, 4u);
  ASSERT_TRUE(mesh.HasNormals());
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    EXPECT_NEAR(mesh.mNormals[i].x, 0.6, kTol);
    EXPECT_NEAR(mesh.mNormals[i].z, -0.8, kTol);
  }
}

TEST_P(MeshExportTest, SeveralMeshesGoToOneFile) {
  const std::string file = path("pair");
  write_mesh(file, GetParam(), {octahedron(), tetrahedron()});
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file, aiProcess_JoinIdenticalVertices);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  unsigned n_vertices = 0;
  unsigned n_faces = 0;
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    n_vertices += scene->mMeshes[k]->mNumVertices;
    n_faces += scene->mMeshes[k]->mNumFaces;
  }
  EXPECT_EQ(n_vertices, 6u + 4u);
  EXPECT_EQ(n_faces, 8u + 4u);
  if (GetParam() == MeshFormat::ply) {
    EXPECT_EQ(scene->mNumMeshes, 1u);  // PLY holds a single mesh: the two are merged
  } else {
    ASSERT_EQ(scene->mNumMeshes, 2u);
    EXPECT_NE(scene->mRootNode->FindNode("octahedron"), nullptr);
    EXPECT_NE(scene->mRootNode->FindNode("tetrahedron"), nullptr);
  }
}

TEST_P(MeshExportTest, UnwritablePathThrowsWithThePath) {
  const std::string file = std::string("/proc/forbidden/x") + mesh_format_extension(GetParam());
  try {
    write_mesh(file, GetParam(), {octahedron()});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
}

TEST_P(MeshExportTest, FailedWriteLeavesNoFileBehind) {
  // A directory where the file should go makes the final rename (or the glTF open) fail.
  const std::string file = path("blocked");
  fs::create_directories(fs::path(file) / "occupied");
  EXPECT_THROW(write_mesh(file, GetParam(), {octahedron()}), std::runtime_error);
  EXPECT_FALSE(fs::exists(file + ".tmp"));
  EXPECT_TRUE(fs::is_directory(file));
}

TEST_P(MeshExportTest, MalformedMeshIsRejectedBeforeWriting) {
  MeshData m = tetrahedron();
  m.triangles.push_back({0, 1, 4});
  const std::string file = path("bad");
  try {
    write_mesh(file, GetParam(), {m});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("meshes[0].triangles[4]"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
}

INSTANTIATE_TEST_SUITE_P(AllFormats, MeshExportTest,
                         ::testing::Values(MeshFormat::obj, MeshFormat::gltf, MeshFormat::ply),
                         [](const ::testing::TestParamInfo<MeshFormat>& param_info) {
                           return std::string(mesh_format_extension(param_info.param) + 1);
                         });

}  // namespace
}  // namespace pbm
