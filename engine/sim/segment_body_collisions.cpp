#include "sim/segment_body_collisions.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "collide/body_push.h"
#include "collide/contact_impulse.h"
#include "collide/rigid_contact.h"
#include "deform/body_dynamics.h"
#include "figure/joint_space_inertia.h"
#include "sim/figure_collisions.h"
#include "sim/model.h"

namespace pbm {
namespace {

constexpr Real kUnitWeight = 1.0;
// Contacts per figure its matrices are sized for ahead (more grow them once).
constexpr int kReservedContacts = 64;

ContactSide node_side(const SegmentBodyContact& c) {
  return ContactSide{c.body, &c.node, &kUnitWeight, 1};
}

bool sized_for(const Model& model, const SegmentBodyWorkspace& sws) {
  if (sws.bodies.size() != model.bodies.size() || sws.H.size() != model.figures.size()) {
    return false;
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!scratch_sized_for(model.bodies[b], sws.bodies[b])) return false;
  }
  return true;
}

Box3 node_bounds(const std::vector<Vec3>& x, Real margin) {
  Box3 box;
  for (const Vec3& p : x) box.add(p);
  box.lo.array() -= margin;
  box.hi.array() += margin;
  return box;
}

bool contains(const Box3& box, const Vec3& x) {
  return (x.array() >= box.lo.array()).all() && (x.array() <= box.hi.array()).all();
}

// The figure's factor L of H = L L^T (in sws.H[f]): x <- H^-1 x.
void solve_inertia(SegmentBodyWorkspace& sws, int f, int n_v, Eigen::Ref<VecX> x) {
  const Eigen::Map<MatX> L = grown_matrix(sws.H[f], n_v, n_v);
  L.triangularView<Eigen::Lower>().solveInPlace(x);
  L.triangularView<Eigen::Lower>().adjoint().solveInPlace(x);
}

Eigen::Map<VecX> figure_v(const Model& model, const BodySet& set, int f) {
  const FigureModel& figure = model.figures[f].model;
  return {set.v.data() + figure.state_v_offset, figure.n_v};
}

// Step 1: every node within the margin of a segment, in the order (body, figure, segment, node).
void detect(const Model& model, const std::vector<std::vector<SpatialTransform>>& worlds,
            SegmentBodyWorkspace& sws, SegmentBodyStats& stats) {
  const BodyCollisionOptions& options = model.body_collisions.options;
  sws.solids.clear();
  sws.boxes.clear();
  sws.first.clear();
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    sws.first.push_back(static_cast<int>(sws.solids.size()));
    const FigureDef& def = model.scene.figures[f];
    for (std::size_t i = 0; i < def.segments.size(); ++i) {
      const ConvexSolid solid = segment_solid(def.segments[i].shape, worlds[f][i]);
      Box3 box = convex_bounds(solid);
      box.lo.array() -= options.margin;
      box.hi.array() += options.margin;
      sws.solids.push_back(solid);
      sws.boxes.push_back(box);
    }
  }
  sws.contacts.clear();
  std::fill(sws.rows.begin(), sws.rows.end(), 0);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const std::vector<Vec3>& x = sws.bodies[b].x;
    for (std::size_t f = 0; f < model.figures.size(); ++f) {
      if (!model.scene.figures[f].body_collisions) continue;
      const int n_segments = model.figures[f].model.size();
      for (int i = 0; i < n_segments; ++i) {
        const Box3& box = sws.boxes[sws.first[f] + i];
        if (!box.overlaps(sws.body_boxes[b])) continue;
        const ConvexSolid& solid = sws.solids[sws.first[f] + i];
        for (int node = 0; node < static_cast<int>(x.size()); ++node) {
          if (!contains(box, x[node])) continue;
          Vec3 n;
          const Real gap = convex_signed_distance(solid, x[node], n);
          if (!(gap < options.margin) || gap < -options.max_depth) continue;
          SegmentBodyContact c;
          c.body = static_cast<int>(b);
          c.node = node;
          c.figure = static_cast<int>(f);
          c.segment = i;
          c.point = x[node] - gap * n;
          c.gap = gap;
          const Vec3 t1 = n.unitOrthogonal();
          c.basis.col(0) = n;
          c.basis.col(1) = t1;
          c.basis.col(2) = n.cross(t1);
          c.column = sws.rows[f];
          sws.rows[f] += 3;
          sws.contacts.push_back(c);
          ++stats.contacts;
          if (gap < 0) {
            ++stats.penetrating;
            stats.max_penetration = std::max(stats.max_penetration, -gap);
          }
        }
      }
    }
  }
}

