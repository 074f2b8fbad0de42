#include "figure/site_actuator.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace pbm {

std::vector<CompiledSiteActuator> compile_site_actuators(const FigureDef& def,
                                                         const FigureModel& figure,
                                                         const std::string& file,
                                                         const std::string& path) {
  std::vector<CompiledSiteActuator> out;
  out.reserve(def.site_actuators.size());
  for (std::size_t k = 0; k < def.site_actuators.size(); ++k) {
    const SiteActuatorDef& d = def.site_actuators[k];
    const std::string at = path + ".site_actuators[" + std::to_string(k) + "]";
    require_keyframes(d.x, file, at + ".x");
    require_keyframes(d.y, file, at + ".y");
    require_keyframes(d.z, file, at + ".z");
    if (!(d.stiffness > 0) || !std::isfinite(d.stiffness)) {
      throw Error(file, at + ".stiffness", "must be > 0 and finite");
    }
    if (!(d.damping >= 0) || !std::isfinite(d.damping)) {
      throw Error(file, at + ".damping", "must be >= 0 and finite");
    }
    if (d.max_force && (!(*d.max_force > 0) || !std::isfinite(*d.max_force))) {
      throw Error(file, at + ".max_force", "must be > 0 and finite");
    }
    if (!(d.t_begin >= 0) || !std::isfinite(d.t_begin)) {
      throw Error(file, at + ".t_begin", "must be >= 0 and finite");
    }
    if (d.t_end && !(*d.t_end >= d.t_begin)) {
      throw Error(file, at + ".t_end", "must be >= t_begin");
    }
    if (!(d.ramp >= 0) || !std::isfinite(d.ramp)) {
      throw Error(file, at + ".ramp", "must be >= 0 and finite");
    }
    out.push_back({find_site(def, figure, d.segment, d.site, file, at), d});
  }
  return out;
}

SitePull site_pull(const CompiledSiteActuator& actuator, Real t, const SpatialTransform& world,
                   const Vec6& v, const std::optional<HeldSiteTarget>& held) {
  const SiteActuatorDef& d = actuator.def;
  SitePull pull;
  if (held && held->time <= t) {
    pull.target = held->target;
  } else {
    pull.target =
        Vec3(evaluate_keys(d.interpolation, d.x, t), evaluate_keys(d.interpolation, d.y, t),
             evaluate_keys(d.interpolation, d.z, t));
    pull.target_velocity = Vec3(evaluate_keys_rate(d.interpolation, d.x, t),
                                evaluate_keys_rate(d.interpolation, d.y, t),
                                evaluate_keys_rate(d.interpolation, d.z, t));
  }
  const Vec3& local = actuator.site.position;
  pull.position = world.r + world.E.transpose() * local;
  pull.velocity = world.E.transpose() * (v.tail<3>() + v.head<3>().cross(local));
  pull.active = t >= d.t_begin && !(d.t_end && t >= *d.t_end);
  if (!pull.active) return pull;
  // A grab ramps its gains in, so that taking hold of a figure at rest does not jolt it.
  const Real ramp = d.ramp > 0 ? std::min<Real>((t - d.t_begin) / d.ramp, 1) : 1;
  pull.force = ramp * (d.stiffness * (pull.target - pull.position) +
                       d.damping * (pull.target_velocity - pull.velocity));
  if (d.max_force) {
    const Real size = pull.force.norm();
    if (size > *d.max_force) {
      pull.force *= *d.max_force / size;
      pull.saturated = true;
    }
  }
  return pull;
}

ForceVector site_pull_force(const CompiledSiteActuator& actuator, const SpatialTransform& world,
                            const SitePull& pull) {
  const Vec3 f = world.E * pull.force;
  return {actuator.site.position.cross(f), f};
}

}  // namespace pbm
