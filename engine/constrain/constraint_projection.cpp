#include "constrain/constraint_projection.h"

#include <algorithm>

#include "constrain/point_constraint.h"
#include "core/quaternion.h"

namespace pbm {
namespace {

// Chord steps of the position level (N is kept from the first): the rotations a projection makes
// are small, so each step gains many digits; the velocity level is linear in v, its second step
// only corrects the Jacobian's move with the positions.
constexpr int kPositionSteps = 4;
constexpr int kVelocitySteps = 2;
constexpr Real kPositionTolerance = 1e-10;  // [m]
constexpr Real kVelocityTolerance = 1e-10;  // [m/s]

Real end_sign(int end) {
  return end == 0 ? 1.0 : -1.0;
}

// Each constrained body's rotation from its quaternion, and the kinematics of those with an end
// on a node (its x = c + R (s + d) needs the reference shape at the current q_s).
void update_frames(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                   std::vector<BodyWorkspace>& bodies, ConstraintProjectionWorkspace& pw) {
  for (std::size_t b = 0; b < system.bodies.size(); ++b) {
    if (!pw.constrained[b]) continue;
    const BodyModel& body = system.bodies[b];
    const auto qb = body_q(body, q);
    pw.R[b] = rotation_from_quaternion(quaternion_of(qb));
    if (pw.node_ends[b]) compute_body_kinematics(body, qb, body_v(body, v), bodies[b], false);
  }
}

Vec3 end_position(const ConstraintPoint& end, const ConstrainedSystem& system, const VecX& q,
                  const std::vector<BodyWorkspace>& bodies,
                  const ConstraintProjectionWorkspace& pw) {
  if (end.body < 0) return end.point;
  if (end.node >= 0) return bodies[end.body].x[end.node];
  return position_of(body_q(system.bodies[end.body], q)) + pw.R[end.body] * end.point;
}

Vec3 end_velocity(const ConstraintPoint& end, const ConstrainedSystem& system, const VecX& v,
                  const std::vector<BodyWorkspace>& bodies,
                  const ConstraintProjectionWorkspace& pw) {
  if (end.body < 0) return Vec3::Zero();
  if (end.node >= 0) return bodies[end.body].x_dot[end.node];
  const auto vb = body_v(system.bodies[end.body], v);
  return velocity_of(vb) + pw.R[end.body] * omega_of(vb).cross(end.point);
}

// C and C-dot of every point constraint at (q, v), after update_frames.
void evaluate_constraints(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                          const std::vector<BodyWorkspace>& bodies,
                          ConstraintProjectionWorkspace& pw, VecX& C, VecX& C_dot) {
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  for (std::size_t l = 0; l < points.size(); ++l) {
    const std::array<ConstraintPoint, 2>& ends = points[l].ends;
    const Eigen::Index at = 3 * static_cast<Eigen::Index>(l);
    C.segment<3>(at) =
        end_position(ends[0], system, q, bodies, pw) - end_position(ends[1], system, q, bodies, pw);
    C_dot.segment<3>(at) =
        end_velocity(ends[0], system, v, bodies, pw) - end_velocity(ends[1], system, v, bodies, pw);
  }
}

Real largest_block(const VecX& x) {
  Real worst = 0;
  for (Eigen::Index l = 0; l + 2 < x.size(); l += 3)
    worst = std::max(worst, x.segment<3>(l).norm());
  return worst;
}

// The body-frame increment s Y_l,e f of every end, summed per body into cw.response.
void gather_increments(const ConstrainedSystem& system, const VecX& f, ConstraintWorkspace& cw,
                       const ConstraintProjectionWorkspace& pw) {
  for (std::size_t b = 0; b < system.bodies.size(); ++b) {
    if (pw.constrained[b]) cw.response[b].setZero();
  }
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  for (std::size_t l = 0; l < points.size(); ++l) {
    const Vec3 f_l = f.segment<3>(3 * static_cast<Eigen::Index>(l));
    for (int e = 0; e < 2; ++e) {
      const int b = points[l].ends[e].body;
      if (b >= 0) cw.response[b].noalias() += end_sign(e) * cw.Y[l][e] * f_l;
    }
  }
}

// pw.rhs = C-dot - C-dot_before, zero for constraints between first-order bodies (their
// velocities are not state, so the velocity level leaves them).
void velocity_gap(const ConstrainedSystem& system, ConstraintProjectionWorkspace& pw) {
  pw.rhs = pw.C_dot - pw.C_dot_before;
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  for (std::size_t l = 0; l < points.size(); ++l) {
    const int a = points[l].ends[0].body;
    if (system.bodies[a].order == DynamicsOrder::first) pw.rhs.segment<3>(3 * l).setZero();
  }
}

// Every constrained body's kinematics and mass block at q (the block is reused where the
// collision stage already factored this q), L^T of every end, M^-1 L^T, and N factored.
void factor_projection(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                       std::vector<BodyWorkspace>& bodies, ConstraintWorkspace& cw,
                       ConstraintProjectionWorkspace& pw) {
  for (std::size_t b = 0; b < system.bodies.size(); ++b) {
    if (!pw.constrained[b]) continue;
    const BodyModel& body = system.bodies[b];
    const auto qb = body_q(body, q);
    compute_body_kinematics(body, qb, body_v(body, v), bodies[b], false);
    factor_generalized_mass(body, qb, bodies[b]);
  }
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  for (std::size_t l = 0; l < points.size(); ++l) {
    for (int e = 0; e < 2; ++e) {
      const ConstraintPoint& end = points[l].ends[e];
      if (end.body < 0) continue;
      constraint_end_jacobian_transpose(end, system.bodies[end.body], bodies[end.body], cw.G[l][e]);
    }
  }
  fill_end_responses(system, bodies, cw);
  factor_constraint_matrix(cw);
}

}  // namespace

void init_constraint_projection(const ConstrainedSystem& system,
                                ConstraintProjectionWorkspace& pw) {
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(system.constraints.points.size());
  for (VecX* x : {&pw.C_before, &pw.C_dot_before, &pw.C, &pw.C_dot, &pw.rhs, &pw.lambda}) {
    x->setZero(n);
  }
  pw.R.assign(system.bodies.size(), Mat3::Identity());
  pw.node_ends.assign(system.bodies.size(), 0);
  pw.constrained.assign(system.bodies.size(), 0);
  for (const PointConstraintModel& c : system.constraints.points) {
    for (const ConstraintPoint& end : c.ends) {
      if (end.body < 0) continue;
      pw.constrained[end.body] = 1;
      if (end.node >= 0) pw.node_ends[end.body] = 1;
    }
  }
}

void record_constraints_before_collisions(const ConstrainedSystem& system, const VecX& q,
                                          const VecX& v, std::vector<BodyWorkspace>& bodies,
                                          ConstraintProjectionWorkspace& pw) {
  update_frames(system, q, v, bodies, pw);
  evaluate_constraints(system, q, v, bodies, pw, pw.C_before, pw.C_dot_before);
}

ConstraintProjection project_constraints_after_collisions(
    const ConstrainedSystem& system, VecX& q, VecX& v, std::vector<BodyWorkspace>& bodies,
    ConstraintWorkspace& cw, ConstraintProjectionWorkspace& pw, Real dt) {
  ConstraintProjection result;
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  if (points.empty()) return result;
  update_frames(system, q, v, bodies, pw);
  evaluate_constraints(system, q, v, bodies, pw, pw.C, pw.C_dot);
  pw.rhs = pw.C - pw.C_before;
  result.opened = largest_block(pw.rhs);
  pw.rhs = pw.C_dot - pw.C_dot_before;
  result.opened_rate = largest_block(pw.rhs);
  // Untouched by the collisions, or moved less than kNegligibleOpening in this substep (the
  // velocity split a local body's collision stage restores every substep moves a point fixed in
  // its frame by 1e-9 m): Baumgarte's feedback keeps those, and the substep stays as it was.
  if (result.opened + dt * result.opened_rate <= kNegligibleOpening) return result;
  result.ran = true;

  // L^T, M^-1 L^T and N at the collided state, for the position level's chord steps.
  factor_projection(system, q, v, bodies, cw, pw);
  bool moved = false;
  // Position level: q_k += s M^-1 L^T lambda with N lambda = C_before - C, repeated on the
  // remaining difference.
  for (int step = 0; step < kPositionSteps; ++step) {
    pw.rhs = pw.C - pw.C_before;
    if (largest_block(pw.rhs) <= kPositionTolerance) break;
    moved = true;
    solve_constraint_matrix_negated(cw, pw.rhs, pw.lambda);
    gather_increments(system, pw.lambda, cw, pw);
    for (std::size_t b = 0; b < system.bodies.size(); ++b) {
      if (!pw.constrained[b]) continue;
      const BodyModel& body = system.bodies[b];
      const VecX& delta = cw.response[b];
      auto qb = body_q(body, q);
      position_of(qb) += pw.R[b] * linear_part(delta);
      const Vec3 turn = angular_part(delta);  // body frame, as omega
      const Real angle = turn.norm();
      if (angle > 0) {
        quaternion_of(qb) =
            quaternion_product(quaternion_of(qb), quaternion_from_axis_angle(turn, angle))
                .normalized();
      }
      if (body.n_s > 0) {
        shape_of(body.layout, qb) += delta.segment(BodyLayout::kShapeInV, body.n_s);
      }
    }
    update_frames(system, q, v, bodies, pw);
    evaluate_constraints(system, q, v, bodies, pw, pw.C, pw.C_dot);
  }
  pw.rhs = pw.C - pw.C_before;
  result.residual = largest_block(pw.rhs);
  // Again at the positions the velocities belong to: the impulses are equal and opposite only
  // through the mass blocks of the state they act on (the momentum of a global body depends on
  // q_s), so the velocity level conserves momentum to rounding.
  if (moved) factor_projection(system, q, v, bodies, cw, pw);

  // Velocity level, second-order bodies only (a first-order body's velocity is not state).
  for (int step = 0; step < kVelocitySteps; ++step) {
    velocity_gap(system, pw);
    if (largest_block(pw.rhs) <= kVelocityTolerance) break;
    solve_constraint_matrix_negated(cw, pw.rhs, pw.lambda);
    gather_increments(system, pw.lambda, cw, pw);
    for (std::size_t b = 0; b < system.bodies.size(); ++b) {
      if (!pw.constrained[b]) continue;
      const BodyModel& body = system.bodies[b];
      if (body.order == DynamicsOrder::first) continue;
      const VecX& delta = cw.response[b];
      auto vb = body_v(body, v);
      velocity_of(vb) += pw.R[b] * linear_part(delta);
      omega_of(vb) += angular_part(delta);
      if (body.n_s > 0)
        shape_rate_of(body.layout, vb) += delta.segment(BodyLayout::kShapeInV, body.n_s);
    }
    update_frames(system, q, v, bodies, pw);
    evaluate_constraints(system, q, v, bodies, pw, pw.C, pw.C_dot);
  }
  velocity_gap(system, pw);
  result.residual_rate = largest_block(pw.rhs);
  return result;
}

}  // namespace pbm
