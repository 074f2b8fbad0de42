#include "bench_figures.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "bullet_multibody_ground.h"
#include "bullet_multibody_tree.h"
#include "figure/articulated_body.h"
#include "figure/figure_model.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

using Clock = std::chrono::steady_clock;
const Vec3 kGravity(0, 0, -9.81);
constexpr Real kStep = 1e-3;  // [s]
constexpr int kRounds = 7;    // alternating rounds; each side's fastest is reported

enum class Topology { chain, tree };

// n revolute links hanging from a fixed base: each from the previous one (chain) or from link
// (i - 1) / 2 (a binary tree, limbs branching like a figure's), axes turning from link to link.
std::vector<bench::MultibodyLink> links_of(Topology topology, int n) {
  std::vector<bench::MultibodyLink> links(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    bench::MultibodyLink& l = links[static_cast<std::size_t>(i)];
    l.parent = i == 0 ? -1 : topology == Topology::chain ? i - 1 : (i - 1) / 2;
    l.mass = 1.0 + 0.1 * (i % 5);
    l.principal = Vec3(0.02, 0.02 + 0.001 * (i % 3), 0.005);
    l.parent_com_to_pivot = Vec3(0.02 * ((i % 3) - 1), 0.01, l.parent < 0 ? 0.0 : -0.15);
    l.pivot_to_com = Vec3(0, 0, -0.15);
    l.rot_parent_to_this = Eigen::AngleAxis<Real>(0.3, Vec3(1, 0, 0)).toRotationMatrix();
    l.axis = Vec3(i % 3 == 0, i % 3 == 1, i % 3 == 2);
  }
  return links;
}

struct Timing {
  double ours_aba = 1e300, ours_step = 1e300, bullet_aba = 1e300, bullet_step = 1e300;
};

template <class F>
void time_fastest(int calls, double& fastest, F&& f) {
  const auto t0 = Clock::now();
  for (int k = 0; k < calls; ++k) f();
  fastest = std::min(fastest,
                     std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / calls);
}

Timing race(Topology topology, int n) {
  const std::vector<bench::MultibodyLink> links = links_of(topology, n);
  const FigureModel figure = bench::figure_of_links(links);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  bench::BulletMultibodyTreePtr peer = bench::make_bullet_multibody_tree(links);
  VecX q = VecX::Constant(n, 0.2), v = VecX::Constant(n, 0.1), qdd(n), q_dot(n);
  const VecX tau = VecX::Zero(n), q0 = q, v0 = v;
  bench::set_state(*peer, q, v);
  const int calls = std::max(20, 40000 / n);
  Timing t;
  for (int round = 0; round < kRounds; ++round) {
    time_fastest(calls, t.ours_aba, [&] {
      forward_dynamics(figure, q.data(), v.data(), tau.data(), {}, kGravity, ws, qdd.data());
    });
    time_fastest(calls, t.bullet_aba, [&] { bench::accelerations(*peer, kGravity); });
    // Steps from the same start each round, so both swing the same motion.
    q = q0;
    v = v0;
    time_fastest(calls, t.ours_step, [&] {
      forward_dynamics(figure, q.data(), v.data(), tau.data(), {}, kGravity, ws, qdd.data());
      v += kStep * qdd;
      figure_q_dot(figure, q.data(), v.data(), q_dot.data());
      q += kStep * q_dot;
      figure_normalize(figure, q.data());
    });
    bench::set_state(*peer, q0, v0);
    time_fastest(calls, t.bullet_step, [&] { bench::step(*peer, kGravity, kStep); });
    bench::set_state(*peer, q0, v0);
  }
  return t;
}

// The step with contacts: n capsules (radius 0.04 m, 0.3 m from joint to joint) lying end to end
// along +x on the ground, like a rope on the floor, their joints turning about y (up and down) and
// z (sideways) in turn, the first one's pivot fixed at the ground's height plus the radius. Ours
// is the World's step of the scene (contact springs at each capsule's two end spheres, the impact
// stage, ABA, Euler); Bullet's is btMultiBodyDynamicsWorld's (its collision detection, its
// multibody constraint solver for the contacts, ABA). Both settle for 0.2 s first, untimed.
constexpr Real kRadius = 0.04, kLink = 0.3, kFriction = 0.5;

Scene ground_chain_scene(int n) {
  Scene scene;
  scene.name = "ground-chain";
  scene.solver.dt = kStep;
  scene.solver.fps = 1.0 / kStep;
  scene.solver.integrator = IntegratorKind::euler;
  scene.gravity = kGravity;
  ObstacleDef ground;
  ground.name = "ground";
  ground.friction = kFriction;
  scene.obstacles.push_back(ground);
  FigureDef figure;
  figure.name = "chain";
  figure.self_collisions = false;
  for (int i = 0; i < n; ++i) {
    SegmentDef s;
    s.name = "s" + std::to_string(i);
    s.parent = i == 0 ? "" : "s" + std::to_string(i - 1);
    s.joint.axis = i % 2 == 0 ? Vec3::UnitY() : Vec3::UnitZ();
    // The first joint's frame turns the segment's -z (where it extends) to the world's +x.
    s.joint.position = i == 0 ? Vec3(0, 0, kRadius) : Vec3(0, 0, -kLink);
    if (i == 0) s.joint.orientation = Vec4(std::sqrt(0.5), 0, -std::sqrt(0.5), 0);
    s.shape.kind = SegmentShapeKind::capsule;
    s.shape.size = Vec3(kRadius, kRadius, kLink / 2 - kRadius);
    s.shape.center = Vec3(0, 0, -kLink / 2);
    figure.segments.push_back(s);
  }
  scene.figures.push_back(figure);
  return scene;
}

