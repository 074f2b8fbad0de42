#include "collide/body_contact_side.h"

#include "collide/body_push.h"
#include "deform/body_dynamics.h"

namespace pbm {
namespace {

// World velocity of node k of a rigid or global body from the scratch nu: R P_k nu (3.4).
Vec3 generalized_node_velocity(const BodyModel& body, const BodyWorkspace& bw,
                               const BodyContactScratch& s, int k) {
  Vec3 r = linear_part(s.nu) + angular_part(s.nu).cross(bw.p[k]);
  if (body.n_s > 0) r += J_times(bw, k, s.nu.data() + BodyLayout::kShapeInV);
  return bw.R * r;
}

// L^T J = sum w_k P_k^T R^T J into s.g (rigid and global sides).
void generalized_impulse(const BodyModel& body, const BodyWorkspace& bw, const ContactSide& side,
                         const Vec3& J, BodyContactScratch& s) {
  const Vec3 y = bw.R.transpose() * J;
  s.g.setZero();
  for (int k = 0; k < side.count; ++k) {
    const int i = side.nodes[k];
    const Real w = side.weights[k];
    linear_part(s.g) += w * y;
    angular_part(s.g) += w * bw.p[i].cross(y);
    if (body.n_s > 0) add_Jt_y(bw, i, y, w, s.g.data() + BodyLayout::kShapeInV);
  }
}

}  // namespace

bool scratch_sized_for(const BodyModel& body, const BodyContactScratch& s) {
  return static_cast<int>(s.x0.size()) == body.n_nodes() && s.nu.size() == body.n_generalized() &&
         s.node_triangles.size() == 3 * body.tessellation.triangles.size();
}

void size_body_scratch(const BodyModel& body, BodyContactScratch& s) {
  s = BodyContactScratch{};
  s.stiffness = node_contact_stiffness(body);
  const auto n = static_cast<std::size_t>(body.n_nodes());
  s.x0.assign(n, Vec3::Zero());
  s.x.assign(n, Vec3::Zero());
  s.x_dot0.assign(n, Vec3::Zero());
  s.x_dot.assign(n, Vec3::Zero());
  s.normal.assign(n, Vec3::Zero());
  s.nu.setZero(body.n_generalized());
  s.g.setZero(body.n_generalized());
  s.delta.setZero(body.n_generalized());
  const auto& tris = body.tessellation.triangles;
  s.triangle_start.assign(n + 1, 0);
  for (const std::array<int, 3>& t : tris) {
    for (int v : t) ++s.triangle_start[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t k = 1; k <= n; ++k) s.triangle_start[k] += s.triangle_start[k - 1];
  s.node_triangles.assign(3 * tris.size(), 0);
  std::vector<int> fill(s.triangle_start.begin(), s.triangle_start.end() - 1);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (int v : tris[t]) s.node_triangles[fill[v]++] = static_cast<int>(t);
  }
  s.seen.assign(tris.size(), 0);
  s.stamp = 0;
}

void load_body_scratch(const BodySet& set, int b, BodyContactScratch& s) {
  const BodyModel& body = set.models[b];
  BodyWorkspace& bw = set.ws[b];
  const auto q = body_q(body, set.q);
  const auto v = body_v(body, set.v);
  compute_body_kinematics(body, q, v, bw, false);
  s.x0 = bw.x;
  s.x = bw.x;
  s.x_dot0 = bw.x_dot;
  s.x_dot = bw.x_dot;
  s.shift.setZero();
  s.touched = false;
  s.mass_factored = false;
  if (!body.has_local) {
    linear_part(s.nu) = bw.R.transpose() * velocity_of(v);
    after_translation(s.nu, body.n_generalized()) = after_translation(v, body.n_generalized());
  }
}

void ensure_side_mass(const ContactBodies& all, const ContactSide& side) {
  const BodyModel& body = all.body(side);
  BodyContactScratch& s = all.of(side);
  if (body.has_local || s.mass_factored) return;
  factor_generalized_mass(body, body_q(body, all.set.q), all.bw(side));
  s.mass_factored = true;
}

Vec3 side_velocity(const ContactBodies& all, const ContactSide& side) {
  const BodyModel& body = all.body(side);
  const BodyContactScratch& s = all.of(side);
  Vec3 v = Vec3::Zero();
  for (int k = 0; k < side.count; ++k) {
    const int i = side.nodes[k];
    v += side.weights[k] *
         (body.has_local ? s.x_dot[i] : generalized_node_velocity(body, all.bw(side), s, i));
  }
  return v;
}

Vec3 side_position(const ContactBodies& all, const ContactSide& side) {
  const BodyModel& body = all.body(side);
  const BodyContactScratch& s = all.of(side);
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < side.count; ++k) {
    const int i = side.nodes[k];
    x += side.weights[k] * (body.has_local ? s.x[i] : Vec3(s.x0[i] + s.shift));
  }
  return x;
}

