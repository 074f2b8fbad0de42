// The impact stage of a figure's collision (sec. 15.3.1): at the instant two segments (or a
// segment and a fixed surface) collide, velocities jump while positions stay. The book writes
// momentum conservation per segment with the contact impulses and the joint impulses (15.1),
// (15.6), the contact law along the normal (15.2), frictionless (15.3) or sticking (15.4), joint
// impulses with no component along the joint axes (15.7) and the velocity recursion (15.8), and
// solves the sparse system. In joint coordinates the joint impulses drop out ((15.7) is exactly
// that they do no work on the joint's motion): H dqdot = J^T p, with the contact points' velocity
// change J dqdot = J H^-1 J^T p. That dense system has 1 or 3 unknowns per contact instead of 12
// per segment; each figure's H is factored once.
//
// Beyond the book: Coulomb's law |p_t| <= mu p_n on the impulses, and impulses that only push
// (p_n >= 0); where the book's equalities would break either, projected Gauss-Seidel on the same
// Delassus matrix from the equalities' clamped solution.
#pragma once

#include <Eigen/QR>
#include <span>
#include <vector>

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// A figure and its state as the impact sees it: positions read, velocities changed in place.
struct ImpactFigure {
  const FigureModel* model = nullptr;
  const Real* q = nullptr;  // n_q
  Real* v = nullptr;        // n_v
};

struct ImpactContact {
  int figure_a = 0, segment_a = 0;    // the first segment
  int figure_b = -1, segment_b = -1;  // the second, or -1: a fixed surface
  Vec3 point = Vec3::Zero();          // world [m]
  Vec3 normal = Vec3::UnitZ();        // world, unit, from b toward a
  // With b a surface (figure_b = -1): the velocity of its material at the point [m/s]. A moving
  // obstacle is infinitely massive: the contact law (15.2) holds for the velocity relative to it.
  Vec3 surface_velocity = Vec3::Zero();
};

enum class ImpactFriction {
  frictionless,  // (15.3): no tangential impulse
  sticking,      // (15.4): no tangential velocity after the impact
  coulomb,       // sticking where |p_t| <= mu p_n holds, sliding on the cone where it does not
};

struct ImpactSettings {
  Real restitution = 0;  // e of (15.2): v_n+ = -e v_n-
  ImpactFriction friction = ImpactFriction::frictionless;
  Real mu = 0.5;  // Coulomb's coefficient, for ImpactFriction::coulomb
};

struct ImpactResult {
  std::span<const Vec3> impulses;  // world impulse on segment a at each contact [N s] (in ws)
  bool projected = false;          // the equalities' solution broke p_n >= 0 or the cone
};

// Impacts of up to kImpactContactsInPlace contacts are solved on matrices of fixed capacity, so
// the step does not allocate; larger ones take the same steps on heap matrices.
inline constexpr int kImpactContactsInPlace = 32;
inline constexpr int kImpactRowsInPlace = 3 * kImpactContactsInPlace;
using ImpactMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                   kImpactRowsInPlace, kImpactRowsInPlace>;
using ImpactVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, Eigen::ColMajor, kImpactRowsInPlace, 1>;

// The contact-space part of an impact: the Delassus matrix W, the contact velocities before (u),
// after (target) and the impulses p, 3 per contact; the frictionless normal system A p_n = b.
template <class Matrix, class Vector>
struct ImpactSystem {
  Matrix W, A;
  Vector u, target, p, b, p_n;
  Eigen::CompleteOrthogonalDecomposition<Matrix> cod;
};

// Scratch of resolve_impact. Its storage only grows: once it has held an impact of a size, an
// impact of that size or smaller allocates nothing (reserve_impact_workspace sizes it ahead).
struct ImpactWorkspace {
  std::vector<FigureWorkspace> figures;
  std::vector<std::vector<SpatialTransform>> world;
  // Per figure: its joint-space inertia H (n_v x n_v, then its Cholesky factor), the contact
  // Jacobian J (3 m x n_v) and H^-1 J^T (n_v x 3 m), column-major.
  std::vector<std::vector<Real>> H, J, HinvJt;
  std::vector<Vec3> impulses;
  std::vector<int> limit_rows;  // the joint limits in an impact (figure/joint_limits.h)
  std::vector<ImpactSystem<ImpactMatrix, ImpactVector>> in_place;  // one, on the heap (~0.3 MB)
  ImpactSystem<MatX, VecX> on_heap;
};

// Sizes ws for impacts among `figures` figures of up to `segments` segments and n_v DOF each
// with up to `contacts` contacts, so that such impacts allocate nothing.
void reserve_impact_workspace(int figures, int segments, int n_v, int contacts,
                              ImpactWorkspace& ws);

// Grows storage to hold a rows x cols matrix and views it as one (column-major).
Eigen::Map<MatX> grown_matrix(std::vector<Real>& storage, int rows, int cols);

// Changes the figures' velocities by the impact at the contacts.
ImpactResult resolve_impact(std::span<const ImpactFigure> figures,
                            std::span<const ImpactContact> contacts, const ImpactSettings& settings,
                            ImpactWorkspace& ws);

// Adds sign * (velocity of the world point attached to `segment` per joint velocity) to the three
// rows (3 x n_v): for each joint on the path to the root, its subspace in world coordinates at the
// point, v_O + omega x point. Needs figure_kinematics (ws.S) and the world transforms.
void add_point_jacobian(const FigureModel& figure, const FigureWorkspace& ws,
                        const std::vector<SpatialTransform>& world, int segment, const Vec3& point,
                        Real sign, Eigen::Ref<MatX> rows);

// World transform (inertial -> segment) of every segment from figure_kinematics' X_up.
void segment_world_transforms(const FigureModel& figure, const FigureWorkspace& ws,
                              std::vector<SpatialTransform>& world);

}  // namespace pbm
