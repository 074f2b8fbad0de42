#include "figure/figure_impulse.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "figure/articulated_body.h"
#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"

namespace pbm {

std::vector<CompiledImpulse> compile_impulses(const FigureDef& def, const FigureModel& figure,
                                              const std::string& file, const std::string& path) {
  std::vector<CompiledImpulse> out;
  out.reserve(def.impulses.size());
  for (std::size_t k = 0; k < def.impulses.size(); ++k) {
    const ImpulseDef& d = def.impulses[k];
    const std::string at = path + ".impulses[" + std::to_string(k) + "]";
    if (!(d.time >= 0) || !std::isfinite(d.time)) {
      throw Error(file, at + ".time", "must be >= 0 and finite");
    }
    if (!d.linear.allFinite()) throw Error(file, at + ".impulse", "must be finite");
    if (!d.angular.allFinite()) throw Error(file, at + ".angular", "must be finite");
    if (d.linear.isZero(0) && d.angular.isZero(0)) {
      throw Error(file, at + ".impulse", "an impulse needs a non-zero impulse or angular");
    }
    out.push_back({.time = d.time,
                   .site = find_site(def, figure, d.segment, d.site, file, at),
                   .linear = d.linear,
                   .angular = d.angular,
                   .frame = d.frame});
  }
  std::stable_sort(out.begin(), out.end(), [](const CompiledImpulse& a, const CompiledImpulse& b) {
    return a.time < b.time;
  });
  return out;
}

void size_impulse_scratch(int n_v, int segments, ImpulseScratch& scratch) {
  scratch.forces.assign(static_cast<std::size_t>(segments), ForceVector{});
  scratch.world.reserve(static_cast<std::size_t>(segments));
  scratch.zero.setZero(n_v);
  scratch.dv.setZero(n_v);
}

Real apply_impulse(const FigureModel& figure, const Real* q, Real* v,
                   const CompiledImpulse& impulse, ImpulseScratch& scratch, FigureWorkspace& ws) {
  const int i = impulse.site.segment;
  figure_kinematics(figure, q, v, ws);
  const Vec6 before = ws.v[i];
  // P in the segment's coordinates, about its origin: a site-frame vector turns by the site's
  // axes; a world one by the segment's (E of world -> segment).
  Vec3 linear = impulse.site.rotation * impulse.linear;
  Vec3 angular = impulse.site.rotation * impulse.angular;
  if (impulse.frame == ImpulseFrame::world) {
    segment_world_transforms(figure, ws, scratch.world);
    linear = scratch.world[i].E * impulse.linear;
    angular = scratch.world[i].E * impulse.angular;
  }
  ForceVector& P = scratch.forces[i];
  P = ForceVector{angular + impulse.site.position.cross(linear), linear};
  const int n_v = figure.n_v;
  forward_dynamics(figure, q, nullptr, scratch.zero.data(), scratch.forces, Vec3::Zero(), ws,
                   scratch.dv.data());
  const Vec6 P6 = to_vec6(P);
  P = ForceVector{};
  Eigen::Map<VecX>(v, n_v) += scratch.dv.head(n_v);
  // The struck segment's velocity change J dv, by the outward pass at dv alone.
  figure_kinematics(figure, q, scratch.dv.data(), ws);
  return (before + 0.5 * ws.v[i]).dot(P6);
}

}  // namespace pbm
