#include "bench_constraints.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "deform/reference_shape.h"
#include "sim/model.h"
#include "sim/simulation.h"
#include "sim/state.h"

namespace pbm {
namespace {

enum class Topology { chain, tree };

constexpr Real kLink = 0.1;  // [m] between a part's centre and each of its joints

// k + 1 small rigid parts joined by k point constraints: part i to part i - 1 (chain) or to
// part (i - 1) / 2 (binary tree), each joint at the parent's and the child's frame points, met.
Scene build_scene(Topology topology, int k, ConstraintSolverKind solver) {
  Scene s;
  s.solver.dt = 1e-3;
  s.solver.constraint_solver = solver;
  for (int i = 0; i <= k; ++i) {
    BodyDef b;
    b.name = "part" + std::to_string(i);
    b.level = DeformLevel::rigid;
    b.q_s = default_shape_parameters(ShapeKind::superquadric);
    b.q_s[0] = 0.03;
    b.q_s0 = b.q_s;
    b.tessellation.rings = 2;
    b.tessellation.segments = 3;
    b.material.mass = 0.1;
    b.material.damping = 0;
    s.bodies.push_back(b);
  }
  for (int i = 1; i <= k; ++i) {
    const int parent = topology == Topology::chain ? i - 1 : (i - 1) / 2;
    // Each child hangs at an offset of its own so the parts do not share positions.
    const Vec3 offset(kLink, 0.3 * kLink * ((i % 3) - 1), -0.2 * kLink);
    s.bodies[i].position = s.bodies[parent].position + 2 * offset;
    ConstraintDef c;
    c.name = "joint" + std::to_string(i);
    c.a.body = i;
    c.a.point = -offset;
    c.b.body = parent;
    c.b.point = offset;
    s.constraints.push_back(c);
  }
  return s;
}

// Microseconds of the constraints stage per step (one derivative evaluation per Euler step).
double time_solve(Topology topology, int k, ConstraintSolverKind solver) {
  Simulation sim(build_scene(topology, k, solver));
  const Model& model = sim.model;
  int evaluations = 0;
  // The first step warms the caches.
  advance_substep(sim.world, sim.inputs, sim.state, model.solver.dt, sim.ws, evaluations);
  const int steps = std::max(2, std::min(40, 4000 / k));
  sim.ws.clock.reset();
  for (int n = 0; n < steps; ++n) {
    advance_substep(sim.world, sim.inputs, sim.state, model.solver.dt, sim.ws, evaluations);
  }
  return 1e6 * sim.ws.clock.stage_seconds[static_cast<int>(StepStage::constraints)] / steps;
}

// Least-squares slope of log(time) against log(k) over k >= 10.
double growth_exponent(const std::vector<int>& ks, const std::vector<double>& us) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < ks.size(); ++i) {
    if (ks[i] < 10) continue;
    const double x = std::log(ks[i]), y = std::log(us[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  return n < 2 ? 0.0 : (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

int run_bench_constraints(int max_constraints) {
  std::vector<int> ks;
  for (int k : {1, 3, 10, 30, 100, 300, 1000}) {
    if (k <= max_constraints) ks.push_back(k);
  }
  std::printf(
      "bench constraints: us per step of the constraint-force solve (assemble N (7.36)-(7.41), "
      "solve N f_c + r = 0 (7.33), apply), small rigid parts, dt = 1 ms\n");
  std::printf("%6s %14s %14s %14s %14s\n", "k", "chain dense", "chain sparse", "tree dense",
              "tree sparse");
  std::vector<double> columns[4];
  for (int k : ks) {
    const double values[4] = {time_solve(Topology::chain, k, ConstraintSolverKind::dense),
                              time_solve(Topology::chain, k, ConstraintSolverKind::sparse),
                              time_solve(Topology::tree, k, ConstraintSolverKind::dense),
                              time_solve(Topology::tree, k, ConstraintSolverKind::sparse)};
    for (int c = 0; c < 4; ++c) columns[c].push_back(values[c]);
    std::printf("%6d %14.1f %14.1f %14.1f %14.1f\n", k, values[0], values[1], values[2], values[3]);
    std::fflush(stdout);
  }
  std::printf("%6s %14.2f %14.2f %14.2f %14.2f   (growth exponent: log-log slope, k >= 10)\n",
              "slope", growth_exponent(ks, columns[0]), growth_exponent(ks, columns[1]),
              growth_exponent(ks, columns[2]), growth_exponent(ks, columns[3]));
  return 0;
}

}  // namespace pbm
