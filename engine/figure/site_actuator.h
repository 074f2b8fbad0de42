// Site trajectories (sec. 15.4): a site actuator pulls a site of a segment along a keyframed world
// path with a spring-damper, as a marionette's string pulls the puppet's hand. The force acts at
// the site; on the joints it is J^T F (inverse_dynamics.h's add_external_joint_forces), which is
// how the step applies it, among the actuators' forces whose work the stability guard counts.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/spatial.h"
#include "figure/figure_def.h"
#include "figure/figure_model.h"
#include "figure/site_ref.h"

namespace pbm {

struct CompiledSiteActuator {
  SiteRef site;
  SiteActuatorDef def;
};

// The site actuators of `def`, checked: the segment and site exist, each coordinate has keys in
// strictly increasing time, the gains are in range. `path`: the figure's JSON path.
std::vector<CompiledSiteActuator> compile_site_actuators(const FigureDef& def,
                                                         const FigureModel& figure,
                                                         const std::string& file,
                                                         const std::string& path);

// A target held from `time` on, over the path's keys (sim/inputs.h's SiteTargetInput: a mouse
// drag not yet recorded into the keys).
struct HeldSiteTarget {
  Real time = 0;
  Vec3 target = Vec3::Zero();
};

// One actuator at an instant: where its path is, where its site is, the force it exerts.
struct SitePull {
  Vec3 target = Vec3::Zero(), target_velocity = Vec3::Zero();  // p(t), p-dot(t) [m, m/s]
  Vec3 position = Vec3::Zero(), velocity = Vec3::Zero();       // the site's [m, m/s]
  Vec3 force = Vec3::Zero();                                   // on the site, world [N]
  bool saturated = false;                                      // |F| held at max_force
  bool active = true;  // t in [t_begin, t_end): outside, the force is zero
};

// The pull at time t with the site's segment at `world` (inertial -> segment) moving with spatial
// velocity v (segment coordinates, [angular; linear]); `held`, once its time has come, replaces
// the path (its target at rest).
SitePull site_pull(const CompiledSiteActuator& actuator, Real t, const SpatialTransform& world,
                   const Vec6& v, const std::optional<HeldSiteTarget>& held = {});

// The pull's force on its segment, about the segment's origin in its own coordinates.
ForceVector site_pull_force(const CompiledSiteActuator& actuator, const SpatialTransform& world,
                            const SitePull& pull);

}  // namespace pbm