// The figures' side of step 2: H factored, J_p of every contact point and H^-1 J_p^T.
void figure_mobility(const Model& model, const BodySet& set, std::vector<FigureWorkspace>& each,
                     const std::vector<std::vector<SpatialTransform>>& worlds,
                     SegmentBodyWorkspace& sws) {
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    if (sws.rows[f] == 0) continue;
    const FigureModel& figure = model.figures[f].model;
    const int n_v = figure.n_v;
    Eigen::Map<MatX> H = grown_matrix(sws.H[f], n_v, n_v);
    joint_space_inertia(figure, set.q.data() + figure.state_q_offset, sws.figures[f], H);
    grown_matrix(sws.J[f], sws.rows[f], n_v).setZero();
  }
  for (const SegmentBodyContact& c : sws.contacts) {
    const FigureModel& figure = model.figures[c.figure].model;
    Eigen::Map<MatX> J = grown_matrix(sws.J[c.figure], sws.rows[c.figure], figure.n_v);
    add_point_jacobian(figure, each[c.figure], worlds[c.figure], c.segment, c.point, 1.0,
                       J.middleRows(c.column, 3));
  }
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    if (sws.rows[f] == 0) continue;
    const int n_v = model.figures[f].model.n_v;
    Eigen::Map<MatX> H = grown_matrix(sws.H[f], n_v, n_v);
    Eigen::Map<MatX> HinvJt = grown_matrix(sws.HinvJt[f], n_v, sws.rows[f]);
    HinvJt = grown_matrix(sws.J[f], sws.rows[f], n_v).transpose();
    Eigen::LLT<Eigen::Ref<MatX>> llt(H);  // H's storage now holds its factor L
    llt.solveInPlace(HinvJt);
  }
}

// Step 2: inelastic impulses with Coulomb's cone, projected Gauss-Seidel in alternating sweeps.
void solve_impulses(const Model& model, const ContactBodies& all, Real dt,
                    SegmentBodyWorkspace& sws, SegmentBodyStats& stats) {
  const BodyCollisionOptions& options = model.body_collisions.options;
  std::vector<SegmentBodyContact>& contacts = sws.contacts;
  const int m = static_cast<int>(contacts.size());
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    Real change = 0, largest = 0;
    for (int step = 0; step < m; ++step) {
      SegmentBodyContact& c = contacts[iteration % 2 == 0 ? step : m - 1 - step];
      Real allowed = 0;  // apart by gap: the pair may approach by gap in this step, and no more
      if (c.gap > 0) {
        if (!(dt > 0)) continue;
        allowed = c.gap / dt;
      }
      const int n_v = model.figures[c.figure].model.n_v;
      const auto J = grown_matrix(sws.J[c.figure], sws.rows[c.figure], n_v).middleRows(c.column, 3);
      const auto HinvJt =
          grown_matrix(sws.HinvJt[c.figure], n_v, sws.rows[c.figure]).middleCols(c.column, 3);
      Eigen::Map<VecX> v = figure_v(model, all.set, c.figure);
      Vec3 segment_velocity;
      for (int r = 0; r < 3; ++r) segment_velocity[r] = J.row(r).dot(v);
      const Vec3 u = c.basis.transpose() * (side_velocity(all, node_side(c)) - segment_velocity);
      const Real mu =
          std::sqrt(model.scene.figures[c.figure].friction * options.friction);  // (5.13)
      const Vec3 j = updated_contact_impulse(c.impulse, u, allowed, c.inverse_mass, mu);
      const Vec3 dj = j - c.impulse;
      if (dj.isZero(0)) continue;
      c.impulse = j;
      const Vec3 impulse = c.basis * dj;  // on the node; the segment takes -impulse
      apply_side_impulse(all, node_side(c), impulse);
      for (int k = 0; k < 3; ++k) v -= impulse[k] * HinvJt.col(k);
      change = std::max(change, dj.cwiseAbs().maxCoeff());
      largest = std::max(largest, j.cwiseAbs().maxCoeff());
    }
    if (change <= 1e-12 * largest) break;
  }
  for (const SegmentBodyContact& c : contacts) stats.normal_impulse += c.impulse[0];
}

