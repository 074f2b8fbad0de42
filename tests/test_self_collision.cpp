// Self-collision of a local body (collide/self_collision.h): a soft ball squashed flat and a
// plate folded onto itself do not cross their own surface with it on and do with it off; the
// continuous detection's primitives on hand-made cases; one body's impulses conserve its linear
// momentum; same input, same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "collide/body_collisions.h"
#include "collide/continuous_collision.h"
#include "collide/rigid_contact.h"
#include "collide/self_collision.h"
#include "collide/triangle_geometry.h"
#include "deform/body_dynamics.h"
#include "scene_builders.h"
#include "sim/state.h"
#include "sim/world.h"

namespace pbm {
namespace {

// ---- (c) continuous detection primitives -------------------------------------------------------

FourPoints moved(const FourPoints& x, const Vec3& node_shift) {
  FourPoints r = x;
  r[0] += node_shift;
  return r;
}

TEST(ContinuousCollision, NodeThroughTriangleIsFoundAtItsTime) {
  const FourPoints x0 = {Vec3(0.2, 0.3, 0.7), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  // Straight down by 1: crosses z = 0 at t = 0.7.
  const ContinuousContact c = detect_node_face_collision(x0, moved(x0, Vec3(0, 0, -1)), 1e-9);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.t, 0.7, 1e-9);
  EXPECT_NEAR(c.weights[0], 1.0, 0.0);
  EXPECT_NEAR(-c.weights[2], 0.2, 1e-9);  // barycentric weight of (1, 0, 0)
  EXPECT_NEAR(-c.weights[3], 0.3, 1e-9);
  EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);  // against the approach: the node came from +z
  // A moving, tilting triangle against a still node: f(t) is a true cubic. The node at the
  // origin; the triangle's plane z = 0.5 - t (its corners move together) crosses it at 0.5.
  const FourPoints y0 = {Vec3(0.1, 0.1, 0), Vec3(-1, -1, 0.5), Vec3(2, -1, 0.5), Vec3(-1, 2, 0.5)};
  FourPoints y1 = y0;
  for (int k = 1; k < 4; ++k) y1[k] += Vec3(0.3, 0.2, -1.0);
  const ContinuousContact d = detect_node_face_collision(y0, y1, 1e-9);
  ASSERT_TRUE(d.hit);
  EXPECT_NEAR(d.t, 0.5, 1e-9);
  // A corner rising while the others stay: plane through the node when the corner's height is 0,
  // z_2(t) = -0.4 + t, and at that instant the node's projection is inside.
  FourPoints w0 = {Vec3(0.25, 0.25, 0), Vec3(0, 0, 0), Vec3(1, 0, -0.4), Vec3(0, 1, 0)};
  FourPoints w1 = w0;
  w1[2].z() = 0.6;
  const ContinuousContact e = detect_node_face_collision(w0, w1, 1e-9);
  ASSERT_TRUE(e.hit);
  EXPECT_NEAR(e.t, 0.4, 1e-9);
}

TEST(ContinuousCollision, NodeMovingParallelOrBesideIsNotFound) {
  const FourPoints x0 = {Vec3(0.2, 0.3, 1e-3), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  // Parallel to the face, 1 mm above it, across its whole width.
  EXPECT_FALSE(detect_node_face_collision(x0, moved(x0, Vec3(0.5, 0.3, 0)), 1e-9).hit);
  // Through the face's plane but beside the triangle.
  const FourPoints beside = {Vec3(2, 2, 0.5), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_FALSE(detect_node_face_collision(beside, moved(beside, Vec3(0, 0, -1)), 1e-9).hit);
  // Stopping short of the face.
  EXPECT_FALSE(detect_node_face_collision(x0, moved(x0, Vec3(0, 0, -0.5e-3)), 1e-9).hit);
}

TEST(ContinuousCollision, CrossingEdgesAreFoundAndPassingEdgesAreNot) {
  // Edge a along x at z = 1 moving down by 2; edge b along y at z = 0: they cross at t = 0.5.
  const FourPoints x0 = {Vec3(-1, 0, 1), Vec3(1, 0, 1), Vec3(0, -1, 0), Vec3(0, 1, 0)};
  FourPoints x1 = x0;
  x1[0].z() -= 2;
  x1[1].z() -= 2;
  const ContinuousContact c = detect_edge_edge_collision(x0, x1, 1e-9);
  ASSERT_TRUE(c.hit);
  EXPECT_NEAR(c.t, 0.5, 1e-9);
  EXPECT_NEAR(c.weights[1], 0.5, 1e-9);   // s: the middle of a
  EXPECT_NEAR(-c.weights[3], 0.5, 1e-9);  // u: the middle of b
  EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
  // Off-centre crossing with both edges moving: a's points at x = 0.3, b sweeping in y.
  const FourPoints y0 = {Vec3(0.3, -1, 0.2), Vec3(0.3, 1, 0.6), Vec3(-1, 0.1, 0.9),
                         Vec3(1, 0.1, 0.9)};
  FourPoints y1 = y0;
  for (int k = 2; k < 4; ++k) y1[k].z() -= 1.0;  // b descends through z of a at y = 0.1: 0.42
  const ContinuousContact d = detect_edge_edge_collision(y0, y1, 1e-9);
  ASSERT_TRUE(d.hit);
  EXPECT_NEAR(d.t, 0.9 - 0.42, 1e-9);
  // Same motion, b shifted beyond a's end: its line crosses a's line outside the segment.
  FourPoints z0 = y0, z1 = y1;
  for (int k = 2; k < 4; ++k) {
    z0[k].y() = 1.5;
    z1[k].y() = 1.5;
  }
  EXPECT_FALSE(detect_edge_edge_collision(z0, z1, 1e-9).hit);
  // Parallel edges passing each other 1 mm apart.
  const FourPoints p0 = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(-1, -1, 1e-3), Vec3(1, -1, 1e-3)};
  FourPoints p1 = p0;
  p1[2].y() += 2;
  p1[3].y() += 2;
  EXPECT_FALSE(detect_edge_edge_collision(p0, p1, 1e-9).hit);
  // Skew edges passing 1 mm apart (b crosses over a without touching).
  const FourPoints s0 = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.2, -1, 1e-3), Vec3(0.2, 1, 1e-3)};
  FourPoints s1 = s0;
  s1[2].x() -= 0.5;
  s1[3].x() -= 0.5;
  EXPECT_FALSE(detect_edge_edge_collision(s0, s1, 1e-9).hit);
}

