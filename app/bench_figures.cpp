#include "bench_figures.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bullet_multibody_tree.h"
#include "figure/articulated_body.h"
#include "figure/figure_model.h"

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
  return 0;
}

}  // namespace pbm
