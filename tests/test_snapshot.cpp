// make_snapshot (engine/sim/snapshot.h): one moment as plain drawables. Constant geometry is
// shared between snapshots, obstacles and the camera are where their tracks put them at the
// state's time, and the editor's overlays (springs, constraints) are a layer of their own with
// constraints coloured by |C|.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/snapshot.h"

namespace pbm {
namespace {

using draw::Vec3f;

Scene load(const std::string& name) {
  return load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/" + name + ".json");
}

TEST(Snapshot, MeshTopologyIsSharedBetweenSnapshots) {
  test::Simulation sim(load("jello-ball"));
  const draw::Snapshot a = make_snapshot(sim);
  ASSERT_TRUE(advance_frame(sim).ok);
  const draw::Snapshot b = make_snapshot(sim);
  ASSERT_EQ(a.meshes.size(), 1u);
  ASSERT_EQ(b.meshes.size(), 1u);
  // One topology for the model, built with it; the positions are this moment's.
  EXPECT_EQ(a.meshes[0].topology.get(), b.meshes[0].topology.get());
  EXPECT_EQ(a.meshes[0].topology.get(), sim.model.snapshot_geometry.body_topology[0].get());
  EXPECT_NE(a.meshes[0].positions.get(), b.meshes[0].positions.get());
  EXPECT_NE((*a.meshes[0].positions)[0], (*b.meshes[0].positions)[0]);  // the ball fell
  // What it holds is the body's tessellation.
  const Tessellation& t = sim.model.bodies[0].tessellation;
  EXPECT_EQ(a.meshes[0].topology->triangles, t.triangles);
  EXPECT_EQ(a.meshes[0].topology->edges, t.edges);
  EXPECT_EQ(a.meshes[0].positions->size(), static_cast<std::size_t>(t.node_count()));
  // The body: pickable as body 0, smooth, in its scene colour; the focus holds its nodes.
  EXPECT_EQ(a.meshes[0].pick, 0);
  EXPECT_EQ(a.meshes[0].shading, draw::Shading::smooth);
  EXPECT_EQ(a.meshes[0].material.color, Vec3f(0.9f, 0.25f, 0.3f));
  for (const Vec3f& x : *a.meshes[0].positions) {
    EXPECT_TRUE((x.array() >= a.focus.min.array()).all() &&
                (x.array() <= a.focus.max.array()).all());
  }
  EXPECT_NEAR(a.focus.max.z() - a.focus.min.z(), 2.0f, 1e-3f);  // the unit ball's height
  // Two planes, no camera track: the scene's camera.
  EXPECT_EQ(a.planes.size(), 2u);
  ASSERT_TRUE(a.camera);
  EXPECT_EQ(a.camera->position, Vec3f(1.0f, -12.5f, 4.5f));
}

TEST(Snapshot, TheCameraFollowsItsTrack) {
  Scene scene = load("jello-ball");
  scene.tracks.push_back({.target = "camera.position[0]", .keys = {{0.0, 1.0}, {1.0, -6.0}}});
  scene.tracks.push_back({.target = "camera.fov", .keys = {{0.0, 40.0}, {1.0, 20.0}}});
  test::Simulation sim(scene);
  const draw::Snapshot at_0 = make_snapshot(sim);
  State later = sim.state;
  later.time = 1.0;
  const draw::Snapshot at_1 = make_snapshot(sim.world, sim.inputs, later, sim.ws);
  later.time = 0.5;
  const draw::Snapshot at_half = make_snapshot(sim.world, sim.inputs, later, sim.ws);
  ASSERT_TRUE(at_0.camera && at_1.camera && at_half.camera);
  EXPECT_FLOAT_EQ(at_0.camera->position.x(), 1.0f);
  EXPECT_FLOAT_EQ(at_1.camera->position.x(), -6.0f);
  EXPECT_FLOAT_EQ(at_half.camera->position.x(), -2.5f);  // linear keys
  EXPECT_FLOAT_EQ(at_1.camera->fov, 20.0f);
  // What no track drives stays the scene's.
  EXPECT_FLOAT_EQ(at_1.camera->position.y(), -12.5f);
  EXPECT_EQ(at_1.camera->target, Vec3f(0.0f, 0.0f, 1.4f));
  // A scene without a camera has none: views frame the focus.
  scene.camera.reset();
  scene.tracks.clear();
  test::Simulation no_camera(scene);
  EXPECT_FALSE(make_snapshot(no_camera).camera.has_value());
}

// A mesh obstacle turned by a track: drawn from positions shared since load, at rotation x0 +
// offset = R R0^T (x0 - p0) + p, exactly where the collision stages see it.
TEST(Snapshot, AMovingMeshObstacleKeepsItsVerticesAndIsPlacedByItsTrack) {
  Scene scene = parse_scene(R"({
    "bodies": [{"material": {"mass": 1}, "position": [0, 0, 5]}],
    "obstacles": [{"kind": "mesh", "file": "../resources/meshes/wedge.obj", "position": [1, 2, 0],
                   "orientation": [0.9238795, 0, 0, 0.3826834]},
                  {"kind": "box", "center": [0, 0, -1], "half_extents": [2, 3, 0.5]}],
    "tracks": [{"target": "obstacles[0].rotation[2]", "keys": [[0, 0], [1, 1.2]]}]})",
                            std::string(PBM_SOURCE_DIR) + "/scenes/wedge-test.json");
  test::Simulation sim(scene);
  const draw::Snapshot at_0 = make_snapshot(sim);
  State later = sim.state;
  later.time = 0.75;
  const draw::Snapshot turned = make_snapshot(sim.world, sim.inputs, later, sim.ws);
  ASSERT_EQ(turned.meshes.size(), 2u);  // the body, then the obstacle
  const draw::Mesh& wedge = turned.meshes[1];
  EXPECT_EQ(wedge.pick, -1);
  EXPECT_EQ(wedge.shading, draw::Shading::flat);
  EXPECT_EQ(wedge.positions.get(), at_0.meshes[1].positions.get());
  EXPECT_EQ(wedge.topology.get(), at_0.meshes[1].topology.get());
  const ObstacleModel& placed = sim.ws.drive.obstacles[0];  // the drive at t = 0.75
  const MeshObstacle& mesh = *placed.mesh;
  ASSERT_EQ(wedge.positions->size(), mesh.vertices.size());
  double worst = 0;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3 expected =
        placed.rotation * mesh.rotation.transpose() * (mesh.vertices[i] - mesh.position) +
        placed.point;
    const Vec3f drawn = wedge.rotation * (*wedge.positions)[i] + wedge.offset;
    worst = std::max(worst, (drawn.cast<double>() - expected).norm());
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT((turned.meshes[1].rotation - at_0.meshes[1].rotation).norm(), 0.5f);  // it turned
  // The box: a Primitive with the obstacle's placement.
  ASSERT_EQ(turned.primitives.size(), 1u);
  EXPECT_EQ(turned.primitives[0].shape, draw::PrimitiveShape::box);
  EXPECT_EQ(turned.primitives[0].center, Vec3f(0, 0, -1));
  EXPECT_EQ(turned.primitives[0].half_size, Vec3f(2, 3, 0.5f));
}