// Bullet's links of the same chain, with the masses and inertias our model computed.
std::vector<bench::MultibodyLink> ground_chain_links(const FigureModel& figure) {
  std::vector<bench::MultibodyLink> links;
  for (int i = 0; i < figure.size(); ++i) {
    const SpatialInertia& I = figure.segments[static_cast<std::size_t>(i)].inertia;
    bench::MultibodyLink l;
    l.parent = i - 1;
    l.mass = I.m;
    l.principal = I.I_c.diagonal();
    l.pivot_to_com = I.c;
    l.parent_com_to_pivot = i == 0 ? Vec3::Zero() : Vec3(0, 0, -kLink / 2);
    // Parent coordinates to the link's: the transpose of its joint frame's rotation.
    l.rot_parent_to_this =
        i == 0 ? Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix()
               : Mat3::Identity();
    l.axis = i % 2 == 0 ? Vec3::UnitY() : Vec3::UnitZ();
    links.push_back(l);
  }
  return links;
}

struct ContactTiming {
  double ours = 1e300, bullet = 1e300;  // us per step
  int ours_contacts = 0, bullet_contacts = 0;
  Real ours_height = 0, bullet_height = 0;  // mean centre height after the race [m]
};

ContactTiming race_contacts(int n) {
  Simulation sim(ground_chain_scene(n));
  const FigureModel& figure = sim.model.figures[0].model;
  const std::vector<bench::LinkCapsule> capsules(static_cast<std::size_t>(n),
                                                 {kRadius, kLink / 2 - kRadius});
  bench::BulletMultibodyGroundPtr peer = bench::make_bullet_multibody_ground(
      ground_chain_links(figure), capsules, Vec3(0, 0, kRadius), kGravity, kFriction);
  int evaluations = 0;
  auto ours_step = [&] {
    if (!advance_substep(sim.world, sim.inputs, sim.state, kStep, sim.ws, evaluations)) {
      throw std::runtime_error("bench figures: our ground chain's step failed");
    }
  };
  for (int k = 0; k < 200; ++k) {
    ours_step();
    bench::step(*peer, kStep);
  }
  const int calls = std::max(20, 4000 / n);
  ContactTiming t;
  for (int round = 0; round < kRounds; ++round) {
    time_fastest(calls, t.ours, ours_step);
    time_fastest(calls, t.bullet, [&] { bench::step(*peer, kStep); });
  }
  measure_state(sim.world, sim.inputs, sim.state, sim.ws, sim.stats);
  t.ours_contacts = sim.stats.figures[0].contacts;
  t.bullet_contacts = bench::contact_points(*peer);
  std::vector<SpatialTransform> world;
  segment_world_transforms(figure, sim.ws.figures->each[0], world);
  for (int i = 0; i < n; ++i) {
    const SpatialTransform& X = world[static_cast<std::size_t>(i)];
    t.ours_height += (X.r + X.E.transpose() * figure.segments[i].inertia.c).z() / n;
    t.bullet_height += bench::link_height(*peer, i) / n;
  }
  return t;
}

}  // namespace

int run_bench_figures() {
  std::printf(
      "bench figures: microseconds per ABA call and per step (dt = %g s, no contacts), fastest of "
      "%d alternating rounds, ours vs Bullet btMultiBody on the same revolute tree\n",
      kStep, kRounds);
  std::printf("%8s %5s %12s %12s %8s %12s %12s %8s %12s\n", "topology", "DOF", "ours ABA us",
              "bullet ABA", "ratio", "ours step", "bullet step", "ratio", "ours us/DOF");
  for (Topology topology : {Topology::chain, Topology::tree}) {
    for (int n : {7, 15, 30, 60, 120}) {
      const Timing t = race(topology, n);
      std::printf("%8s %5d %12.2f %12.2f %8.3f %12.2f %12.2f %8.3f %12.3f\n",
                  topology == Topology::chain ? "chain" : "tree", n, t.ours_aba, t.bullet_aba,
                  t.ours_aba / t.bullet_aba, t.ours_step, t.bullet_step,
                  t.ours_step / t.bullet_step, t.ours_step / n);
      std::fflush(stdout);
    }
  }
  std::printf(
      "\nstep with contacts: a chain of capsules lying on the ground (joints about y and z in "
      "turn, mu %g, dt = %g s), microseconds per step after 0.2 s of settling, fastest of %d "
      "alternating rounds; contact points and mean centre height at the end (radius %g m)\n",
      kFriction, kStep, kRounds, kRadius);
  std::printf("%5s %12s %12s %8s %12s %12s %10s %10s %12s\n", "DOF", "ours us", "bullet us",
              "ratio", "ours points", "bullet pts", "ours z m", "bullet z", "ours us/DOF");
  for (int n : {7, 15, 30, 60, 120}) {
    const ContactTiming t = race_contacts(n);
    std::printf("%5d %12.2f %12.2f %8.3f %12d %12d %10.4f %10.4f %12.3f\n", n, t.ours, t.bullet,
                t.ours / t.bullet, t.ours_contacts, t.bullet_contacts, t.ours_height,
                t.bullet_height, t.ours / n);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace pbm