// ---- scenes ------------------------------------------------------------------------------------

// Per substep, the pairs of triangles sharing no node that intersect (count_self_intersections).
struct SceneRun {
  int worst = 0;             // most crossing pairs after any substep
  int substeps_crossed = 0;  // substeps that ended with at least one
  int proximity = 0, continuous = 0, zone_nodes = 0, estimated = 0;
  double self_seconds = 0;
  Real flattest = 1e300;  // least height of the body's nodes' bounding box [m]
  std::uint64_t hash = 0;
  bool ok = true;
};

using Setup = std::function<void(test::Simulation&)>;

SceneRun run_scene(const Scene& scene, int substeps, const Setup& setup = {}) {
  test::Simulation sim(scene);
  if (setup) setup(sim);
  SceneRun r;
  const BodyModel& body = sim.model.bodies[0];
  for (int k = 0; k < substeps; ++k) {
    int evaluations = 0;
    r.ok = advance_substep(sim.world, sim.inputs, sim.state, sim.model.solver.dt, sim.ws,
                           evaluations) &&
           r.ok;
    const BodyCollisionStats& stats = sim.ws.body_collision_stats;
    if (!r.ok) break;
    r.proximity += stats.self.proximity_pairs;
    r.continuous += stats.self.continuous_collisions;
    r.zone_nodes += stats.self.zone_nodes;
    r.estimated += stats.self.estimated_starts;
    r.self_seconds += stats.seconds_self;
    compute_body_kinematics(body, sim.state.q.segment(body.q_offset, body.q_size),
                            sim.state.v.segment(body.v_offset, body.v_size), sim.ws.bodies[0],
                            false);
    const std::vector<Vec3>& x = sim.ws.bodies[0].x;
    const int crossing = count_self_intersections(body.tessellation.triangles, x);
    r.worst = std::max(r.worst, crossing);
    r.substeps_crossed += crossing > 0;
    Real lo = 1e300, hi = -1e300;
    for (const Vec3& p : x) {
      lo = std::min(lo, p.z());
      hi = std::max(hi, p.z());
    }
    r.flattest = std::min(r.flattest, hi - lo);
  }
  r.hash = hash_state(sim.state);
  return r;
}