// Step 3: the penetrating nodes out to the segments' surfaces (the body's side alone), passes
// for nodes of a rigid or global body, which move together.
void project_nodes(const Model& model, const ContactBodies& all, SegmentBodyWorkspace& sws) {
  for (int pass = 0; pass < model.body_collisions.options.iterations; ++pass) {
    Real worst = 0;
    for (SegmentBodyContact& c : sws.contacts) {
      if (!(c.position_inverse_mass > 0)) continue;  // a pinned rigid part stays
      const Vec3 n = c.basis.col(0);
      const Real gap = n.dot(side_position(all, node_side(c)) - c.point);
      if (gap >= 0) continue;
      worst = std::min(worst, gap);
      apply_side_displacement(all, node_side(c),
                              (kProjectionMargin - gap) / c.position_inverse_mass, n);
    }
    if (worst >= 0) break;
  }
}

// Step 4: (5.11) on the local bodies' global surfaces inside a segment, Jacobi (every impulse from
// the state the projection left, then all applied).
void push_out(const Model& model, const BodySet& set, std::vector<FigureWorkspace>& each,
              const std::vector<std::vector<SpatialTransform>>& worlds, Real dt,
              SegmentBodyWorkspace& sws, SegmentBodyStats& stats) {
  const Real elasticity = model.body_collisions.options.elasticity;
  if (!(elasticity > 0) || !(dt > 0)) return;
  const int n_figures = static_cast<int>(model.figures.size());
  const int m = static_cast<int>(sws.contacts.size());
  sws.push.assign(static_cast<std::size_t>(m), 0.0);
  sws.pair_stiffness.assign(model.bodies.size() * model.figures.size(), 0.0);
  // The figure's J_y^T n and H^-1 J_y^T n at the segment's point y (sws.push_jn, push_column:
  // their first n_v entries); returns the velocity of the segment's point along n.
  const auto figure_column = [&](const SegmentBodyContact& c, const Vec3& y, const Vec3& n) {
    const FigureModel& figure = model.figures[c.figure].model;
    const int n_v = figure.n_v;
    Eigen::Map<MatX> rows = grown_matrix(sws.push_rows, 3, n_v);
    rows.setZero();
    add_point_jacobian(figure, each[c.figure], worlds[c.figure], c.segment, y, 1.0, rows);
    auto jn = sws.push_jn.head(n_v);
    auto column = sws.push_column.head(n_v);
    for (int k = 0; k < n_v; ++k) jn[k] = rows.col(k).dot(n);
    column = jn;
    solve_inertia(sws, c.figure, n_v, column);
    return jn.dot(figure_v(model, set, c.figure));
  };
  struct Pressing {
    Real phi = 0, stiffness = 0, mobility = 0, approach = 0;
  };
  // First the points and their stiffness (each pair's total sizes its points' shares), then the
  // impulses.
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 0; k < m; ++k) {
      const SegmentBodyContact& c = sws.contacts[k];
      const BodyModel& body = model.bodies[c.body];
      if (!body.has_local || body.order != DynamicsOrder::second) continue;
      BodyWorkspace& bw = set.ws[c.body];
      const GlobalPoint p =
          global_point(body, bw, body_q(body, set.q), body_v(body, set.v), c.node);
      Vec3 n;
      const Real phi = convex_signed_distance(sws.solids[sws.first[c.figure] + c.segment], p.x, n);
      const Real stiffness = elasticity * sws.bodies[c.body].stiffness[c.node];
      if (!(phi < 0) || !(stiffness > 0)) continue;
      const std::size_t pair = static_cast<std::size_t>(c.body * n_figures + c.figure);
      if (pass == 0) {
        sws.pair_stiffness[pair] += stiffness;
        continue;
      }
      Pressing s{.phi = phi, .stiffness = stiffness};
      BodyContactScratch& scratch = sws.bodies[c.body];
      if (!scratch.mass_factored) {
        factor_generalized_mass(body, body_q(body, set.q), bw);
        scratch.mass_factored = true;
      }
      push_direction(body, bw, &c.node, &kUnitWeight, 1, n, scratch.g);
      solve_generalized_mass(bw, scratch.g, scratch.delta);
      s.mobility = scratch.g.dot(scratch.delta);
      const Vec3 y = p.x - phi * n;
      const Real segment_speed = figure_column(c, y, n);
      const int n_v = model.figures[c.figure].model.n_v;
      s.mobility += sws.push_jn.head(n_v).dot(sws.push_column.head(n_v));
      s.approach = -(n.dot(p.x_dot) - segment_speed);
      if (!(s.mobility > 0)) continue;
      const Real share = s.stiffness / sws.pair_stiffness[pair];
      sws.push[k] = push_impulse(s.stiffness, share / s.mobility, s.phi, s.approach, dt);
      ++stats.pressing;
    }
  }
  for (BodyContactScratch& s : sws.bodies) s.touched = false;
  for (int k = 0; k < m; ++k) {
    if (sws.push[k] == 0) continue;
    const SegmentBodyContact& c = sws.contacts[k];
    const BodyModel& body = model.bodies[c.body];
    BodyWorkspace& bw = set.ws[c.body];
    const GlobalPoint p = global_point(body, bw, body_q(body, set.q), body_v(body, set.v), c.node);
    Vec3 n;
    const Real phi = convex_signed_distance(sws.solids[sws.first[c.figure] + c.segment], p.x, n);
    const Vec3 J = sws.push[k] * n;
    BodyContactScratch& scratch = sws.bodies[c.body];
    push_direction(body, bw, &c.node, &kUnitWeight, 1, J, scratch.g);
    solve_generalized_mass(bw, scratch.g, scratch.delta);
    auto v = body_v(body, set.v);
    velocity_of(v) += bw.R * linear_part(scratch.delta);
    after_translation(v, body.n_generalized()) +=
        after_translation(scratch.delta, body.n_generalized());
    figure_column(c, p.x - phi * n, n);
    const int n_v = model.figures[c.figure].model.n_v;
    figure_v(model, set, c.figure) -= sws.push[k] * sws.push_column.head(n_v);
    sws.bodies[c.body].touched = true;
    stats.push_impulse += sws.push[k];
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (!sws.bodies[b].touched) continue;
    const BodyModel& body = model.bodies[b];
    compute_body_kinematics(body, body_q(body, set.q), body_v(body, set.v), set.ws[b], false);
  }
}

}  // namespace

