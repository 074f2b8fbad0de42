// The multigrid preconditioner of MGPCG (liquid/pressure_multigrid.h; McAdams, Sifakis and Teran
// 2010) under a conjugate gradient written here against an operator L written here: iterations
// that do not grow with the resolution on a tank with a free surface (3D and 2D) nor with flat
// cells, a symmetric and positive definite V-cycle (else CG loses its guarantees), the discrete
// closed-form solution on an anisotropic grid, an irregular domain with obstacles, air pockets and
// odd sizes, a closed box (singular L), no allocation in build and apply, and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "liquid/pressure_multigrid.h"

namespace {
bool g_counting = false;
long g_allocations = 0;
}  // namespace

// Counts the allocations of the calls under test (std::vector allocates through operator new).
void* operator new(std::size_t size) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace pbm {
namespace {

constexpr Real kPi = 3.14159265358979323846;

struct Problem {
  MacGrid grid;
  std::vector<CellFlag> flags;  // per cell; the ghost layer Solid
  CellFlag& at(int i, int j, int k) { return flags[static_cast<std::size_t>(grid.index(i, j, k))]; }
};

Problem empty_box(const Eigen::Vector3i& n, const Vec3& h) {
  Problem p;
  p.grid.resize(n, h, Vec3::Zero());
  p.flags.assign(static_cast<std::size_t>(p.grid.size), CellFlag::solid);
  for (int k = 1; k <= n.z(); ++k) {
    for (int j = 1; j <= n.y(); ++j) {
      for (int i = 1; i <= n.x(); ++i) p.at(i, j, k) = CellFlag::empty;
    }
  }
  return p;
}

// Liquid in the lower `fill` of a walled box: Full below layer k_s, Surface at it, Empty above.
Problem tank(const Eigen::Vector3i& n, const Vec3& h, Real fill, int* k_surface = nullptr) {
  Problem p = empty_box(n, h);
  const int ks = static_cast<int>(std::lround(fill * n.z()));
  for (int k = 1; k <= ks; ++k) {
    for (int j = 1; j <= n.y(); ++j) {
      for (int i = 1; i <= n.x(); ++i) p.at(i, j, k) = k < ks ? CellFlag::full : CellFlag::surface;
    }
  }
  if (k_surface) *k_surface = ks;
  return p;
}

bool is_unknown(const Problem& p, int c) {
  return p.flags[static_cast<std::size_t>(c)] == CellFlag::full;
}

// (L x)_c over the Full cells: (x_c - x_nb) / h_a^2 across every face not shared with a Solid or
// Inflow cell, x_nb = 0 beyond a Surface, Empty or Outflow cell; 0 on the other cells.
void apply_laplacian(const Problem& p, const std::vector<Real>& x, std::vector<Real>& out) {
  const MacGrid& g = p.grid;
  for (int c = 0; c < g.size; ++c) out[static_cast<std::size_t>(c)] = 0;
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        if (!is_unknown(p, c)) continue;
        Real sum = 0;
        for (int a = 0; a < 3; ++a) {
          for (const int nb : {c - g.stride(a), c + g.stride(a)}) {
            const CellFlag f = p.flags[static_cast<std::size_t>(nb)];
            if (f == CellFlag::solid || f == CellFlag::inflow) continue;
            const Real x_nb = f == CellFlag::full ? x[static_cast<std::size_t>(nb)] : 0.0;
            sum += (x[static_cast<std::size_t>(c)] - x_nb) / (g.h[a] * g.h[a]);
          }
        }
        out[static_cast<std::size_t>(c)] = sum;
      }
    }
  }
}

Real dot(const Problem& p, const std::vector<Real>& a, const std::vector<Real>& b) {
  Real s = 0;
  for (int c = 0; c < p.grid.size; ++c) {
    if (is_unknown(p, c)) s += a[static_cast<std::size_t>(c)] * b[static_cast<std::size_t>(c)];
  }
  return s;
}

// Uniform in [-1/2, 1/2) on the Full cells, 0 elsewhere (the engine's mt19937 stream, converted
// here rather than by std::uniform_real_distribution, whose output is implementation-defined).
std::vector<Real> random_field(const Problem& p, unsigned seed) {
  std::mt19937 gen(seed);
  std::vector<Real> v(static_cast<std::size_t>(p.grid.size), 0.0);
  for (int c = 0; c < p.grid.size; ++c) {
    const Real u = static_cast<Real>(gen()) / 4294967296.0 - 0.5;
    if (is_unknown(p, c)) v[static_cast<std::size_t>(c)] = u;
  }
  return v;
}

struct Solve {
  int iterations = 0;
  Real residual = 0;  // ||b - L x|| / ||b|| at the end, recomputed from x
};