Real side_inverse_mass(const ContactBodies& all, const ContactSide& side, const Vec3& d) {
  const BodyModel& body = all.body(side);
  if (body.has_local) {
    Real sum = 0;
    for (int k = 0; k < side.count; ++k) {
      sum += side.weights[k] * side.weights[k] / body.node_mass[side.nodes[k]];
    }
    return sum;
  }
  BodyContactScratch& s = all.of(side);
  BodyWorkspace& bw = all.bw(side);
  generalized_impulse(body, bw, side, d, s);
  solve_generalized_mass(bw, s.g, s.delta);
  return s.g.dot(s.delta);
}

void apply_side_impulse(const ContactBodies& all, const ContactSide& side, const Vec3& J) {
  const BodyModel& body = all.body(side);
  BodyContactScratch& s = all.of(side);
  s.touched = true;
  if (body.has_local) {
    for (int k = 0; k < side.count; ++k) {
      const int i = side.nodes[k];
      s.x_dot[i] += (side.weights[k] / body.node_mass[i]) * J;
    }
    return;
  }
  BodyWorkspace& bw = all.bw(side);
  generalized_impulse(body, bw, side, J, s);
  solve_generalized_mass(bw, s.g, s.delta);
  s.nu += s.delta;
}

void apply_side_displacement(const ContactBodies& all, const ContactSide& side, Real lambda,
                             const Vec3& n) {
  const BodyModel& body = all.body(side);
  BodyContactScratch& s = all.of(side);
  s.touched = true;
  if (body.has_local) {
    for (int k = 0; k < side.count; ++k) {
      const int i = side.nodes[k];
      s.x[i] += (lambda * side.weights[k] / body.node_mass[i]) * n;
    }
  } else if (!all.pinned(side)) {
    s.shift += (lambda / body.mass) * n;
  }
}

Real side_position_inverse_mass(const ContactBodies& all, const ContactSide& side) {
  const BodyModel& body = all.body(side);
  if (!body.has_local) return all.pinned(side) ? 0.0 : 1.0 / body.mass;
  return side_inverse_mass(all, side, Vec3::UnitX());
}

void write_back_body(const BodySet& set, int b, BodyContactScratch& s) {
  const BodyModel& body = set.models[b];
  BodyWorkspace& bw = set.ws[b];
  auto q = body_q(body, set.q);
  auto v = body_v(body, set.v);
  const Mat3 Rt = bw.R.transpose();
  if (body.has_local) {
    const int d_q = body.layout.displacement_in_q(), d_v = body.layout.displacement_in_v();
    const Vec3 omega = omega_of(v);
    for (int i = 0; i < body.n_nodes(); ++i) {
      // x-dot = R (V + omega x p + p-dot) (3.4): a node moved by dp would gain omega x dp, so
      // its d-dot loses it and the velocity is the one the impulses left.
      const Vec3 dp = Rt * (s.x[i] - s.x0[i]);
      q.segment<3>(d_q + 3 * i) += dp;
      v.segment<3>(d_v + 3 * i) += Rt * (s.x_dot[i] - s.x_dot0[i]) - omega.cross(dp);
    }
    recenter_displacements(body, q, v);
    compute_body_kinematics(body, q, v, bw, false);
    factor_generalized_mass(body, q, bw);
    resplit_velocities(body, q, v, bw);
  } else {
    position_of(q) += s.shift;
    velocity_of(v) = bw.R * linear_part(s.nu);
    after_translation(v, body.n_generalized()) = after_translation(s.nu, body.n_generalized());
  }
  compute_body_kinematics(body, q, v, bw, false);
}

}  // namespace pbm
