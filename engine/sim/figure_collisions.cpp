#include "sim/figure_collisions.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/quaternion.h"
#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"
#include "sim/model.h"

namespace pbm {
namespace {

ConvexKind convex_kind(SegmentShapeKind kind) {
  switch (kind) {
    case SegmentShapeKind::box:
      return ConvexKind::box;
    case SegmentShapeKind::sphere:
      return ConvexKind::sphere;
    case SegmentShapeKind::cylinder:
      return ConvexKind::cylinder;
    case SegmentShapeKind::capsule:
      return ConvexKind::capsule;
  }
  return ConvexKind::box;
}

}  // namespace

ConvexSolid segment_solid(const SegmentShapeDef& shape, const SpatialTransform& X) {
  return {.kind = convex_kind(shape.kind),
          .size = shape.size,
          .rotation = X.E.transpose() * rotation_from_quaternion(shape.orientation),
          .center = X.r + X.E.transpose() * shape.center};
}

PairContactSettings pair_contact_settings(const FigureDef& a, const FigureDef& b) {
  return {.restitution = std::min(a.restitution, b.restitution),
          .impact_speed = std::min(a.impact_speed, b.impact_speed),
          .stiffness = std::min(a.contact_stiffness, b.contact_stiffness),
          .damping = std::min(a.contact_damping, b.contact_damping),
          .friction = std::sqrt(a.friction * b.friction)};
}

bool segments_may_collide(const Model& model, int figure_a, int segment_a, int figure_b,
                          int segment_b) {
  if (figure_a == figure_b) return model.figures[figure_a].collides(segment_a, segment_b);
  return model.scene.figures[figure_a].figure_collisions &&
         model.scene.figures[figure_b].figure_collisions;
}

bool any_segment_pair_may_collide(const Model& model) {
  int across = 0;  // figures that collide with other figures
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const std::vector<std::uint8_t>& pairs = model.figures[f].self_pairs;
    if (std::find(pairs.begin(), pairs.end(), 1) != pairs.end()) return true;
    across += model.scene.figures[f].figure_collisions ? 1 : 0;
  }
  return across >= 2;
}

void collect_segment_contacts(const Model& model,
                              const std::vector<std::vector<SpatialTransform>>& worlds,
                              SegmentCollisionScratch& s, std::vector<SegmentContact>& out) {
  out.clear();
  const int n_figures = static_cast<int>(model.figures.size());
  s.solids.clear();
  s.boxes.clear();
  s.first.assign(static_cast<std::size_t>(n_figures) + 1, 0);
  for (int f = 0; f < n_figures; ++f) {
    s.first[f] = static_cast<int>(s.solids.size());
    const FigureDef& def = model.scene.figures[f];
    for (int i = 0; i < model.figures[f].model.size(); ++i) {
      s.solids.push_back(segment_solid(def.segments[i].shape, worlds[f][i]));
      s.boxes.push_back(convex_bounds(s.solids.back()));
    }
  }
  s.first[n_figures] = static_cast<int>(s.solids.size());
  // Sweep and prune along x: a strict total order (lower x, then index), so the candidate set and
  // its order are the poses' alone.
  const int n = static_cast<int>(s.solids.size());
  s.order.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) s.order[k] = k;
  std::sort(s.order.begin(), s.order.end(), [&](int a, int b) {
    return std::tie(s.boxes[a].lo.x(), a) < std::tie(s.boxes[b].lo.x(), b);
  });
  const auto owner = [&](int k) {
    const int f =
        static_cast<int>(std::upper_bound(s.first.begin(), s.first.end(), k) - s.first.begin()) - 1;
    return std::pair{f, k - s.first[f]};
  };
  // The candidate pairs (k < l), sorted: the narrowphase then runs in pair order, which is
  // (figure_a, segment_a, figure_b, segment_b) order, whatever the sweep's.
  s.pairs.clear();
  for (int x = 0; x < n; ++x) {
    for (int y = x + 1; y < n && s.boxes[s.order[y]].lo.x() <= s.boxes[s.order[x]].hi.x(); ++y) {
      const int k = std::min(s.order[x], s.order[y]), l = std::max(s.order[x], s.order[y]);
      if (s.boxes[k].overlaps(s.boxes[l])) s.pairs.push_back({k, l});
    }
  }
  std::sort(s.pairs.begin(), s.pairs.end());
  ConvexContacts points;
  for (const auto& [k, l] : s.pairs) {
    const auto [fa, sa] = owner(k);
    const auto [fb, sb] = owner(l);
    if (!segments_may_collide(model, fa, sa, fb, sb)) continue;
    const int m = convex_contacts(s.solids[k], s.solids[l], points);
    for (int c = 0; c < m; ++c) {
      out.push_back({.figure_a = fa,
                     .segment_a = sa,
                     .figure_b = fb,
                     .segment_b = sb,
                     .point = points[c].point,
                     .normal = points[c].normal,
                     .depth = points[c].depth});
    }
  }
}

void settle_initial_segment_overlaps(Model& model) {
  model.segment_collisions = any_segment_pair_may_collide(model);
  if (!model.segment_collisions) return;
  const std::size_t n_figures = model.figures.size();
  std::vector<std::vector<SpatialTransform>> worlds(n_figures);
  FigureWorkspace ws;
  for (std::size_t f = 0; f < n_figures; ++f) {
    const FigureModel& figure = model.figures[f].model;
    size_figure_workspace(figure, ws);
    figure_kinematics(figure, model.figures[f].q0.data(), nullptr, ws);
    segment_world_transforms(figure, ws, worlds[f]);
  }
  SegmentCollisionScratch scratch;
  std::vector<SegmentContact> contacts;
  collect_segment_contacts(model, worlds, scratch, contacts);
  const auto note = [&](const std::string& text) {
    model.notes += (model.notes.empty() ? "" : "; ") + text;
  };
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const SegmentContact& k = contacts[c];
    if (c > 0 && k.figure_a == contacts[c - 1].figure_a &&
        k.segment_a == contacts[c - 1].segment_a && k.figure_b == contacts[c - 1].figure_b &&
        k.segment_b == contacts[c - 1].segment_b) {
      continue;  // the pair's other points
    }
    const FigureModel& a = model.figures[k.figure_a].model;
    const FigureModel& b = model.figures[k.figure_b].model;
    if (k.figure_a == k.figure_b) {
      CompiledFigure& figure = model.figures[k.figure_a];
      figure.self_pairs[k.segment_a * a.size() + k.segment_b] = 0;
      figure.self_pairs[k.segment_b * a.size() + k.segment_a] = 0;
      note("figure '" + a.name + "': segments '" + a.segments[k.segment_a].name + "' and '" +
           a.segments[k.segment_b].name +
           "' overlap at the initial pose, so they do not collide with each other");
    } else {
      note("figures '" + a.name + "' and '" + b.name + "' overlap at the start (segments '" +
           a.segments[k.segment_a].name + "' and '" + b.segments[k.segment_b].name +
           "'): their contact springs push them apart");
    }
  }
  model.segment_collisions = any_segment_pair_may_collide(model);
}

Vec3 segment_point_velocity(const SpatialTransform& world, const Vec6& v, const Vec3& point) {
  const MotionVector m = motion_from_vec6(v);
  const Vec3 local = world.E * (point - world.r);
  return world.E.transpose() * (m.linear + m.angular.cross(local));
}

}  // namespace pbm
