// The multigrid V-cycle of MGPCG (McAdams, Sifakis and Teran, "A parallel multigrid Poisson
// solver for fluids simulation on large grids", SCA 2010) on the cell labels of the liquid grid.
// Only the three functions of liquid/pressure_multigrid.h live here; the grid itself and its
// interpolation (interpolate_velocity, interpolate_component) are liquid/mac_grid.cpp's.
//
// As in McAdams et al.: purely geometric coarsening of the labels (a coarse cell is Dirichlet if
// any child is, else unknown if any child is, else Neumann), the same 7-point Laplacian L
// rediscretized on every level with the doubled cell size (no Galerkin product), trilinear
// prolongation P with restriction R = P^T / 2^d (d the coarsened axes), and extra smoothing of the
// cells beside a boundary, where the coarse grids' voxelized boundary is furthest from the fine
// one. Unlike their damped Jacobi we smooth with red-black Gauss-Seidel, which needs no scratch
// vector and damps more per sweep; the post-smoother is the pre-smoother's exact reverse, so the
// cycle is the symmetric operator CG needs:
//   M^-1 = S + S^T - S^T L S + (I - S^T L) P M_c^-1 R (I - L S),
// (S the pre-smoother as a map from b to x, x starting at 0). The smoothing terms are positive
// definite for Gauss-Seidel (S + S^T - S^T L S = S^T D S for one sweep) and the coarse term is
// semidefinite once M_c^-1 is positive definite, which holds by induction down to the coarsest
// level's symmetric Gauss-Seidel sweeps, even where L is singular (a closed box full of liquid).
#include "liquid/pressure_multigrid.h"

#include <algorithm>
#include <cassert>
#include <cstddef>

namespace pbm {
namespace {

constexpr std::uint8_t kUnknown = 0, kDirichlet = 1, kNeumann = 2;
// An axis stops coarsening at this many cells or fewer: the coarsest level is at most 4^3 cells,
// where many sweeps are as good as an exact solve and cost less than one fine sweep.
constexpr int kCoarsestCells = 4;
// Red-black sweeps on every cell before the restriction (and after the prolongation, reversed).
constexpr int kSweeps = 2;
// Further sweeps on the cells beside a Dirichlet or Neumann cell (McAdams et al.'s boundary
// smoothing): the coarse levels misplace the boundary by up to a coarse cell, so the error there
// is the one the coarse correction leaves behind. On a 0.6-full tank MGPCG to 1e-6 takes 9, 12, 14
// iterations at 16^3, 32^3, 64^3 without them, 6, 8, 9 with 2 and 6, 6, 7 with 4, each costing
// less than a full sweep.
constexpr int kBoundarySweeps = 4;
// Symmetric sweeps that stand in for the coarsest level's exact solve (a fixed count keeps the
// cycle a fixed linear map).
constexpr int kCoarsestSweeps = 40;

std::uint8_t type_of(CellFlag f) {
  switch (f) {
    case CellFlag::full:
      return kUnknown;
    case CellFlag::surface:
    case CellFlag::empty:
    case CellFlag::outflow:
      return kDirichlet;
    case CellFlag::solid:
    case CellFlag::inflow:
      return kNeumann;
  }
  return kNeumann;
}

std::size_t at(int c) {
  return static_cast<std::size_t>(c);
}

// Whether `coarse` halves the cells of `fine` along axis a (an axis of one cell is never halved,
// and every halved axis of more than one cell loses cells).
bool halved(const MacGrid& fine, const MacGrid& coarse, int a) {
  return coarse.n[a] < fine.n[a];
}

// The fine cells along one axis that a coarse index covers: I in 1..n_c covers 2I-1 and 2I (those
// beyond the fine interior are missing, i.e. Neumann); a ghost covers the fine ghost on its side.
void children(int I, bool halve, int n_coarse, int n_fine, int& lo, int& hi) {
  if (!halve) {
    lo = hi = I;
  } else if (I == 0) {
    lo = hi = 0;
  } else if (I == n_coarse + 1) {
    lo = hi = n_fine + 1;
  } else {
    lo = 2 * I - 1;
    hi = std::min(2 * I, n_fine);
  }
}

// The trilinear stencil along one axis: fine index i lies 1/4 coarse cell from its parent
// (weight 3/4) toward the next coarse cell on its side (weight 1/4).
struct AxisStencil {
  int index[2];
  Real weight[2];
  int count;
};

AxisStencil axis_stencil(int i, bool halve) {
  if (!halve) return {{i, i}, {1.0, 0.0}, 1};
  const int parent = (i + 1) / 2;
  const int side = (i & 1) ? parent - 1 : parent + 1;
  return {{parent, side}, {0.75, 0.25}, 2};
}

// Whether a face neighbour of c is Dirichlet or Neumann.
bool beside_boundary(const MultigridLevel& lv, const int (&e)[3], int c) {
  for (int a = 0; a < 3; ++a) {
    if (lv.type[at(c - e[a])] != kUnknown || lv.type[at(c + e[a])] != kUnknown) return true;
  }
  return false;
}

// The level's diagonal and its cells of each colour from its types (no allocation: the lists
// are reserved for every interior cell by size_multigrid).
void index_level(MultigridLevel& lv) {
  const MacGrid& g = lv.grid;
  const Real w[3] = {1 / (g.h.x() * g.h.x()), 1 / (g.h.y() * g.h.y()), 1 / (g.h.z() * g.h.z())};
  const int e[3] = {g.sx, g.sy, g.sz};
  for (int colour = 0; colour < 2; ++colour) {
    lv.unknown[colour].clear();
    lv.boundary[colour].clear();
  }
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        if (lv.type[at(c)] != kUnknown) continue;
        Real diag = 0;
        for (int a = 0; a < 3; ++a) {
          for (const int nb : {c - e[a], c + e[a]}) {
            if (lv.type[at(nb)] != kNeumann) diag += w[a];
          }
        }
        lv.diag[at(c)] = diag;
        const int colour = (i + j + k) & 1;
        lv.unknown[colour].push_back(c);
        if (beside_boundary(lv, e, c)) lv.boundary[colour].push_back(c);
      }
    }
  }
}