// Conjugate gradients on L x = b preconditioned by one V-cycle per iteration, from x = 0, until
// ||r|| <= tolerance ||b||.
Solve solve_mgpcg(const Problem& p, MultigridHierarchy& mg, const std::vector<Real>& b,
                  std::vector<Real>& x, Real tolerance, int max_iterations) {
  const std::size_t size = static_cast<std::size_t>(p.grid.size);
  std::vector<Real> r = b, z(size), s(size), q(size);
  x.assign(size, 0.0);
  const Real b_norm = std::sqrt(dot(p, b, b));
  Solve out;
  apply_multigrid(mg, r, z);
  s = z;
  Real rho = dot(p, z, r);
  for (int it = 0; it < max_iterations; ++it) {
    apply_laplacian(p, s, q);
    const Real alpha = rho / dot(p, s, q);
    for (std::size_t c = 0; c < size; ++c) {
      x[c] += alpha * s[c];
      r[c] -= alpha * q[c];
    }
    out.iterations = it + 1;
    if (std::sqrt(dot(p, r, r)) <= tolerance * b_norm) break;
    apply_multigrid(mg, r, z);
    const Real rho_new = dot(p, z, r);
    const Real beta = rho_new / rho;
    rho = rho_new;
    for (std::size_t c = 0; c < size; ++c) s[c] = z[c] + beta * s[c];
  }
  apply_laplacian(p, x, q);
  for (std::size_t c = 0; c < size; ++c) q[c] = b[c] - q[c];
  out.residual = std::sqrt(dot(p, q, q)) / b_norm;
  return out;
}

Solve solve_random(const Problem& p, Real tolerance, int max_iterations, unsigned seed = 1) {
  MultigridHierarchy mg;
  size_multigrid(p.grid, mg);
  build_multigrid(p.flags, mg);
  const std::vector<Real> b = random_field(p, seed);
  std::vector<Real> x;
  return solve_mgpcg(p, mg, b, x, tolerance, max_iterations);
}

void report(const std::string& name, const Solve& s) {
  std::printf("%-34s %2d iterations, residual %.2e\n", name.c_str(), s.iterations, s.residual);
  testing::Test::RecordProperty(name, s.iterations);
}

TEST(LiquidMultigrid, TankIterationsDoNotGrowWithResolution) {
  int iterations[3] = {};
  const int sizes[3] = {16, 32, 64};
  for (int s = 0; s < 3; ++s) {
    const int n = sizes[s];
    const Problem p = tank({n, n, n}, Vec3::Constant(1.0 / n), 0.6);
    const Solve solve = solve_random(p, 1e-6, 100);
    report("tank_" + std::to_string(n) + "^3", solve);
    EXPECT_LE(solve.iterations, 20) << n;
    EXPECT_LE(solve.residual, 1e-6) << n;
    iterations[s] = solve.iterations;
  }
  EXPECT_LE(iterations[2] - iterations[0], 2);
}

TEST(LiquidMultigrid, TwoDimensionalTankKeepsItsThinAxis) {
  const Problem p = tank({64, 1, 64}, Vec3(1.0 / 64, 0.1, 1.0 / 64), 0.6);
  MultigridHierarchy mg;
  size_multigrid(p.grid, mg);
  ASSERT_GT(mg.levels.size(), 3u);
  for (const MultigridLevel& lv : mg.levels) EXPECT_EQ(lv.grid.n.y(), 1);
  EXPECT_LE(mg.levels.back().grid.n.x(), 4);
  const Solve solve = solve_random(p, 1e-6, 100);
  report("tank_64x1x64", solve);
  EXPECT_LE(solve.iterations, 20);
  EXPECT_LE(solve.residual, 1e-6);
}

// Cells 2 and 4 times finer along one axis: the hierarchy halves that axis alone until the cells
// are near cubes (else point smoothing stalls on the strong coupling: always halving every axis
// takes 9 and 13 iterations here), then all of them; within 2 iterations of the same tank in cubes.
TEST(LiquidMultigrid, FlatCellsConvergeLikeCubes) {
  const Solve cube = solve_random(tank({32, 32, 32}, Vec3::Constant(1.0 / 32), 0.6), 1e-6, 100);
  const Problem flat = tank({32, 32, 64}, Vec3(1.0 / 32, 1.0 / 32, 1.0 / 64), 0.6);
  MultigridHierarchy mg;
  size_multigrid(flat.grid, mg);
  ASSERT_GT(mg.levels.size(), 1u);
  EXPECT_EQ(mg.levels[1].grid.n, Eigen::Vector3i(32, 32, 32));
  const Solve flat_solve = solve_random(flat, 1e-6, 100);
  report("tank_32x32x64_hz=h/2", flat_solve);
  EXPECT_LE(flat_solve.iterations, cube.iterations + 2);
  const Problem thin = tank({16, 64, 48}, Vec3(1.0 / 16, 1.0 / 64, 1.0 / 48), 0.6);
  const Solve thin_solve = solve_random(thin, 1e-6, 100);
  report("tank_16x64x48_hy=hx/4", thin_solve);
  EXPECT_LE(thin_solve.iterations, cube.iterations + 2);
}

