#include "collide/implicit_contact.h"

#include <algorithm>

#include "deform/body_dynamics.h"
#include "deform/body_layout.h"

namespace pbm {

namespace {

// Rounds of the active set: each adds or drops at least one point, and a patch settles in two or
// three; past this the last consistent-enough set is kept (a pull of a few points for one step).
constexpr int kActiveSetRounds = 16;

}  // namespace

void prepare_implicit_contact(const BodyModel& body, BodyWorkspace& ws) {
  ImplicitContactWorkspace& ic = ws.implicit_contact;
  ic.on = body.has_local;
  if (!ic.on) return;
  const int k = body.n_generalized();
  const auto samples = static_cast<Eigen::Index>(body.contact_samples.size());
  ic.G.setZero(k, samples);
  ic.excess.setZero(samples);
  ic.weight.setZero(samples);
  ic.end_force.setZero(samples);
  ic.active.assign(static_cast<std::size_t>(samples), 0);
  ic.system.setZero(k, k);
  ic.factor = Eigen::LDLT<MatX>(k);
  ic.rhs.setZero(k);
  ic.fallback.setZero(k);
  ic.scratch.setZero(k, samples);
}

void implicit_contact_rates(const BodyModel& body, BodyWorkspace& ws, Eigen::Ref<VecX> rates) {
  ImplicitContactWorkspace& ic = ws.implicit_contact;
  const int m = ic.candidates;
  if (!ic.on || m == 0) return;
  const int ns = body.n_s;
  const bool second = body.order == DynamicsOrder::second;
  const auto G = ic.G.leftCols(m);
  const auto e = ic.excess.head(m);
  const auto beta = ic.weight.head(m);
  auto f = ic.end_force.head(m);
  for (int p = 0; p < m; ++p) ic.active[p] = e[p] > 0;
  VecX& x = ic.rhs;
  bool solved = false;
  for (int round = 0; round < kActiveSetRounds; ++round) {
    // A' + G diag(beta_active) G^T and r_g + G (e_active), through the scratch (no allocation).
    auto W = ic.scratch.leftCols(m);
    for (int p = 0; p < m; ++p) {
      if (ic.active[p]) {
        W.col(p) = beta[p] * G.col(p);
      } else {
        W.col(p).setZero();
      }
    }
    // The rows' damping at the step's end as implicit_row_damping takes it: A (1 + h nu).
    ic.system = ws.A;
    ic.system *= second ? 1.0 + ws.dt * body.damping : body.damping;
    ic.system.noalias() += W * G.transpose();
    x = ws.r_g;
    for (int p = 0; p < m; ++p) {
      if (ic.active[p]) x.noalias() += e[p] * G.col(p);
    }
    ic.factor.compute(ic.system);
    if (ic.factor.info() != Eigen::Success || !ic.factor.isPositive()) break;
    ic.factor.solveInPlace(x);
    if (!x.allFinite()) break;
    solved = true;
    // The end forces of every candidate at this solution; the set is consistent when the active
    // points push and the others would not.
    f.noalias() = G.transpose() * x;
    bool changed = false;
    for (int p = 0; p < m; ++p) {
      f[p] = e[p] - beta[p] * f[p];
      const char push = f[p] > 0;
      if (push != ic.active[p]) {
        ic.active[p] = push;
        changed = true;
      }
    }
    ic.rounds = round + 1;
    if (!changed) break;
  }
  if (!solved) {
    // A mass block the factor cannot take (a degenerate body): the explicit pushes of the points
    // inside, through the pseudo-inverse the explicit rates use.
    ic.fallback = ws.r_g;
    for (int p = 0; p < m; ++p) ic.fallback.noalias() += std::max(0.0, e[p]) * G.col(p);
    solve_generalized_mass(ws, ic.fallback, x);
    x /= second ? 1.0 + ws.dt * body.damping : body.damping;
  }
  velocity_of(rates) = ws.R * linear_part(x);
  omega_of(rates) = angular_part(x);
  if (ns > 0) rates.segment(BodyLayout::kShapeInV, ns) = x.tail(ns);
}

}  // namespace pbm
