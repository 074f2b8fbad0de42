#include "integrate/integrators.h"

#include <algorithm>
#include <cmath>

namespace pbm {

void IntegratorWorkspace::resize(int n_q, int n_v) {
  for (int i = 0; i < 7; ++i) {
    kq[i].setZero(n_q);
    kv[i].setZero(n_v);
  }
  q_stage.setZero(n_q);
  v_stage.setZero(n_v);
  q_err.setZero(n_q);
  v_err.setZero(n_v);
}

void euler_step(const DerivativeFn& f, const KinematicFn& kin, Real t, Real dt, VecX& q, VecX& v,
                IntegratorWorkspace& ws, IntegrationStats& stats) {
  f(t, q, v, ws.kq[0], ws.kv[0]);
  ++stats.evaluations;
  v += dt * ws.kv[0];
  kin(q, v, ws.kq[0]);
  q += dt * ws.kq[0];
  ++stats.accepted;
}

void rk4_step(const DerivativeFn& f, Real t, Real dt, VecX& q, VecX& v, IntegratorWorkspace& ws,
              IntegrationStats& stats) {
  f(t, q, v, ws.kq[0], ws.kv[0]);
  ws.q_stage = q + 0.5 * dt * ws.kq[0];
  ws.v_stage = v + 0.5 * dt * ws.kv[0];
  f(t + 0.5 * dt, ws.q_stage, ws.v_stage, ws.kq[1], ws.kv[1]);
  ws.q_stage = q + 0.5 * dt * ws.kq[1];
  ws.v_stage = v + 0.5 * dt * ws.kv[1];
  f(t + 0.5 * dt, ws.q_stage, ws.v_stage, ws.kq[2], ws.kv[2]);
  ws.q_stage = q + dt * ws.kq[2];
  ws.v_stage = v + dt * ws.kv[2];
  f(t + dt, ws.q_stage, ws.v_stage, ws.kq[3], ws.kv[3]);
  q += dt / 6.0 * (ws.kq[0] + 2.0 * ws.kq[1] + 2.0 * ws.kq[2] + ws.kq[3]);
  v += dt / 6.0 * (ws.kv[0] + 2.0 * ws.kv[1] + 2.0 * ws.kv[2] + ws.kv[3]);
  stats.evaluations += 4;
  ++stats.accepted;
}

namespace {
// Dormand-Prince 5(4) tableau.
constexpr Real c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr Real a21 = 1.0 / 5;
constexpr Real a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr Real a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr Real a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
               a54 = -212.0 / 729;
constexpr Real a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
               a65 = -5103.0 / 18656;
constexpr Real b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784,
               b6 = 11.0 / 84;
// b - b* (fifth minus fourth order weights) for the error estimate.
constexpr Real e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
               e6 = 22.0 / 525, e7 = -1.0 / 40;
}  // namespace

bool rk45_advance(const DerivativeFn& f, Real t, Real dt, Real tol, VecX& q, VecX& v,
                  Real& step_size, IntegratorWorkspace& ws, IntegrationStats& stats) {
  const Real t_end = t + dt;
  Real h = step_size > 0 ? std::min(step_size, dt) : dt;
  auto stage = [&](int k, Real tk, std::initializer_list<std::pair<int, Real>> terms, Real hh) {
    ws.q_stage = q;
    ws.v_stage = v;
    for (const auto& [j, a] : terms) {
      ws.q_stage += hh * a * ws.kq[j];
      ws.v_stage += hh * a * ws.kv[j];
    }
    f(tk, ws.q_stage, ws.v_stage, ws.kq[k], ws.kv[k]);
    ++stats.evaluations;
  };
  while (t < t_end) {
    // Land exactly on t_end: never leave a sliver step.
    if (t + h >= t_end || t + 1.1 * h >= t_end) h = t_end - t;
    f(t, q, v, ws.kq[0], ws.kv[0]);
    ++stats.evaluations;
    stage(1, t + c2 * h, {{0, a21}}, h);
    stage(2, t + c3 * h, {{0, a31}, {1, a32}}, h);
    stage(3, t + c4 * h, {{0, a41}, {1, a42}, {2, a43}}, h);
    stage(4, t + c5 * h, {{0, a51}, {1, a52}, {2, a53}, {3, a54}}, h);
    stage(5, t + h, {{0, a61}, {1, a62}, {2, a63}, {3, a64}, {4, a65}}, h);
    stage(6, t + h, {{0, b1}, {2, b3}, {3, b4}, {4, b5}, {5, b6}}, h);
    // The 7th stage is the solution (FSAL); its state is q_stage / v_stage.
    ws.q_err = h * (e1 * ws.kq[0] + e3 * ws.kq[2] + e4 * ws.kq[3] + e5 * ws.kq[4] + e6 * ws.kq[5] +
                    e7 * ws.kq[6]);
    ws.v_err = h * (e1 * ws.kv[0] + e3 * ws.kv[2] + e4 * ws.kv[3] + e5 * ws.kv[4] + e6 * ws.kv[5] +
                    e7 * ws.kv[6]);
    Real err = 0;
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      err = std::max(err, std::abs(ws.q_err[i]) / (tol + tol * std::abs(q[i])));
    }
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      err = std::max(err, std::abs(ws.v_err[i]) / (tol + tol * std::abs(v[i])));
    }
    if (!std::isfinite(err)) err = 1e10;
    if (err <= 1.0) {
      q = ws.q_stage;
      v = ws.v_stage;
      t += h;
      ++stats.accepted;
      stats.error = err;
      const Real grow = err > 0 ? std::min(5.0, 0.9 * std::pow(err, -0.2)) : 5.0;
      const Real h_next = h * grow;
      if (t < t_end) h = h_next;
      step_size = h_next;
    } else {
      ++stats.rejected;
      h *= std::max(0.1, 0.9 * std::pow(err, -0.25));
      if (h < 1e-12 * std::max(1.0, std::abs(t_end))) return false;
    }
  }
  return true;
}

}  // namespace pbm
