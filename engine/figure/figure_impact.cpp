#include "figure/figure_impact.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "figure/figure_kinematics.h"
#include "figure/joint_space_inertia.h"

namespace pbm {
namespace {

// Projected Gauss-Seidel stops when no impulse changes by more than this share of the largest,
// or after kMaxSweeps sweeps.
constexpr Real kSweepTolerance = 1e-13;
constexpr int kMaxSweeps = 20000;
// The equalities' solution may cross p_n >= 0 or the cone by rounding; beyond this share of the
// largest impulse it is projected.
constexpr Real kFeasibilityTolerance = 1e-10;

// The relative velocity the contact law asks of a contact after the impact: along n, -e times
// u_n before (15.2); across n, zero (15.4; a frictionless contact reads only the normal part).
Vec3 contact_target(const Vec3& n, Real u_n_before, Real e) {
  return -e * u_n_before * n;
}

// x = A^+ b, the least-norm solution of the complete orthogonal decomposition `cod` of A, the
// steps of Eigen's CompleteOrthogonalDecomposition::solve in the same order (so the same bits),
// with its scratch in Vector: Eigen's own solve allocates a heap vector where A is rank
// deficient (a box's corners on a floor), which the step must not (docs/architecture.md,
// "Allocation"); an ImpactVector lives on the stack.
template <class Cod, class Vector>
void least_norm_solve(const Cod& cod, const Vector& b, Vector& x) {
  const Eigen::Index rank = cod.rank(), cols = cod.cols();
  x.resize(cols);
  if (rank == 0) {
    x.setZero();
    return;
  }
  Vector c = b;  // Q^* b
  c.applyOnTheLeft(cod.householderQ().setLength(rank).adjoint());
  x.head(rank) = cod.matrixT()
                     .topLeftCorner(rank, rank)
                     .template triangularView<Eigen::Upper>()
                     .solve(c.head(rank));
  if (rank < cols) {
    // y = Z^* [z; 0], Householder reflector by reflector.
    x.tail(cols - rank).setZero();
    Vector workspace(cols);
    for (Eigen::Index k = 0; k < rank; ++k) {
      if (k != rank - 1) std::swap(x(k), x(rank - 1));
      x.segment(rank - 1, cols - rank + 1)
          .applyHouseholderOnTheLeft(cod.matrixQTZ().row(k).tail(cols - rank).adjoint(),
                                     cod.zCoeffs()(k), workspace.data());
      if (k != rank - 1) std::swap(x(k), x(rank - 1));
    }
  }
  c.head(cols) = x;
  x = cod.colsPermutation() * c.head(cols);
}

}  // namespace

void segment_world_transforms(const FigureModel& figure, const FigureWorkspace& ws,
                              std::vector<SpatialTransform>& world) {
  world.resize(figure.segments.size());
  for (int i = 0; i < figure.size(); ++i) {
    const int p = figure.segments[i].parent;
    world[i] = p >= 0 ? ws.X_up[i] * world[p] : ws.X_up[i];
  }
}

void add_point_jacobian(const FigureModel& figure, const FigureWorkspace& ws,
                        const std::vector<SpatialTransform>& world, int segment, const Vec3& point,
                        Real sign, Eigen::Ref<MatX> rows) {
  for (int j = segment; j >= 0; j = figure.segments[j].parent) {
    const SpatialTransform to_world = inverse(world[j]);
    const MotionSubspace& S = ws.S[j];
    for (int k = 0; k < S.cols(); ++k) {
      const Vec6 column = S.col(k);
      const MotionVector s = transform_motion(to_world, motion_from_vec6(column));
      rows.col(figure.segments[j].v_offset + k) += sign * (s.linear + s.angular.cross(point));
    }
  }
}

namespace {

// The impulses p (3 per contact) that take the contact velocities u to the contact law's, with
// W the Delassus matrix: the book's equalities, projected where they break p_n >= 0 or the cone.
// Returns whether it projected.
template <class Matrix, class Vector>
bool solve_impulses(std::span<const ImpactContact> contacts, const ImpactSettings& settings,
                    ImpactSystem<Matrix, Vector>& sys) {
  const int m = static_cast<int>(contacts.size());
  const Matrix& W = sys.W;
  const Vector& u = sys.u;
  Vector& p = sys.p;
  sys.target.resize(3 * m);
  sys.b.resize(m);
  for (int c = 0; c < m; ++c) {
    const Real u_n = contacts[c].normal.dot(u.template segment<3>(3 * c));
    sys.target.template segment<3>(3 * c) =
        contact_target(contacts[c].normal, u_n, settings.restitution);
    sys.b[c] = -(1 + settings.restitution) * u_n;
  }
  // The book's equalities (15.2) with (15.3) or (15.4), least-norm where contacts are redundant
  // (a box's four corners on a floor).
  const bool frictionless = settings.friction == ImpactFriction::frictionless;
  if (frictionless) {
    // Along the normals alone: A = N W N^T, with N the normals row by row.
    sys.A.resize(m, m);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < m; ++j) {
        sys.A(i, j) =
            contacts[i].normal.dot(W.template block<3, 3>(3 * i, 3 * j) * contacts[j].normal);
      }
    }
    sys.cod.compute(sys.A);
    least_norm_solve(sys.cod, sys.b, sys.p_n);
    p.setZero(3 * m);
    for (int c = 0; c < m; ++c) p.template segment<3>(3 * c) = sys.p_n[c] * contacts[c].normal;
  } else {
    sys.cod.compute(W);
    sys.p_n = sys.target - u;  // the right-hand side
    least_norm_solve(sys.cod, sys.p_n, p);
  }
  // Feasible: every contact pushes, and (Coulomb) stays in its cone.
  const auto largest = [&] { return std::max<Real>(p.cwiseAbs().maxCoeff(), 1e-300); };
  const auto feasible = [&](int c) {
    const Vec3 pc = p.template segment<3>(3 * c);
    const Vec3& n = contacts[c].normal;
    const Real pn = n.dot(pc);
    if (pn < -kFeasibilityTolerance * largest()) return false;
    if (settings.friction != ImpactFriction::coulomb) return true;
    return (pc - pn * n).norm() <=
           settings.mu * std::max<Real>(pn, 0) + kFeasibilityTolerance * largest();
  };
  bool all_feasible = true;
  for (int c = 0; c < m; ++c) all_feasible &= feasible(c);
  if (all_feasible) return false;
  // Projected Gauss-Seidel on W p = target - u, contact by contact, from the equalities'
  // solution: the normal impulse given all others (then p_n >= 0), the tangential one given
  // the new normal (then the cone).
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    Real change = 0;
    for (int c = 0; c < m; ++c) {
      const Vec3& n = contacts[c].normal;
      const auto velocity = [&] {
        return Vec3(u.template segment<3>(3 * c) + W.middleRows(3 * c, 3) * p);
      };
      const Vec3 old = p.template segment<3>(3 * c);
      const Mat3 W_cc = W.template block<3, 3>(3 * c, 3 * c);
      const Vec3 target = sys.target.template segment<3>(3 * c);
      // Normal, then tangential, each against the other's latest value: a sliding contact's
      // normal impulse must see its tangential one as clamped.
      const Real w_nn = n.dot(W_cc * n);
      const Real p_n = std::max<Real>(n.dot(old) + (n.dot(target) - n.dot(velocity())) / w_nn, 0);
      p.template segment<3>(3 * c) = old + (p_n - n.dot(old)) * n;
      Vec3 next = p.template segment<3>(3 * c);
      if (!frictionless) {
        Eigen::Matrix<Real, 3, 2> T;
        T.col(0) = n.unitOrthogonal();
        T.col(1) = n.cross(T.col(0));
        const Eigen::Matrix<Real, 2, 2> W_tt = T.transpose() * W_cc * T;
        Eigen::Matrix<Real, 2, 1> p_t = T.transpose() * next;
        p_t += W_tt.ldlt().solve(T.transpose() * (target - velocity()));
        const Real limit = settings.friction == ImpactFriction::coulomb
                               ? settings.mu * p_n
                               : std::numeric_limits<Real>::infinity();
        if (p_t.norm() > limit) p_t *= limit / p_t.norm();
        next = p_n * n + T * p_t;
      }
      p.template segment<3>(3 * c) = next;
      change = std::max(change, (next - old).cwiseAbs().maxCoeff());
    }
    if (change <= kSweepTolerance * largest()) break;
  }
  return true;
}