// An irregular liquid: a wavy surface (not aligned with the coarse cells), a solid sphere and a
// pillar inside it, air bubbles (Empty cells wrapped in Surface cells), an outflow and an inflow
// box, on a grid of odd sizes and unequal cell sizes.
Problem irregular_domain() {
  const Eigen::Vector3i n(37, 29, 33);
  Problem p = empty_box(n, Vec3(1.0 / 37, 0.8 / 29, 1.1 / 33));
  const MacGrid& g = p.grid;
  for (int k = 1; k <= n.z(); ++k) {
    for (int j = 1; j <= n.y(); ++j) {
      for (int i = 1; i <= n.x(); ++i) {
        const Vec3 x = g.centre(i, j, k);
        const Real surface = 0.6 + 0.15 * std::sin(2 * kPi * x.x()) * std::cos(kPi * x.y() / 0.8);
        const Real below = surface - x.z();
        CellFlag f = below > g.h.z() ? CellFlag::full
                     : below > 0     ? CellFlag::surface
                                     : CellFlag::empty;
        if ((x - Vec3(0.35, 0.4, 0.3)).norm() < 0.15) f = CellFlag::solid;
        if (std::abs(x.x() - 0.75) < 0.05 && std::abs(x.y() - 0.3) < 0.05 && x.z() < 0.5) {
          f = CellFlag::solid;
        }
        for (const Vec3& bubble : {Vec3(0.7, 0.6, 0.2), Vec3(0.2, 0.15, 0.15)}) {
          const Real d = (x - bubble).norm();
          if (d < 0.04) {
            f = CellFlag::empty;
          } else if (d < 0.07) {
            f = CellFlag::surface;
          }
        }
        if (x.x() > 0.94 && x.y() < 0.1 && x.z() < 0.1) f = CellFlag::outflow;
        if (x.x() < 0.06 && x.y() > 0.7 && x.z() < 0.1) f = CellFlag::inflow;
        p.at(i, j, k) = f;
      }
    }
  }
  return p;
}

TEST(LiquidMultigrid, IrregularDomainConverges) {
  const Problem p = irregular_domain();
  const Solve solve = solve_random(p, 1e-6, 100);
  report("irregular_37x29x33", solve);
  EXPECT_LE(solve.iterations, 25);
  EXPECT_LE(solve.residual, 1e-6);
}

// <M^-1 a, b> = <a, M^-1 b> and <M^-1 a, a> > 0: CG's conditions on a preconditioner.
void expect_symmetric_positive(const Problem& p) {
  MultigridHierarchy mg;
  size_multigrid(p.grid, mg);
  build_multigrid(p.flags, mg);
  const std::size_t size = static_cast<std::size_t>(p.grid.size);
  std::vector<Real> ma(size), mb(size);
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const std::vector<Real> a = random_field(p, 2 * seed), b = random_field(p, 2 * seed + 1);
    apply_multigrid(mg, a, ma);
    apply_multigrid(mg, b, mb);
    const Real ab = dot(p, ma, b), ba = dot(p, a, mb);
    const Real scale = std::sqrt(dot(p, ma, ma) * dot(p, b, b));
    EXPECT_LE(std::abs(ab - ba), 1e-10 * scale) << ab << " vs " << ba;
    EXPECT_GT(dot(p, ma, a), 0);
    EXPECT_GT(dot(p, mb, b), 0);
    for (int c = 0; c < p.grid.size; ++c) {
      if (!is_unknown(p, c)) {
        ASSERT_EQ(ma[static_cast<std::size_t>(c)], 0.0) << c;
      }
    }
  }
}

TEST(LiquidMultigrid, VCycleIsSymmetricPositiveDefinite) {
  expect_symmetric_positive(tank({16, 16, 16}, Vec3::Constant(1.0 / 16), 0.6));
  expect_symmetric_positive(irregular_domain());
  expect_symmetric_positive(tank({24, 1, 20}, Vec3(0.05, 1, 0.04), 0.7));
}