// Gauss-Seidel updates of the cells listed: x_c = (b_c + sum over unknown nb of x_nb / h_a^2) /
// diag_c. Every cell that is not unknown holds x = 0 (each level's x starts at 0 and only
// unknown cells are written), so the sum runs over all six neighbours without a branch: the
// same sum, term for term, as over the unknown ones (the type tests and the diagonal's
// recomputation per update were most of the smoother's time, `perf record pbm simulate`).
// Within a colour the updates are independent (the 7-point stencil couples only the other
// colour), so the order inside a half-sweep does not matter for symmetry.
void relax_cells(MultigridLevel& lv, const std::vector<int>& cells) {
  const MacGrid& g = lv.grid;
  const Real w[3] = {1 / (g.h.x() * g.h.x()), 1 / (g.h.y() * g.h.y()), 1 / (g.h.z() * g.h.z())};
  const int sx = g.sx, sy = g.sy, sz = g.sz;
  Real* x = lv.x.data();
  const Real* b = lv.b.data();
  const Real* diag = lv.diag.data();
  for (const int c : cells) {
    Real sum = b[c];
    sum += w[0] * x[c - sx];
    sum += w[0] * x[c + sx];
    sum += w[1] * x[c - sy];
    sum += w[1] * x[c + sy];
    sum += w[2] * x[c - sz];
    sum += w[2] * x[c + sz];
    // An unknown cell walled in on all sides has a zero row; it keeps x = 0.
    x[c] = diag[c] > 0 ? sum / diag[c] : 0.0;
  }
}

// Updates the unknown cells of one colour, all of them or only those beside a boundary.
void relax_colour(MultigridLevel& lv, int colour, bool boundary_only) {
  relax_cells(lv, boundary_only ? lv.boundary[colour] : lv.unknown[colour]);
}

// The smoother S (red then black, all cells, then the boundary cells) and its adjoint S^T, the
// same half-sweeps in reverse order.
void pre_smooth(MultigridLevel& lv) {
  for (int s = 0; s < kSweeps; ++s) {
    relax_colour(lv, 0, false);
    relax_colour(lv, 1, false);
  }
  for (int s = 0; s < kBoundarySweeps; ++s) {
    relax_colour(lv, 0, true);
    relax_colour(lv, 1, true);
  }
}

void post_smooth(MultigridLevel& lv) {
  for (int s = 0; s < kBoundarySweeps; ++s) {
    relax_colour(lv, 1, true);
    relax_colour(lv, 0, true);
  }
  for (int s = 0; s < kSweeps; ++s) {
    relax_colour(lv, 1, false);
    relax_colour(lv, 0, false);
  }
}

// r = b - L x on the unknown cells (the restriction reads no other cell of r).
void compute_residual(MultigridLevel& lv) {
  const MacGrid& g = lv.grid;
  const Real w[3] = {1 / (g.h.x() * g.h.x()), 1 / (g.h.y() * g.h.y()), 1 / (g.h.z() * g.h.z())};
  const int e[3] = {g.sx, g.sy, g.sz};
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        if (lv.type[at(c)] != kUnknown) continue;
        Real lx = 0;
        for (int a = 0; a < 3; ++a) {
          for (const int nb : {c - e[a], c + e[a]}) {
            const std::uint8_t t = lv.type[at(nb)];
            if (t == kNeumann) continue;
            lx += w[a] * (lv.x[at(c)] - (t == kUnknown ? lv.x[at(nb)] : 0.0));
          }
        }
        lv.r[at(c)] = lv.b[at(c)] - lx;
      }
    }
  }
}