// Assembles W and u from the figures' H^-1 J^T and J, solves for the impulses, and applies them.
template <class Matrix, class Vector>
bool impact_in(std::span<const ImpactFigure> figures, std::span<const ImpactContact> contacts,
               const ImpactSettings& settings, ImpactWorkspace& ws,
               ImpactSystem<Matrix, Vector>& sys) {
  const int m = static_cast<int>(contacts.size());
  sys.W.setZero(3 * m, 3 * m);
  sys.u.setZero(3 * m);
  for (std::size_t f = 0; f < figures.size(); ++f) {
    const int n_v = figures[f].model->n_v;
    const Eigen::Map<MatX> J = grown_matrix(ws.J[f], 3 * m, n_v);
    const Eigen::Map<MatX> HinvJt = grown_matrix(ws.HinvJt[f], n_v, 3 * m);
    sys.W.noalias() += J * HinvJt;
    sys.u.noalias() += J * Eigen::Map<const VecX>(figures[f].v, n_v);
  }
  for (int c = 0; c < m; ++c) {
    if (contacts[c].figure_b < 0) sys.u.template segment<3>(3 * c) -= contacts[c].surface_velocity;
  }
  const bool projected = solve_impulses(contacts, settings, sys);
  for (std::size_t f = 0; f < figures.size(); ++f) {
    const int n_v = figures[f].model->n_v;
    const Eigen::Map<MatX> HinvJt = grown_matrix(ws.HinvJt[f], n_v, 3 * m);
    Eigen::Map<VecX>(figures[f].v, n_v).noalias() += HinvJt * sys.p;
  }
  for (int c = 0; c < m; ++c) ws.impulses[c] = sys.p.template segment<3>(3 * c);
  return projected;
}

}  // namespace