// The discrete eigenvector of L in a tank with Neumann walls and floor and the Dirichlet Surface
// layer k_s: x* = cos(pi (i - 1/2) / n_x) cos(2 pi (j - 1/2) / n_y) cos(pi (k - 1/2) / (2 k_s - 1))
// (even about the walls' faces, zero at the Surface cells' centres), L x* = lambda x* with
// lambda = sum_a (2 - 2 cos theta_a) / h_a^2. Solving L x = lambda x* must give x*.
TEST(LiquidMultigrid, SolvesTheClosedFormOnAnAnisotropicGrid) {
  int ks = 0;
  const Eigen::Vector3i n(24, 20, 32);
  const Vec3 h(0.05, 0.035, 0.03);
  const Problem p = tank(n, h, 0.75, &ks);
  const Real theta[3] = {kPi / n.x(), 2 * kPi / n.y(), kPi / (2 * ks - 1)};
  Real lambda = 0;
  for (int a = 0; a < 3; ++a) lambda += (2 - 2 * std::cos(theta[a])) / (h[a] * h[a]);
  const std::size_t size = static_cast<std::size_t>(p.grid.size);
  std::vector<Real> x_star(size, 0.0), b(size, 0.0), lx(size);
  for (int k = 1; k < ks; ++k) {
    for (int j = 1; j <= n.y(); ++j) {
      for (int i = 1; i <= n.x(); ++i) {
        const std::size_t c = static_cast<std::size_t>(p.grid.index(i, j, k));
        x_star[c] = std::cos(theta[0] * (i - 0.5)) * std::cos(theta[1] * (j - 0.5)) *
                    std::cos(theta[2] * (k - 0.5));
        b[c] = lambda * x_star[c];
      }
    }
  }
  // The closed form holds for the operator itself...
  apply_laplacian(p, x_star, lx);
  Real worst = 0;
  for (std::size_t c = 0; c < size; ++c) worst = std::max(worst, std::abs(lx[c] - b[c]));
  EXPECT_LE(worst, 1e-9 * lambda);
  // ...and MGPCG finds it.
  MultigridHierarchy mg;
  size_multigrid(p.grid, mg);
  build_multigrid(p.flags, mg);
  std::vector<Real> x;
  const Solve solve = solve_mgpcg(p, mg, b, x, 1e-10, 60);
  report("closed_form_24x20x32_anisotropic", solve);
  Real err = 0, ref = 0;
  for (std::size_t c = 0; c < size; ++c) {
    err = std::max(err, std::abs(x[c] - x_star[c]));
    ref = std::max(ref, std::abs(x_star[c]));
  }
  EXPECT_LE(err, 1e-6 * ref);
  EXPECT_LE(solve.iterations, 30);
}

// A closed box full of liquid: L is singular (constants), and CG still converges on a right-hand
// side of zero mean, as pressure_solvers' closed-box case needs.
TEST(LiquidMultigrid, ClosedBoxOfLiquidConverges) {
  Problem p = empty_box({20, 20, 20}, Vec3::Constant(0.05));
  for (CellFlag& f : p.flags) {
    if (f == CellFlag::empty) f = CellFlag::full;
  }
  MultigridHierarchy mg;
  size_multigrid(p.grid, mg);
  build_multigrid(p.flags, mg);
  std::vector<Real> b = random_field(p, 7), x;
  Real mean = 0;
  int count = 0;
  for (int c = 0; c < p.grid.size; ++c) {
    if (is_unknown(p, c)) mean += b[static_cast<std::size_t>(c)], ++count;
  }
  mean /= count;
  for (int c = 0; c < p.grid.size; ++c) {
    if (is_unknown(p, c)) b[static_cast<std::size_t>(c)] -= mean;
  }
  const Solve solve = solve_mgpcg(p, mg, b, x, 1e-6, 100);
  report("closed_box_20^3", solve);
  EXPECT_LE(solve.iterations, 25);
  EXPECT_LE(solve.residual, 1e-6);
}

TEST(LiquidMultigrid, BuildAndApplyAllocateNothing) {
  const Problem p = irregular_domain();
  MultigridHierarchy mg;
  size_multigrid(p.grid, mg);
  const std::vector<Real> r = random_field(p, 3);
  std::vector<Real> z(r.size());
  g_allocations = 0;
  g_counting = true;
  build_multigrid(p.flags, mg);
  apply_multigrid(mg, r, z);
  g_counting = false;
  EXPECT_EQ(g_allocations, 0);
}

TEST(LiquidMultigrid, IsDeterministic) {
  const Problem p = irregular_domain();
  MultigridHierarchy mg1, mg2;
  size_multigrid(p.grid, mg1);
  size_multigrid(p.grid, mg2);
  build_multigrid(p.flags, mg1);
  build_multigrid(p.flags, mg2);
  const std::vector<Real> r = random_field(p, 5);
  std::vector<Real> z1(r.size()), z2(r.size()), z3(r.size());
  apply_multigrid(mg1, r, z1);
  apply_multigrid(mg2, r, z2);
  apply_multigrid(mg1, r, z3);  // again on a hierarchy that has been used
  EXPECT_EQ(z1, z2);
  EXPECT_EQ(z1, z3);
}

}  // namespace
}  // namespace pbm