// Visits every unknown fine cell with the coarse cells of its trilinear stencil and their weights:
// visit(fine cell, coarse cell, weight). Restriction and prolongation share it, so R is exactly
// P^T up to the factor 2^-d.
template <typename Visit>
void for_each_stencil(const MultigridLevel& fine, const MultigridLevel& coarse, Visit visit) {
  const MacGrid& f = fine.grid;
  const MacGrid& c = coarse.grid;
  const bool hx = halved(f, c, 0), hy = halved(f, c, 1), hz = halved(f, c, 2);
  for (int k = 1; k <= f.n.z(); ++k) {
    const AxisStencil sk = axis_stencil(k, hz);
    for (int j = 1; j <= f.n.y(); ++j) {
      const AxisStencil sj = axis_stencil(j, hy);
      for (int i = 1; i <= f.n.x(); ++i) {
        const int cf = f.index(i, j, k);
        if (fine.type[at(cf)] != kUnknown) continue;
        const AxisStencil si = axis_stencil(i, hx);
        for (int ck = 0; ck < sk.count; ++ck) {
          for (int cj = 0; cj < sj.count; ++cj) {
            const Real wjk = sj.weight[cj] * sk.weight[ck];
            for (int ci = 0; ci < si.count; ++ci) {
              const int cc = c.index(si.index[ci], sj.index[cj], sk.index[ck]);
              if (coarse.type[at(cc)] == kUnknown) visit(cf, cc, si.weight[ci] * wjk);
            }
          }
        }
      }
    }
  }
}

// b_coarse = R r_fine with R = P^T / 2^d: the weights of each coarse cell sum to 1 away from the
// boundary, so the coarse right-hand side is a local average of the fine residual, matching the
// rediscretized (not 2^d-scaled) coarse operator.
void restrict_residual(const MultigridLevel& fine, MultigridLevel& coarse) {
  int d = 0;
  for (int a = 0; a < 3; ++a) d += halved(fine.grid, coarse.grid, a) ? 1 : 0;
  const Real scale = 1.0 / static_cast<Real>(1 << d);
  std::fill(coarse.b.begin(), coarse.b.end(), 0.0);
  for_each_stencil(fine, coarse,
                   [&](int cf, int cc, Real w) { coarse.b[at(cc)] += scale * w * fine.r[at(cf)]; });
}

// x_fine += P x_coarse (trilinear; coarse cells that are not unknown contribute 0).
void prolong_correction(const MultigridLevel& coarse, MultigridLevel& fine) {
  for_each_stencil(fine, coarse,
                   [&](int cf, int cc, Real w) { fine.x[at(cf)] += w * coarse.x[at(cc)]; });
}

}  // namespace

void size_multigrid(const MacGrid& grid, MultigridHierarchy& mg) {
  mg.levels.clear();
  MacGrid g = grid;
  for (;;) {
    MultigridLevel& lv = mg.levels.emplace_back();
    lv.grid = g;
    const std::size_t cells = static_cast<std::size_t>(g.size);
    lv.type.assign(cells, kNeumann);
    lv.x.assign(cells, 0.0);
    lv.b.assign(cells, 0.0);
    lv.r.assign(cells, 0.0);
    lv.diag.assign(cells, 0.0);
    const auto interior = static_cast<std::size_t>(g.interior_cells());
    for (int colour = 0; colour < 2; ++colour) {
      lv.unknown[colour].reserve(interior / 2 + 1);
      lv.boundary[colour].reserve(interior / 2 + 1);
    }
    bool more = false;
    for (int a = 0; a < 3; ++a) more = more || g.n[a] > kCoarsestCells;
    if (!more) break;
    // Halve the axes whose cells are the smallest (within 1.5x) among those with more than one
    // cell: the coupling 1/h^2 is strongest along them, and halving them first keeps the coarse
    // levels near isotropic, where point smoothing works (an axis of one cell is never halved).
    Real h_min = 0;
    for (int a = 0; a < 3; ++a) {
      if (g.n[a] > 1 && (h_min == 0 || g.h[a] < h_min)) h_min = g.h[a];
    }
    Eigen::Vector3i n = g.n;
    Vec3 h = g.h;
    for (int a = 0; a < 3; ++a) {
      if (g.n[a] > 1 && g.h[a] < 1.5 * h_min) {
        n[a] = (g.n[a] + 1) / 2;
        h[a] = 2 * g.h[a];
      }
    }
    g.resize(n, h, grid.origin);
  }
}