// The overlay layer: scene springs while active and the mouse's, in the spring colour with end
// points; point constraints green when held and red at 1 cm, one segment per model point
// constraint from end a to end b.
TEST(Snapshot, SpringsAndConstraintsAreOverlayLines) {
  Scene scene = load("jello-ball");
  test::Simulation probe(scene);
  const int top = probe.model.bodies[0].tessellation.north_pole;
  const draw::Snapshot first = make_snapshot(probe);
  EXPECT_TRUE(first.lines.empty() && first.points.empty()) << "nothing to draw over the scene";
  const Vec3 pole = (*first.meshes[0].positions)[top].cast<double>();
  SpringDef spring;
  spring.body = 0;
  spring.node = top;
  spring.target = Vec3(3, 0, 6);
  spring.stiffness = 1;
  spring.t_begin = 0.5;
  scene.springs.push_back(spring);
  // A second spring whose target's x an input of the moment sets (as a mouse drag does).
  SpringDef dragged = spring;
  dragged.node = 0;
  dragged.target = Vec3::Zero();
  scene.springs.push_back(dragged);
  scene.tracks.push_back(
      {.target = "springs[1].target[0]", .interpolation = Interpolation::step, .keys = {{0, 0}}});
  ConstraintDef held;
  held.a.body = 0;
  held.a.node = top;
  held.b.world = pole;
  ConstraintDef broken = held;
  broken.b.world = pole + Vec3(0.03, 0, 0);
  scene.constraints = {held, broken};
  test::Simulation sim(scene);
  Inputs inputs;
  inputs.tracks.push_back({.track = 0, .time = 0.55, .value = -3});
  EXPECT_EQ(make_snapshot(sim).lines.size(), 1u)
      << "only the constraints: the springs start at 0.5 s";
  State later = sim.state;
  later.time = 0.6;  // the scene spring is on
  const draw::Snapshot snap = make_snapshot(sim.world, inputs, later, sim.ws);
  ASSERT_EQ(snap.lines.size(), 2u);
  const draw::Lines& springs = snap.lines[0];
  EXPECT_EQ(springs.layer, draw::Layer::overlay);
  EXPECT_TRUE(springs.end_points);
  ASSERT_EQ(springs.points.size(), 4u);  // the scene's springs, the second moved by the input
  EXPECT_EQ(springs.points[1], Vec3f(3, 0, 6));
  EXPECT_EQ(springs.points[3], Vec3f(-3, 0, 0));
  EXPECT_EQ(springs.colors[0], Vec3f(0.95f, 0.85f, 0.2f));
  const draw::Lines& constraints = snap.lines[1];
  EXPECT_EQ(constraints.layer, draw::Layer::overlay);
  ASSERT_EQ(constraints.points.size(), 4u);
  EXPECT_LT((constraints.points[2] - constraints.points[3]).norm(), 0.031f);
  EXPECT_GT((constraints.points[2] - constraints.points[3]).norm(), 0.029f);
  const Vec3f green(0.25f, 0.9f, 0.35f), red(0.95f, 0.2f, 0.2f);
  EXPECT_LT((constraints.colors[0] - green).norm(), 1e-4f);
  EXPECT_LT((constraints.colors[1] - red).norm(), 1e-6f);
  // Nothing of the overlay is in the scene layer.
  for (const draw::Lines& l : snap.lines) EXPECT_EQ(l.layer, draw::Layer::overlay);
  EXPECT_TRUE(snap.points.empty());
}

}  // namespace
}  // namespace pbm