void size_segment_body_workspace(const Model& model, SegmentBodyWorkspace& sws) {
  sws.bodies.assign(model.bodies.size(), BodyContactScratch{});
  std::size_t nodes = 0, segments = 0;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    size_body_scratch(model.bodies[b], sws.bodies[b]);
    nodes += static_cast<std::size_t>(model.bodies[b].n_nodes());
  }
  sws.body_boxes.assign(model.bodies.size(), Box3{});
  const std::size_t n_figures = model.figures.size();
  for (const CompiledFigure& f : model.figures) segments += f.model.segments.size();
  sws.solids.reserve(segments);
  sws.boxes.reserve(segments);
  sws.first.reserve(n_figures);
  sws.contacts.reserve(nodes);
  sws.rows.assign(n_figures, 0);
  sws.H.assign(n_figures, {});
  sws.J.assign(n_figures, {});
  sws.HinvJt.assign(n_figures, {});
  sws.figures.assign(n_figures, FigureWorkspace{});
  // Room for kReservedContacts contacts per figure, so that a strike does not allocate.
  int max_v = 0;
  for (std::size_t f = 0; f < n_figures; ++f) {
    const FigureModel& figure = model.figures[f].model;
    size_figure_workspace(figure, sws.figures[f]);
    grown_matrix(sws.H[f], figure.n_v, figure.n_v);
    grown_matrix(sws.J[f], 3 * kReservedContacts, figure.n_v);
    grown_matrix(sws.HinvJt[f], figure.n_v, 3 * kReservedContacts);
    max_v = std::max(max_v, figure.n_v);
  }
  grown_matrix(sws.push_rows, 3, max_v);
  sws.push_jn.setZero(max_v);
  sws.push_column.setZero(max_v);
  sws.push.reserve(nodes);
  sws.pair_stiffness.reserve(model.bodies.size() * n_figures);
}