void print(const char* name, bool self, const SceneRun& r, int substeps) {
  std::printf(
      "%s, self_collision %s: worst %d crossing pairs, %d substeps crossed, flattest %.3f m, "
      "%d proximity pairs, %d continuous hits, %d zone nodes, self stage %.1f us/substep\n",
      name, self ? "on" : "off", r.worst, r.substeps_crossed, r.flattest, r.proximity, r.continuous,
      r.zone_nodes, 1e6 * r.self_seconds / substeps);
}

ObstacleDef ground() {
  ObstacleDef g;
  g.kind = ObstacleKind::plane;
  g.friction = 0.3;
  g.elasticity = 670;
  return g;
}

// A soft shell dropped under 8 g: it lands and is pressed flat, its top meeting its bottom.
Scene squash_scene(bool self) {
  BodyDef ball = test::ball(DeformLevel::local, 12);
  ball.position = Vec3(0, 0, 1.1);
  ball.material.w0 = 2;
  ball.material.w1 = 1;
  ball.material.damping = 2;
  ball.k_s = VecX::Constant(6, 500.0);  // the shell's size gives way too: flat in 0.3 s
  Scene scene = test::free_space(ball);
  scene.gravity = Vec3(0, 0, -8 * 9.81);
  scene.obstacles = {ground()};
  scene.solver.dt = 1e-3;
  scene.solver.self_collision = self;
  return scene;
}

// (a)
TEST(SelfCollision, SquashedShellDoesNotCrossItself) {
  constexpr int kSubsteps = 1500;
  const SceneRun off = run_scene(squash_scene(false), kSubsteps);
  print("squash", false, off, kSubsteps);
  const SceneRun on = run_scene(squash_scene(true), kSubsteps);
  print("squash", true, on, kSubsteps);
  ASSERT_TRUE(off.ok);
  ASSERT_TRUE(on.ok);
  EXPECT_GT(off.worst, 0);  // the scene does cross itself: the test can fail
  EXPECT_EQ(on.worst, 0);
  EXPECT_GT(on.proximity, 0);
  EXPECT_EQ(on.estimated, 0);   // the world recorded every step's start
  EXPECT_LT(on.flattest, 0.5);  // it was pressed flat (radius 1)
}

// A soft plate whose right half is flung up and over its left half (turning at 8 rad/s about a
// line across its top at x = 0.2): the halves' top faces meet, as in a fold.
Scene fold_scene(bool self) {
  BodyDef plate = test::ball(DeformLevel::local, 10);
  plate.name = "plate";
  plate.q_s << 1.0, 2.0, 0.6, 0.12, 0.4, 0.4;  // a0, a1, a2, a3, eps1, eps2
  plate.q_s0 = plate.q_s;
  plate.k_s = VecX::Constant(6, 5e4);
  plate.tessellation.segments = 24;
  plate.position = Vec3(0, 0, 0.13);
  plate.material.w0 = 2;
  plate.material.w1 = 1;
  plate.material.damping = 1;
  Scene scene = test::free_space(plate);
  scene.gravity = Vec3(0, 0, -9.81);
  scene.obstacles = {ground()};
  scene.solver.dt = 1e-3;
  scene.solver.self_collision = self;
  return scene;
}

void fling_right_half(test::Simulation& sim) {
  const BodyModel& body = sim.model.bodies[0];
  BodyWorkspace& bw = sim.ws.bodies[0];
  auto q = sim.state.q.segment(body.q_offset, body.q_size);
  auto v = sim.state.v.segment(body.v_offset, body.v_size);
  compute_body_kinematics(body, q, v, bw, false);
  const Vec3 pivot(0.2, 0, 0.25);
  const Vec3 omega(0, -8, 0);
  for (int i = 0; i < body.n_nodes(); ++i) {
    const Vec3 r = bw.x[i] - pivot;
    if (r.x() > 0) v.segment<3>(6 + body.n_s + 3 * i) = omega.cross(r);  // body frame = world
  }
  compute_body_kinematics(body, q, v, bw, false);
  factor_generalized_mass(body, q, bw);
  resplit_velocities(body, q, v, bw);
}

