// The liquid's surface mesh from its OpenVDB level set (engine/liquid/liquid_surface_mesh.h): a
// closed surface around the liquid's volume, for markers and for a height field, in 3D and 2D,
// and the .vdb file Blender and Houdini read.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "liquid/liquid_surface_mesh.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81;

LiquidModel tank(int cells, Real depth, bool three_d, SurfaceMethod surface) {
  LiquidDef def;
  def.name = "tank";
  def.domain = {Vec3(0, 0, 0), Vec3(1, three_d ? 1.0 : 1.0 / cells, 1)};
  def.resolution = Eigen::Vector3i(cells, three_d ? cells : 1, cells);
  def.fluid.push_back({{Vec3(0, 0, 0), Vec3(1, 1, depth)}, Vec3::Zero()});
  def.surface = surface;
  return build_liquid_model(def, Vec3(0, 0, -kG), "test.json", 0);
}

// The volume the mesh encloses, by the divergence theorem: positive when it is wound
// counter-clockwise seen from outside.
Real enclosed_volume(const LiquidSurfaceMesh& mesh) {
  Real v = 0;
  for (const auto& [a, b, c] : mesh.triangles) {
    v += mesh.positions[a].dot(mesh.positions[b].cross(mesh.positions[c])) / 6;
  }
  return v;
}

// Every edge a -> b of one triangle is b -> a of exactly one other: closed and consistently wound.
bool closed(const LiquidSurfaceMesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) edges[{t[k], t[(k + 1) % 3]}] += 1;
  }
  for (const auto& [edge, count] : edges) {
    const auto back = edges.find({edge.second, edge.first});
    if (count != 1 || back == edges.end() || back->second != 1) return false;
  }
  return !mesh.triangles.empty();
}

Real highest(const LiquidSurfaceMesh& mesh) {
  Real z = -1e300;
  for (const Vec3& x : mesh.positions) z = std::max(z, x.z());
  return z;
}

TEST(LiquidSurfaceMesh, MarkersOfAStillTankMeshTheirVolume) {
  const LiquidModel model = tank(16, 0.5, true, SurfaceMethod::markers);
  const LiquidState state = initial_liquid_state(model, Vec3(0, 0, -kG));
  const LiquidSurfaceMesh mesh = liquid_surface_mesh(model, state, {});
  std::printf("markers 16^3: %zu triangles, voxel %.4f m, volume %.4f m^3 (0.5), top %.4f m\n",
              mesh.triangles.size(), mesh.voxel_size, enclosed_volume(mesh), highest(mesh));
  EXPECT_TRUE(closed(mesh));
  // The liquid a marker stands for ends half a spacing beyond it: the box, within the rounding
  // the smoothing gives its edges and corners.
  EXPECT_NEAR(enclosed_volume(mesh), 0.5, 0.03 * 0.5);
  EXPECT_NEAR(highest(mesh), 0.5, mesh.voxel_size);
}

TEST(LiquidSurfaceMesh, TwoDimensionalMarkersMeshASlabAsThickAsTheGrid) {
  const LiquidModel model = tank(32, 0.5, false, SurfaceMethod::markers);
  const LiquidState state = initial_liquid_state(model, Vec3(0, 0, -kG));
  // Voxels of an eighth of the cell: eight across the slab.
  const LiquidSurfaceMesh mesh = liquid_surface_mesh(model, state, {.voxel = 0.125});
  const Real slab = 0.5 / 32;
  std::printf("markers 32 x 1 x 32: volume %.6f m^3 (%.6f)\n", enclosed_volume(mesh), slab);
  EXPECT_TRUE(closed(mesh));
  EXPECT_NEAR(enclosed_volume(mesh), slab, 0.06 * slab);
}

TEST(LiquidSurfaceMesh, HeightFieldMeshFollowsItsSurface) {
  const LiquidModel model = tank(16, 0.5, true, SurfaceMethod::height_field);
  LiquidState state = initial_liquid_state(model, Vec3(0, 0, -kG));
  // A tilted surface: the mean depth stays 0.5.
  Real sum = 0;
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      state.height[i + 16 * j] = 0.5 + 0.1 * ((i + 0.5) / 16 - 0.5);
      sum += state.height[i + 16 * j] / 256;
    }
  }
  const LiquidSurfaceMesh mesh = liquid_surface_mesh(model, state, {.voxel = 0, .smoothing = 0});
  std::printf("height field 16^3: volume %.4f m^3 (%.4f), top %.4f m (0.5469)\n",
              enclosed_volume(mesh), sum, highest(mesh));
  EXPECT_TRUE(closed(mesh));
  EXPECT_NEAR(enclosed_volume(mesh), sum, 0.02 * sum);
  // The top corner's height is its column's (0.5 + 0.1 * 15.5/16 - 0.05), within a voxel.
  EXPECT_NEAR(highest(mesh), 0.5 + 0.1 * (15.5 / 16 - 0.5), mesh.voxel_size);
}

TEST(LiquidSurfaceMesh, FinerVoxelsApproachTheVolume) {
  const LiquidModel model = tank(16, 0.5, true, SurfaceMethod::markers);
  const LiquidState state = initial_liquid_state(model, Vec3(0, 0, -kG));
  const Real coarse = enclosed_volume(liquid_surface_mesh(model, state, {.voxel = 0.5}));
  const Real fine = enclosed_volume(liquid_surface_mesh(model, state, {.voxel = 0.125}));
  std::printf("voxel 1/2 cell: %.5f m^3, 1/8 cell: %.5f m^3 (0.5)\n", coarse, fine);
  EXPECT_LT(std::abs(fine - 0.5), std::abs(coarse - 0.5));
}

TEST(LiquidSurfaceMesh, WritesALevelSetFileAndRefusesAnUnwritablePath) {
  const LiquidModel model = tank(8, 0.5, true, SurfaceMethod::markers);
  const LiquidState state = initial_liquid_state(model, Vec3(0, 0, -kG));
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "pbm_test_liquid_surface.vdb";
  std::filesystem::remove(path);
  const LiquidSurfaceMesh mesh = liquid_surface_mesh(model, state, {}, path.string());
  EXPECT_GT(mesh.active_voxels, 0);
  // OpenVDB's files open with its magic number 0x56444220 (" BDV" little-endian).
  std::ifstream in(path, std::ios::binary);
  std::uint32_t magic = 0;
  in.read(reinterpret_cast<char*>(&magic), sizeof magic);
  EXPECT_EQ(magic, 0x56444220u);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  try {
    liquid_surface_mesh(model, state, {}, "/nonexistent-dir/x.vdb");
    FAIL() << "wrote to a missing folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.vdb"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists("/nonexistent-dir/x.vdb.tmp"));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace pbm