SegmentBodyStats resolve_segment_body_collisions(
    const Model& model, const BodySet& set, std::vector<FigureWorkspace>& each,
    const std::vector<std::vector<SpatialTransform>>& worlds, Real dt, SegmentBodyWorkspace& sws) {
  SegmentBodyStats stats;
  if (!sized_for(model, sws)) size_segment_body_workspace(model, sws);
  const Real margin = model.body_collisions.options.margin;
  for (int b = 0; b < set.size(); ++b) {
    load_body_scratch(set, b, sws.bodies[b]);
    sws.body_boxes[b] = node_bounds(sws.bodies[b].x, margin);
  }
  detect(model, worlds, sws, stats);
  if (sws.contacts.empty()) return stats;
  figure_mobility(model, set, each, worlds, sws);
  const ContactBodies all{set, sws.bodies, model.body_collisions.constrained};
  for (SegmentBodyContact& c : sws.contacts) {
    const ContactSide side = node_side(c);
    ensure_side_mass(all, side);
    const int n_v = model.figures[c.figure].model.n_v;
    const auto J = grown_matrix(sws.J[c.figure], sws.rows[c.figure], n_v).middleRows(c.column, 3);
    const auto HinvJt =
        grown_matrix(sws.HinvJt[c.figure], n_v, sws.rows[c.figure]).middleCols(c.column, 3);
    Mat3 JHJt;  // the segment's J_p H^-1 J_p^T, entry by entry (no temporaries in the step)
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) JHJt(r, k) = J.row(r).dot(HinvJt.col(k));
    }
    const Mat3 W = c.basis.transpose() * JHJt * c.basis;
    for (int d = 0; d < 3; ++d) {
      c.inverse_mass[d] = side_inverse_mass(all, side, c.basis.col(d)) + W(d, d);
    }
    c.position_inverse_mass = side_position_inverse_mass(all, side);
  }
  solve_impulses(model, all, dt, sws, stats);
  project_nodes(model, all, sws);
  for (int b = 0; b < set.size(); ++b) {
    BodyContactScratch& s = sws.bodies[b];
    if (!s.touched) continue;
    write_back_body(set, b, s);
    s.mass_factored = false;  // the write-back refactored a local body's block at the new q
  }
  push_out(model, set, each, worlds, dt, sws, stats);
  return stats;
}

}  // namespace pbm
