// Mesh obstacles: a cube read by assimp from an OBJ file. Its sampled signed distance agrees
// with the exact one (a pass over the triangles) to within a grid cell, with the right sign and
// normal; a ball dropped on it never ends a step inside and stays on top; a missing or
// empty file is a clear error naming the scene's field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "collide/mesh_obstacle.h"
#include "collide/obstacle.h"
#include "core/error.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/world.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;

// A closed cube [-1, 1]^3 with outward triangles, as an OBJ file in a fresh folder.
fs::path write_cube(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pbm_mesh_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream out(file);
  out << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
      << "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  return file;
}

Real box_distance(const Vec3& x) {  // of [-1, 1]^3
  const Vec3 q = x.cwiseAbs() - Vec3::Ones();
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TEST(MeshObstacle, SampledDistanceMatchesTheCubeWithinACell) {
  const auto mesh =
      load_mesh_obstacle(write_cube("cube.obj").string(), Mat3::Identity(), Vec3::Zero(), 1.0);
  ASSERT_EQ(mesh->triangles.size(), 12u);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Real> coordinate(-1.8, 1.8);
  Real worst = 0;
  for (int k = 0; k < 500; ++k) {
    const Vec3 x(coordinate(rng), coordinate(rng), coordinate(rng));
    EXPECT_NEAR(mesh_exact_signed_distance(*mesh, x), box_distance(x), 1e-12);
    Vec3 n;
    const Real d = mesh_signed_distance(*mesh, x, n);
    worst = std::max(worst, std::abs(d - box_distance(x)));
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  }
  EXPECT_LT(worst, mesh->cell);
  // Above the top face the normal points up.
  Vec3 n;
  EXPECT_NEAR(mesh_signed_distance(*mesh, Vec3(0.1, 0.2, 1.3), n), 0.3, 0.5 * mesh->cell);
  EXPECT_GT(n.z(), 0.98);  // the interpolant's gradient, smoothed near the edges
}

TEST(MeshObstacle, ABallDroppedOnItStaysOnTopAndNeverInside) {
  BodyDef body = test::ball(DeformLevel::local, 12);
  body.position = Vec3(0.2, 0.1, 3.0);
  body.material.damping = 1.4;
  Scene scene = test::free_space(body);
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solver.dt = 0.005;
  scene.solver.fps = 50;
  ObstacleDef mesh;
  mesh.name = "cube";
  mesh.kind = ObstacleKind::mesh;
  mesh.file = write_cube("cube2.obj").string();
  mesh.point = Vec3(0, 0, 0);
  scene.obstacles.push_back(mesh);
  test::Simulation sim(scene);
  Real lowest = 1e300;
  for (int f = 0; f < 250; ++f) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    lowest = std::min(lowest, sim.stats.min_distance);
    if (f >= 150) {  // after 3 s it sits on the top face (z = 1), a ball of radius 1 above it
      EXPECT_GT(sim.state.q[2], 1.6);
      EXPECT_LT(sim.state.q[2], 2.1);
    }
  }
  EXPECT_GE(lowest, 0.0);
  EXPECT_LT(std::abs(sim.state.q[0]), 1.0);  // still over the cube
  EXPECT_LT(std::abs(sim.state.q[1]), 1.0);
}

TEST(MeshObstacle, MissingOrEmptyFileNamesTheField) {
  const fs::path dir = write_cube("cube3.obj").parent_path();
  const fs::path scene_file = dir / "scene.json";
  std::ofstream(scene_file) << R"({"bodies": [{"material": {"mass": 1}}],
    "obstacles": [{"kind": "plane"}, {"kind": "mesh", "file": "no-such.obj"}]})";
  try {
    build_model(load_scene(scene_file.string()));
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("obstacles[1].file"), std::string::npos) << what;
    EXPECT_NE(what.find("no-such.obj"), std::string::npos) << what;
  }
  std::ofstream(dir / "empty.obj") << "# nothing\n";
  std::ofstream(scene_file) << R"({"bodies": [{"material": {"mass": 1}}],
    "obstacles": [{"kind": "mesh", "file": "empty.obj"}]})";
  EXPECT_THROW(build_model(load_scene(scene_file.string())), Error);
  // Relative to the scene file: the cube next to it loads.
  std::ofstream(scene_file) << R"({"bodies": [{"material": {"mass": 1}, "position": [0, 0, 5]}],
    "obstacles": [{"kind": "mesh", "file": "cube3.obj", "scale": 2, "position": [0, 0, -2]}]})";
  const Model model = build_model(load_scene(scene_file.string()));
  ASSERT_TRUE(model.obstacles[0].mesh);
  Vec3 n;
  EXPECT_NEAR(signed_distance(model.obstacles[0], Vec3(0, 0, 1), n), 1.0, 0.1);
  // A box key on a mesh is refused.
  std::ofstream(scene_file) << R"({"bodies": [{"material": {"mass": 1}}],
    "obstacles": [{"kind": "mesh", "file": "cube3.obj", "half_extents": [1, 1, 1]}]})";
  try {
    load_scene(scene_file.string());
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not valid for a mesh obstacle"), std::string::npos);
  }
}

}  // namespace
}  // namespace pbm
