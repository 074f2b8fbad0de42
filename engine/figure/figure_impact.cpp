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

// Adds sign * (velocity of the world point attached to `segment` per joint velocity) to the three
// rows: for each joint on the path to the root, its subspace in world coordinates at the point,
// v_O + omega x point.
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

// The relative velocity the contact law asks of a contact after the impact: along n, -e times
// u_n before (15.2); across n, zero (15.4; a frictionless contact reads only the normal part).
Vec3 contact_target(const Vec3& n, Real u_n_before, Real e) {
  return -e * u_n_before * n;
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

ImpactResult resolve_impact(std::span<const ImpactFigure> figures,
                            std::span<const ImpactContact> contacts, const ImpactSettings& settings,
                            ImpactWorkspace& ws) {
  const int n_figures = static_cast<int>(figures.size());
  const int m = static_cast<int>(contacts.size());
  ImpactResult result;
  result.impulses.assign(m, Vec3::Zero());
  if (m == 0) return result;
  ws.figures.resize(n_figures);
  ws.H.resize(n_figures);
  ws.J.resize(n_figures);
  ws.HinvJt.resize(n_figures);
  std::vector<std::vector<SpatialTransform>> world(n_figures);
  for (int f = 0; f < n_figures; ++f) {
    const FigureModel& model = *figures[f].model;
    size_figure_workspace(model, ws.figures[f]);
    joint_space_inertia(model, figures[f].q->data(), ws.figures[f], ws.H[f]);
    segment_world_transforms(model, ws.figures[f], world[f]);
    ws.J[f].setZero(3 * m, model.n_v);
  }
  // J: rows 3c..3c+2 give the velocity of contact c's point on a relative to b.
  for (int c = 0; c < m; ++c) {
    const ImpactContact& contact = contacts[c];
    const auto add = [&](int f, int segment, Real sign) {
      add_point_jacobian(*figures[f].model, ws.figures[f], world[f], segment, contact.point, sign,
                         ws.J[f].middleRows(3 * c, 3));
    };
    add(contact.figure_a, contact.segment_a, 1.0);
    if (contact.figure_b >= 0) add(contact.figure_b, contact.segment_b, -1.0);
  }
  // W = sum_f J_f H_f^-1 J_f^T and the velocities before.
  ws.W.setZero(3 * m, 3 * m);
  ws.u.setZero(3 * m);
  for (int f = 0; f < n_figures; ++f) {
    ws.HinvJt[f] = ws.H[f].llt().solve(ws.J[f].transpose());
    ws.W.noalias() += ws.J[f] * ws.HinvJt[f];
    ws.u.noalias() += ws.J[f] * *figures[f].v;
  }
  std::vector<Real> u_n(m);
  VecX target(3 * m);
  for (int c = 0; c < m; ++c) {
    u_n[c] = contacts[c].normal.dot(ws.u.segment<3>(3 * c));
    target.segment<3>(3 * c) = contact_target(contacts[c].normal, u_n[c], settings.restitution);
  }
  // The book's equalities (15.2) with (15.3) or (15.4), least-norm where contacts are redundant
  // (a box's four corners on a floor).
  VecX p = VecX::Zero(3 * m);
  const bool frictionless = settings.friction == ImpactFriction::frictionless;
  if (frictionless) {
    MatX N = MatX::Zero(m, 3 * m);
    for (int c = 0; c < m; ++c) N.block<1, 3>(c, 3 * c) = contacts[c].normal.transpose();
    const MatX A = N * ws.W * N.transpose();
    VecX b(m);
    for (int c = 0; c < m; ++c) b[c] = -(1 + settings.restitution) * u_n[c];
    const VecX p_n = A.completeOrthogonalDecomposition().solve(b);
    p = N.transpose() * p_n;
  } else {
    p = ws.W.completeOrthogonalDecomposition().solve(target - ws.u);
  }
  // Feasible: every contact pushes, and (Coulomb) stays in its cone.
  const auto largest = [&] { return std::max<Real>(p.cwiseAbs().maxCoeff(), 1e-300); };
  const auto feasible = [&](int c) {
    const Vec3 pc = p.segment<3>(3 * c);
    const Vec3& n = contacts[c].normal;
    const Real pn = n.dot(pc);
    if (pn < -kFeasibilityTolerance * largest()) return false;
    if (settings.friction != ImpactFriction::coulomb) return true;
    return (pc - pn * n).norm() <=
           settings.mu * std::max<Real>(pn, 0) + kFeasibilityTolerance * largest();
  };
  bool all_feasible = true;
  for (int c = 0; c < m; ++c) all_feasible &= feasible(c);
  if (!all_feasible) {
    result.projected = true;
    // Projected Gauss-Seidel on W p = target - u, contact by contact, from the equalities'
    // solution: the normal impulse given all others (then p_n >= 0), the tangential one given
    // the new normal (then the cone).
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
      Real change = 0;
      for (int c = 0; c < m; ++c) {
        const Vec3& n = contacts[c].normal;
        const auto velocity = [&] {
          return Vec3(ws.u.segment<3>(3 * c) + ws.W.middleRows(3 * c, 3) * p);
        };
        const Vec3 old = p.segment<3>(3 * c);
        const Mat3 W_cc = ws.W.block<3, 3>(3 * c, 3 * c);
        // Normal, then tangential, each against the other's latest value: a sliding contact's
        // normal impulse must see its tangential one as clamped.
        const Real w_nn = n.dot(W_cc * n);
        const Real p_n = std::max<Real>(
            n.dot(old) + (n.dot(target.segment<3>(3 * c)) - n.dot(velocity())) / w_nn, 0);
        p.segment<3>(3 * c) = old + (p_n - n.dot(old)) * n;
        Vec3 next = p.segment<3>(3 * c);
        if (!frictionless) {
          Eigen::Matrix<Real, 3, 2> T;
          T.col(0) = n.unitOrthogonal();
          T.col(1) = n.cross(T.col(0));
          const Eigen::Matrix<Real, 2, 2> W_tt = T.transpose() * W_cc * T;
          Eigen::Matrix<Real, 2, 1> p_t = T.transpose() * next;
          p_t += W_tt.ldlt().solve(T.transpose() * (target.segment<3>(3 * c) - velocity()));
          const Real limit = settings.friction == ImpactFriction::coulomb
                                 ? settings.mu * p_n
                                 : std::numeric_limits<Real>::infinity();
          if (p_t.norm() > limit) p_t *= limit / p_t.norm();
          next = p_n * n + T * p_t;
        }
        p.segment<3>(3 * c) = next;
        change = std::max(change, (next - old).cwiseAbs().maxCoeff());
      }
      if (change <= kSweepTolerance * largest()) break;
    }
  }
  for (int f = 0; f < n_figures; ++f) *figures[f].v += ws.HinvJt[f] * p;
  for (int c = 0; c < m; ++c) result.impulses[c] = p.segment<3>(3 * c);
  return result;
}

}  // namespace pbm