// (b)
TEST(SelfCollision, FoldedPlateDoesNotCrossItself) {
  constexpr int kSubsteps = 800;
  const SceneRun off = run_scene(fold_scene(false), kSubsteps, fling_right_half);
  print("fold", false, off, kSubsteps);
  const SceneRun on = run_scene(fold_scene(true), kSubsteps, fling_right_half);
  print("fold", true, on, kSubsteps);
  ASSERT_TRUE(off.ok);
  ASSERT_TRUE(on.ok);
  EXPECT_GT(off.worst, 0);
  EXPECT_EQ(on.worst, 0);
  EXPECT_GT(on.proximity + on.continuous, 0);
}

// (d) One body's self-collision impulses, the call alone (the world steps without it, the test
// calls it after each substep): its linear momentum sum m x-dot is unchanged to 1e-9 of
// sum m |x-dot|.
TEST(SelfCollision, ImpulsesConserveTheBodysLinearMomentum) {
  test::Simulation sim(fold_scene(false));
  sim.ws.bodies[0].dt = sim.model.solver.dt;
  fling_right_half(sim);
  BodyCollisionWorkspace cws;
  BodyCollisionOptions options = sim.model.body_collisions.options;
  options.self_collision = true;
  const BodyModel& body = sim.model.bodies[0];
  auto momentum = [&](Real& scale) {
    compute_body_kinematics(body, sim.state.q.segment(body.q_offset, body.q_size),
                            sim.state.v.segment(body.v_offset, body.v_size), sim.ws.bodies[0],
                            false);
    Vec3 p = Vec3::Zero();
    scale = 0;
    for (int i = 0; i < body.n_nodes(); ++i) {
      p += body.node_mass[i] * sim.ws.bodies[0].x_dot[i];
      scale += body.node_mass[i] * sim.ws.bodies[0].x_dot[i].norm();
    }
    return p;
  };
  Real worst = 0;
  int calls_with_impulses = 0;
  for (int k = 0; k < 500; ++k) {
    record_step_start(sim.model.bodies, sim.state.q, sim.state.v, sim.state.time,
                      sim.model.solver.dt, options, cws.self);
    int evaluations = 0;
    ASSERT_TRUE(advance_substep(sim.world, sim.inputs, sim.state, sim.model.solver.dt, sim.ws,
                                evaluations));
    Real scale = 0;
    const Vec3 before = momentum(scale);
    BodyCollisionStats stats;
    const BodySet bodies{sim.model.bodies, sim.ws.bodies, sim.state.q, sim.state.v, sim.state.time};
    resolve_body_self_collisions(options, bodies, sim.model.solver.dt, cws, stats);
    ASSERT_EQ(stats.self.estimated_starts, 0);
    if (stats.self.proximity_pairs + stats.self.continuous_collisions == 0) continue;
    ++calls_with_impulses;
    Real unused = 0;
    worst = std::max(worst, (momentum(unused) - before).norm() / scale);
  }
  std::printf("momentum: %d calls with impulses, worst |dP| / sum m|x-dot| %.3g\n",
              calls_with_impulses, worst);
  EXPECT_GT(calls_with_impulses, 10);
  EXPECT_LT(worst, 1e-9);
}

// (e) Same input, same bits, and a workspace copied mid-run (trees rebuilt) changes nothing.
TEST(SelfCollision, RunsAreBitIdentical) {
  const SceneRun a = run_scene(fold_scene(true), 400, fling_right_half);
  const SceneRun b = run_scene(fold_scene(true), 400, fling_right_half);
  EXPECT_EQ(a.hash, b.hash);
  test::Simulation c(fold_scene(true));
  fling_right_half(c);
  for (int k = 0; k < 400; ++k) {
    int evaluations = 0;
    ASSERT_TRUE(advance_substep(c.world, c.inputs, c.state, c.model.solver.dt, c.ws, evaluations));
    if (k % 100 == 50) c.ws.body_collisions = BodyCollisionWorkspace(*c.ws.body_collisions);
  }
  EXPECT_EQ(hash_state(c.state), a.hash);
}

}  // namespace
}  // namespace pbm
