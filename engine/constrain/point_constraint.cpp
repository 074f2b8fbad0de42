#include "constrain/point_constraint.h"

namespace pbm {
namespace {

// Body-frame position of the end and its velocity relative to the frame (J q_s-dot + d-dot).
Vec3 body_point(const ConstraintPoint& end, const BodyWorkspace& bw) {
  return end.node >= 0 ? bw.p[end.node] : end.point;
}

}  // namespace

Vec3 constraint_end_position(const ConstraintPoint& end, const std::vector<BodyWorkspace>& bodies,
                             const ConstrainedSystem& system, const VecX& q) {
  if (end.body < 0) return end.point;
  const BodyWorkspace& bw = bodies[end.body];
  if (end.node >= 0) return bw.x[end.node];
  // x = c + R p (3.3) for a point fixed in the frame.
  return q.segment<3>(system.bodies[end.body].q_offset) + bw.R * end.point;
}

Vec3 constraint_end_velocity(const ConstraintPoint& end, const std::vector<BodyWorkspace>& bodies,
                             const ConstrainedSystem& system, const VecX& v) {
  if (end.body < 0) return Vec3::Zero();
  const BodyWorkspace& bw = bodies[end.body];
  if (end.node >= 0) return bw.x_dot[end.node];
  const BodyModel& body = system.bodies[end.body];
  const auto v_body = v.segment(body.v_offset, body.v_size);
  return velocity_of(v_body) + bw.R * omega_of(v_body).cross(end.point);
}

Vec3 constraint_end_rate(const ConstraintPoint& end, const std::vector<BodyWorkspace>& bodies,
                         const ConstrainedSystem& system, const VecX& rates) {
  if (end.body < 0) return Vec3::Zero();
  const BodyModel& body = system.bodies[end.body];
  const BodyWorkspace& bw = bodies[end.body];
  const auto r = rates.segment(body.v_offset, body.v_size);
  const Vec3 p = body_point(end, bw);
  const Vec3 turn = omega_of(r);  // omega-dot, or omega for first-order bodies
  Vec3 local = turn.cross(p);
  if (end.node >= 0) {
    if (body.n_s > 0) local += J_times(bw, end.node, r.data() + BodyLayout::kShapeInV);
    if (body.has_local) local += r.segment<3>(body.layout.displacement_in_v() + 3 * end.node);
    if (body.order == DynamicsOrder::second) local += bw.a_vp[end.node];
  } else if (body.order == DynamicsOrder::second) {
    local += bw.omega.cross(bw.omega.cross(p));  // (3.18) for a point fixed in the frame
  }
  return velocity_of(r) + bw.R * local;
}

void constraint_end_jacobian_transpose(const ConstraintPoint& end, const BodyModel& body,
                                       const BodyWorkspace& bw, MatX& G) {
  // Column j of P^T R^T is P^T y for y = R^T e_j: (y, p x y, J^T y).
  const Vec3 p = body_point(end, bw);
  G.setZero();
  for (int j = 0; j < 3; ++j) {
    const Vec3 y = bw.R.row(j).transpose();
    linear_part(G.col(j)) = y;
    angular_part(G.col(j)) = p.cross(y);
    if (end.node >= 0 && body.n_s > 0) {
      add_Jt_y(bw, end.node, y, 1.0, G.col(j).data() + BodyLayout::kShapeInV);
    }
  }
}

void add_generalized_rate(const BodyModel& body, const BodyWorkspace& bw, const VecX& delta,
                          VecX& rates) {
  auto r = rates.segment(body.v_offset, body.n_generalized());
  velocity_of(r) += bw.R * linear_part(delta);
  omega_of(r) += angular_part(delta);
  if (body.n_s > 0) shape_rate_of(body.layout, r) += shape_rate_of(body.layout, delta);
}

}  // namespace pbm
