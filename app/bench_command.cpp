#include "bench_command.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "bench_constraints.h"
#include "bench_drag.h"
#include "bench_figures.h"
#include "bench_liquid.h"
#include "bench_render.h"
#include "bullet_soft_ellipsoid.h"
#include "core/error.h"
#include "scene/scene_enum_names.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

using Clock = std::chrono::steady_clock;

constexpr Real kDropHeight = 0.005;  // [m] above the ground at the start
constexpr int kWarmUpSteps = 3;      // untimed: at 0.031 s the ball lands in the first

// Total mass of a body as the scene gives it: its mass, or its nodal mass times its nodes.
Real total_mass(const BodyDef& body) {
  if (body.material.mass > 0) return body.material.mass;
  return body.material.nodal_mass * (2 + body.tessellation.rings * body.tessellation.segments);
}

// Height of the centre of a body resting on z = 0: its lowest reference point's depth.
Real resting_height(const BodyDef& body) {
  const Real a0 = body.q_s.size() ? body.q_s[0] : 1.0;
  return body.q_s.size() >= 4 ? a0 * body.q_s[3] : a0;
}

// Rounds of timed steps per size, ours and Bullet's alternating so both see the same machine
// load; each side's fastest round is reported (the least disturbed by other processes on these
// shared machines, where one round's time varies by 30%).
constexpr int kRounds = 5;

// One size of the ball, ours and Bullet's, built once and stepped in alternating rounds.
// The substep is the model's: solver.dt, or shorter where the ball's explicit limit is past it
// (sim/model.h); Bullet steps the same dt.
struct DeformRace {
  // Fastest round [us/step]: ours at the scene's contact quadrature, ours with the centroid rule
  // (one contact point per triangle, scenes/README.md "tessellation"), Bullet's.
  double ours = 0, centroid = 0, bullet = 0;
  int nodes = 0, bullet_nodes = 0;
  Real dt = 0;
};

DeformRace race(const Scene& base, int resolution, int steps) {
  Scene scene = base;
  scene.bodies.resize(1);
  scene.bodies[0].tessellation.rings = resolution;
  scene.bodies[0].tessellation.segments = resolution;
  // The same ball at every resolution: the scene's total mass (the book's 8 kg a node at its
  // resolution) shared by the nodes; with 8 kg a node at 16k nodes it would weigh 130 t and lie
  // flat, every node in contact. It starts 5 mm above the ground, away from the slope, so the
  // timed steps are steps in contact (as Bullet's below).
  BodyDef& body = scene.bodies[0];
  body.material.mass = total_mass(base.bodies[0]);
  body.material.nodal_mass = 0;
  body.position = Vec3(-3.0, 0.0, resting_height(body) + kDropHeight);
  Simulation sim(scene);
  Scene coarse = scene;
  coarse.bodies[0].tessellation.contact = ContactQuadrature::centroid;
  Simulation sim_centroid(coarse);
  DeformRace r;
  r.nodes = sim.model.bodies[0].n_nodes();
  r.dt = sim.model.substep;
  const Real a0 = body.q_s.size() ? body.q_s[0] : 1.0;
  const Vec3 radii = body.q_s.size() >= 4
                         ? Vec3(a0 * body.q_s[1], a0 * body.q_s[2], a0 * body.q_s[3])
                         : Vec3(a0, a0, a0);
  auto peer = bench::make_bullet_soft_ellipsoid(r.nodes, radii.x(), radii.y(), radii.z(),
                                                radii.z() + kDropHeight, body.material.mass);
  r.bullet_nodes = bench::node_count(*peer);
  int evaluations = 0;
  for (int k = 0; k < kWarmUpSteps; ++k) {  // lands, and fills the caches
    advance_substep(sim.world, sim.inputs, sim.state, r.dt, sim.ws, evaluations);
    advance_substep(sim_centroid.world, sim_centroid.inputs, sim_centroid.state, r.dt,
                    sim_centroid.ws, evaluations);
    bench::step(*peer, r.dt);
  }
  const auto time_ours = [&](Simulation& s, double& fastest) {
    const auto t0 = Clock::now();
    for (int k = 0; k < steps; ++k) {
      advance_substep(s.world, s.inputs, s.state, r.dt, s.ws, evaluations);
    }
    fastest = std::min(
        fastest, std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / steps);
  };
  r.ours = r.centroid = r.bullet = 1e300;
  for (int round = 0; round < kRounds; ++round) {
    time_ours(sim, r.ours);
    time_ours(sim_centroid, r.centroid);
    const auto t0 = Clock::now();
    for (int k = 0; k < steps; ++k) bench::step(*peer, r.dt);
    r.bullet = std::min(
        r.bullet, std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / steps);
  }
  return r;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  if (o.what == "render") return run_bench_render(o.scene, std::max(5, o.steps / 2));
  if (o.what == "constraints") return run_bench_constraints(o.max_constraints);
  if (o.what == "drag") return run_bench_drag(o.scene, std::max(1, o.steps));
  if (o.what == "figures") return run_bench_figures();
  // --steps 128 adds the 128^3 grid (about 2 GB and a few minutes).
  if (o.what == "liquid") return run_bench_liquid(o.steps >= 128 ? 128 : 64);
  if (o.what != "deform") {
    spdlog::error(
        "unknown benchmark '{}' (known: deform, render, constraints, drag, figures, liquid, "
        "tradeoff, realtime)",
        o.what);
    return 2;
  }
  Scene scene;
  try {
    scene = load_scene(o.scene);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  std::printf(
      "bench deform: one step of '%s' resting on the ground, fastest of 5 rounds (dt = %g s or the "
      "ball's stability limit, last column; %s integrator), at the scene's contact points and "
      "with one per triangle (\"centroid\"), vs Bullet btSoftBody at the same dt\n",
      scene.name.c_str(), scene.solver.dt, name_of(kIntegratorKindNames, scene.solver.integrator));
  std::printf("%8s %14s %14s %14s %14s %10s %10s %12s %10s\n", "nodes", "ours us/step",
              "centroid us", "bullet nodes", "bullet us/step", "ratio", "centroid", "ours us/node",
              "dt s");
  for (int resolution : {8, 16, 32, 64, 128}) {
    const int expected = 2 + resolution * resolution;
    if (expected > o.max_nodes) break;
    const int steps = std::max(10, o.steps * 258 / expected / kRounds);
    const DeformRace r = race(scene, resolution, steps);
    std::printf("%8d %14.1f %14.1f %14d %14.1f %10.3f %10.3f %12.3f %10.4f\n", r.nodes, r.ours,
                r.centroid, r.bullet_nodes, r.bullet, r.ours / r.bullet, r.centroid / r.bullet,
                r.ours / r.nodes, r.dt);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace pbm
