#include "liquid/pressure_solvers.h"

#include <algorithm>
#include <cmath>

#include "liquid/boundary_conditions.h"
#include "liquid/pressure_multigrid.h"

namespace pbm {

namespace {

std::size_t at(int c) {
  return static_cast<std::size_t>(c);
}

// Moves cell c's open faces for a pressure change dp of c alone (16.8).
void move_faces(const MacGrid& g, const LiquidWorkspace& ws, Real dt, int c, Real dp,
                MacField& field) {
  for (int a = 0; a < 3; ++a) {
    const int e = g.stride(a);
    const Real k = dt / g.h[a] * dp;
    if (!fixes_velocity(ws.flags[at(c + e)])) field.u[a][at(c)] += k * ws.face_scale[a][at(c)];
    if (!fixes_velocity(ws.flags[at(c - e)])) {
      field.u[a][at(c - e)] -= k * ws.face_scale[a][at(c - e)];
    }
  }
}

// (A x)_c on the Full cells (x is read on Full cells only: its other entries are stale).
void apply_a(const MacGrid& g, const LiquidWorkspace& ws, Real dt, const std::vector<Real>& x,
             std::vector<Real>& y) {
  auto value = [&](int c) { return ws.flags[at(c)] == CellFlag::full ? x[at(c)] : 0.0; };
  const Real w[3] = {dt / (g.h.x() * g.h.x()), dt / (g.h.y() * g.h.y()), dt / (g.h.z() * g.h.z())};
  for (int c : ws.cell_of_row) {
    y[at(c)] = ws.diag[at(c)] * x[at(c)] - w[0] * (value(c - g.sx) + value(c + g.sx)) -
               w[1] * (value(c - g.sy) + value(c + g.sy)) -
               w[2] * (value(c - g.sz) + value(c + g.sz));
  }
}

Real dot(const LiquidWorkspace& ws, const std::vector<Real>& a, const std::vector<Real>& b) {
  Real sum = 0;
  for (int c : ws.cell_of_row) sum += a[at(c)] * b[at(c)];
  return sum;
}

Real max_abs(const LiquidWorkspace& ws, const std::vector<Real>& a) {
  Real m = 0;
  for (int c : ws.cell_of_row) m = std::max(m, std::abs(a[at(c)]));
  return m;
}

// A's entry between c and its + neighbour along a: -dt / h_a^2 when both are Full.
Real off_diagonal(const MacGrid& g, const LiquidWorkspace& ws, Real dt, int c, int a) {
  const int e = g.stride(a);
  return ws.flags[at(c + e)] == CellFlag::full ? -dt / (g.h[a] * g.h[a]) : 0.0;
}

// The modified incomplete Cholesky factor's inverse diagonal (tau 0.97, safety 0.25).
void build_mic(const MacGrid& g, LiquidWorkspace& ws, Real dt) {
  constexpr Real kTau = 0.97, kSigma = 0.25;
  for (int c : ws.cell_of_row) {
    Real e = ws.diag[at(c)];
    for (int a = 0; a < 3; ++a) {
      const int m = c - g.stride(a);
      if (ws.flags[at(m)] != CellFlag::full) continue;
      const Real am = off_diagonal(g, ws, dt, m, a);
      const Real pm = ws.precon[at(m)];
      e -= (am * pm) * (am * pm);
      Real others = 0;
      for (int b = 0; b < 3; ++b) {
        if (b != a) others += off_diagonal(g, ws, dt, m, b);
      }
      e -= kTau * am * others * pm * pm;
    }
    if (e < kSigma * ws.diag[at(c)]) e = ws.diag[at(c)];
    ws.precon[at(c)] = 1 / std::sqrt(e);
  }
}

void apply_mic(const MacGrid& g, LiquidWorkspace& ws, Real dt, const std::vector<Real>& r,
               std::vector<Real>& z) {
  std::vector<Real>& q = ws.q;  // the forward solve's result, reused
  for (int c : ws.cell_of_row) {
    Real t = r[at(c)];
    for (int a = 0; a < 3; ++a) {
      const int m = c - g.stride(a);
      if (ws.flags[at(m)] == CellFlag::full) {
        t -= off_diagonal(g, ws, dt, m, a) * ws.precon[at(m)] * q[at(m)];
      }
    }
    q[at(c)] = t * ws.precon[at(c)];
  }
  for (auto it = ws.cell_of_row.rbegin(); it != ws.cell_of_row.rend(); ++it) {
    const int c = *it;
    Real t = q[at(c)];
    for (int a = 0; a < 3; ++a) {
      const int p = c + g.stride(a);
      if (ws.flags[at(p)] == CellFlag::full) {
        t -= off_diagonal(g, ws, dt, c, a) * ws.precon[at(c)] * z[at(p)];
      }
    }
    z[at(c)] = t * ws.precon[at(c)];
  }
}

}  // namespace

void relax_pressure(const LiquidModel& model, Real dt, const PressureSolveOptions& options,
                    LiquidWorkspace& ws, MacField& field, std::vector<Real>& pressure,
                    PressureSolveStats& stats) {
  const MacGrid& g = model.grid;
  const Real beta0 = model.def.relaxation;
  // No sweep where every cell already meets epsilon: the pressure carries from substep to
  // substep, and an over-relaxed sweep (beta_0 > 1) applied to the rounding errors of a converged
  // field each substep amplifies them (by 1.8 a substep at beta_0 = 1.7 on still water), where a
  // sweep only when needed leaves them to grow by rounding alone.
  if (max_full_divergence(model, ws, field) < options.tolerance) {
    stats.converged = true;
    return;
  }
  for (int sweep = 0; sweep < options.max_iterations; ++sweep) {
    Real worst = 0;
    for (int c : ws.cell_of_row) {
      const Real d = ws.target[at(c)] - cell_divergence(g, field, c);  // (16.5)
      worst = std::max(worst, std::abs(d));
      const Real dp = beta0 * d / ws.diag[at(c)];  // (16.6), (16.7)
      move_faces(g, ws, dt, c, dp, field);         // (16.8)
      pressure[at(c)] += dp;                       // (16.9)
    }
    stats.iterations = sweep + 1;
    // The sweep's D were each taken before the cell's own update and its neighbours' later ones:
    // the criterion is the divergence the sweep leaves.
    if (worst < options.tolerance && max_full_divergence(model, ws, field) < options.tolerance) {
      stats.converged = true;
      break;
    }
  }
}

void conjugate_gradient_pressure(const LiquidModel& model, PressureSolver solver, Real dt,
                                 bool dirichlet, const PressureSolveOptions& options,
                                 LiquidWorkspace& ws, MacField& field, std::vector<Real>& pressure,
                                 PressureSolveStats& stats) {
  const MacGrid& g = model.grid;
  std::vector<Real>& x = ws.dp;
  std::vector<Real>& r = ws.r;
  std::vector<Real>& z = ws.z;
  std::vector<Real>& s = ws.s;
  for (int c : ws.cell_of_row) {
    x[at(c)] = 0;
    r[at(c)] = ws.target[at(c)] - cell_divergence(g, field, c);  // D of (16.5)
  }
  if (!dirichlet) {
    // Only the part of D with zero mean can be removed by pressure in a closed, full box.
    Real mean = 0;
    for (int c : ws.cell_of_row) mean += r[at(c)];
    mean /= static_cast<Real>(ws.cell_of_row.size());
    for (int c : ws.cell_of_row) r[at(c)] -= mean;
  }
  const Real b_norm = std::sqrt(dot(ws, r, r));
  auto done = [&](const std::vector<Real>& res) {
    if (options.relative > 0) return std::sqrt(dot(ws, res, res)) <= options.relative * b_norm;
    return max_abs(ws, res) < options.tolerance;
  };
  auto precondition = [&](const std::vector<Real>& in, std::vector<Real>& out) {
    if (solver == PressureSolver::mgpcg) {
      apply_multigrid(ws.multigrid, in, out);
      for (int c : ws.cell_of_row) out[at(c)] /= dt;  // A ~ dt L
    } else {
      apply_mic(g, ws, dt, in, out);
    }
  };
  if (solver == PressureSolver::mgpcg) {
    build_multigrid(ws.flags, ws.multigrid);
  } else {
    build_mic(g, ws, dt);
  }
  if (!done(r)) {
    precondition(r, z);
    for (int c : ws.cell_of_row) s[at(c)] = z[at(c)];
    Real rho = dot(ws, z, r);
    for (int it = 0; it < options.max_iterations; ++it) {
      std::vector<Real>& as = ws.q;  // free between preconditioner calls
      apply_a(g, ws, dt, s, as);
      const Real sas = dot(ws, s, as);
      if (!(sas > 0)) break;
      const Real alpha = rho / sas;
      for (int c : ws.cell_of_row) {
        x[at(c)] += alpha * s[at(c)];
        r[at(c)] -= alpha * as[at(c)];
      }
      stats.iterations = it + 1;
      if (done(r)) break;
      precondition(r, z);
      const Real rho_new = dot(ws, z, r);
      const Real beta = rho_new / rho;
      rho = rho_new;
      for (int c : ws.cell_of_row) s[at(c)] = z[at(c)] + beta * s[at(c)];
    }
  }
  stats.converged = done(r);
  stats.residual = b_norm > 0 ? std::sqrt(dot(ws, r, r)) / b_norm : 0;
  // (16.8), (16.9) for the whole dp: each face once, from the Full cell below it or, when the
  // cell below is not Full, from the one above.
  for (int c : ws.cell_of_row) {
    pressure[at(c)] += x[at(c)];
    for (int a = 0; a < 3; ++a) {
      const int e = g.stride(a);
      const Real k = dt / g.h[a];
      const CellFlag up = ws.flags[at(c + e)], down = ws.flags[at(c - e)];
      if (!fixes_velocity(up)) {
        const Real x_up = up == CellFlag::full ? x[at(c + e)] : 0.0;
        field.u[a][at(c)] += k * ws.face_scale[a][at(c)] * (x[at(c)] - x_up);
      }
      if (!fixes_velocity(down) && down != CellFlag::full) {
        field.u[a][at(c - e)] -= k * ws.face_scale[a][at(c - e)] * x[at(c)];
      }
    }
  }
}

}  // namespace pbm