void build_multigrid(const std::vector<CellFlag>& flags, MultigridHierarchy& mg) {
  assert(!mg.levels.empty() && flags.size() == mg.levels[0].type.size());
  MultigridLevel& finest = mg.levels[0];
  const MacGrid& g0 = finest.grid;
  for (int k = 0; k <= g0.n.z() + 1; ++k) {
    for (int j = 0; j <= g0.n.y() + 1; ++j) {
      for (int i = 0; i <= g0.n.x() + 1; ++i) {
        const int c = g0.index(i, j, k);
        const std::uint8_t t = type_of(flags[at(c)]);
        // The ghost layer holds no unknowns: its cells are walls (or applied pressures).
        finest.type[at(c)] = (t == kUnknown && !g0.interior(i, j, k)) ? kNeumann : t;
      }
    }
  }
  for (std::size_t l = 1; l < mg.levels.size(); ++l) {
    const MultigridLevel& fine = mg.levels[l - 1];
    MultigridLevel& coarse = mg.levels[l];
    const MacGrid& f = fine.grid;
    const MacGrid& c = coarse.grid;
    bool halve[3];
    for (int a = 0; a < 3; ++a) halve[a] = halved(f, c, a);
    for (int K = 0; K <= c.n.z() + 1; ++K) {
      int k0, k1;
      children(K, halve[2], c.n.z(), f.n.z(), k0, k1);
      for (int J = 0; J <= c.n.y() + 1; ++J) {
        int j0, j1;
        children(J, halve[1], c.n.y(), f.n.y(), j0, j1);
        for (int I = 0; I <= c.n.x() + 1; ++I) {
          int i0, i1;
          children(I, halve[0], c.n.x(), f.n.x(), i0, i1);
          // McAdams et al.: Dirichlet if any child is, else unknown if any child is, else Neumann
          // (missing children of an odd-sized axis count as Neumann).
          bool dirichlet = false, unknown = false;
          for (int k = k0; k <= k1; ++k) {
            for (int j = j0; j <= j1; ++j) {
              for (int i = i0; i <= i1; ++i) {
                const std::uint8_t t = fine.type[at(f.index(i, j, k))];
                dirichlet = dirichlet || t == kDirichlet;
                unknown = unknown || t == kUnknown;
              }
            }
          }
          const bool ghost = !c.interior(I, J, K);
          coarse.type[at(c.index(I, J, K))] = dirichlet             ? kDirichlet
                                              : (unknown && !ghost) ? kUnknown
                                                                    : kNeumann;
        }
      }
    }
  }
  for (MultigridLevel& lv : mg.levels) index_level(lv);
}

void apply_multigrid(MultigridHierarchy& mg, const std::vector<Real>& r, std::vector<Real>& z) {
  const std::size_t n_levels = mg.levels.size();
  assert(n_levels > 0 && r.size() == mg.levels[0].b.size() && z.size() == r.size());
  MultigridLevel& finest = mg.levels[0];
  for (std::size_t c = 0; c < r.size(); ++c) {
    finest.b[c] = finest.type[c] == kUnknown ? r[c] : 0.0;
  }
  // Down: smooth from x = 0, restrict the residual (McAdams et al.'s V-cycle).
  for (std::size_t l = 0; l + 1 < n_levels; ++l) {
    MultigridLevel& lv = mg.levels[l];
    std::fill(lv.x.begin(), lv.x.end(), 0.0);
    pre_smooth(lv);
    compute_residual(lv);
    restrict_residual(lv, mg.levels[l + 1]);
  }
  // The coarsest level: symmetric Gauss-Seidel sweeps from x = 0 (red, black, red), i.e.
  // x = sum_j (I - M^-1 L)^j M^-1 b with M the symmetric Gauss-Seidel matrix: symmetric, and
  // positive definite even for a singular L, as M - L is semidefinite (the j = 0 term is M^-1,
  // the others are semidefinite). 40 of them on at most 4^3 cells: the tank tests' iterations do
  // not change at 100.
  MultigridLevel& coarsest = mg.levels[n_levels - 1];
  std::fill(coarsest.x.begin(), coarsest.x.end(), 0.0);
  for (int s = 0; s < kCoarsestSweeps; ++s) {
    relax_colour(coarsest, 0, false);
    relax_colour(coarsest, 1, false);
    relax_colour(coarsest, 0, false);
  }
  // Up: add the interpolated correction, then the reversed smoother.
  for (std::size_t l = n_levels - 1; l-- > 0;) {
    prolong_correction(mg.levels[l + 1], mg.levels[l]);
    post_smooth(mg.levels[l]);
  }
  for (std::size_t c = 0; c < z.size(); ++c) {
    z[c] = finest.type[c] == kUnknown ? finest.x[c] : 0.0;
  }
}

}  // namespace pbm