Eigen::Map<MatX> grown_matrix(std::vector<Real>& storage, int rows, int cols) {
  const std::size_t size = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  if (storage.size() < size) storage.resize(size);
  return {storage.data(), rows, cols};
}

void reserve_impact_workspace(int figures, int segments, int n_v, int contacts,
                              ImpactWorkspace& ws) {
  ws.figures.resize(static_cast<std::size_t>(figures));
  ws.world.resize(static_cast<std::size_t>(figures));
  ws.H.resize(static_cast<std::size_t>(figures));
  ws.J.resize(static_cast<std::size_t>(figures));
  ws.HinvJt.resize(static_cast<std::size_t>(figures));
  const std::size_t n = static_cast<std::size_t>(segments);
  for (int f = 0; f < figures; ++f) {
    FigureWorkspace& w = ws.figures[f];
    w.X_up.reserve(n);
    w.S.reserve(n);
    w.axis_column.reserve(n);
    w.axis_sign.reserve(n);
    w.v.reserve(n);
    w.c.reserve(n);
    w.inertia.reserve(n);
    w.a.reserve(n);
    w.f.reserve(n);
    w.IA.reserve(n);
    w.U.reserve(n);
    w.D_inv.reserve(n);
    w.u.reserve(n);
    ws.world[f].reserve(n);
    ws.H[f].reserve(static_cast<std::size_t>(n_v * n_v));
    ws.J[f].reserve(static_cast<std::size_t>(3 * contacts * n_v));
    ws.HinvJt[f].reserve(static_cast<std::size_t>(3 * contacts * n_v));
  }
  ws.impulses.reserve(static_cast<std::size_t>(contacts));
  ws.limit_rows.reserve(static_cast<std::size_t>(n_v));
  if (ws.in_place.empty()) ws.in_place.resize(1);
}

ImpactResult resolve_impact(std::span<const ImpactFigure> figures,
                            std::span<const ImpactContact> contacts, const ImpactSettings& settings,
                            ImpactWorkspace& ws) {
  const int n_figures = static_cast<int>(figures.size());
  const int m = static_cast<int>(contacts.size());
  ws.impulses.assign(static_cast<std::size_t>(m), Vec3::Zero());
  ImpactResult result;
  result.impulses = ws.impulses;
  if (m == 0) return result;
  if (static_cast<int>(ws.figures.size()) < n_figures) {
    ws.figures.resize(n_figures);
    ws.world.resize(n_figures);
    ws.H.resize(n_figures);
    ws.J.resize(n_figures);
    ws.HinvJt.resize(n_figures);
  }
  for (int f = 0; f < n_figures; ++f) {
    const FigureModel& model = *figures[f].model;
    size_figure_workspace(model, ws.figures[f]);
    Eigen::Map<MatX> H = grown_matrix(ws.H[f], model.n_v, model.n_v);
    joint_space_inertia(model, figures[f].q, ws.figures[f], H);
    segment_world_transforms(model, ws.figures[f], ws.world[f]);
    grown_matrix(ws.J[f], 3 * m, model.n_v).setZero();
  }
  // J: rows 3c..3c+2 give the velocity of contact c's point on a relative to b.
  for (int c = 0; c < m; ++c) {
    const ImpactContact& contact = contacts[c];
    const auto add = [&](int f, int segment, Real sign) {
      Eigen::Map<MatX> J = grown_matrix(ws.J[f], 3 * m, figures[f].model->n_v);
      add_point_jacobian(*figures[f].model, ws.figures[f], ws.world[f], segment, contact.point,
                         sign, J.middleRows(3 * c, 3));
    };
    add(contact.figure_a, contact.segment_a, 1.0);
    if (contact.figure_b >= 0) add(contact.figure_b, contact.segment_b, -1.0);
  }
  // H^-1 J^T by H's Cholesky factor, in place in H's storage.
  for (int f = 0; f < n_figures; ++f) {
    const int n_v = figures[f].model->n_v;
    Eigen::Map<MatX> H = grown_matrix(ws.H[f], n_v, n_v);
    Eigen::Map<MatX> HinvJt = grown_matrix(ws.HinvJt[f], n_v, 3 * m);
    HinvJt = grown_matrix(ws.J[f], 3 * m, n_v).transpose();
    Eigen::LLT<Eigen::Ref<MatX>> llt(H);
    llt.solveInPlace(HinvJt);
  }
  if (m <= kImpactContactsInPlace) {
    if (ws.in_place.empty()) ws.in_place.resize(1);
    result.projected = impact_in(figures, contacts, settings, ws, ws.in_place.front());
  } else {
    result.projected = impact_in(figures, contacts, settings, ws, ws.on_heap);
  }
  return result;
}

}  // namespace pbm
