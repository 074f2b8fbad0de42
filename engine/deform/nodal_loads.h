// External nodal forces on a body (f in 3.47), world frame: gravity and force fields, the scene's
// springs (sec. 6.4: a spring-damper from a node to a target, the mouse spring among them) and
// the damping D = nu M of second-order bodies (sec. 6.1). Needs the body's kinematics.
#pragma once

#include <span>

#include "core/types.h"
#include "deform/body_def.h"
#include "deform/body_model.h"
#include "deform/body_workspace.h"

namespace pbm {

// What drives the loads at one time: gravity, and each spring's target and stiffness after
// tracks (one entry per spring).
struct NodalLoadDrive {
  Vec3 gravity = Vec3::Zero();
  std::span<const Vec3> spring_target;
  std::span<const Real> spring_stiffness;
};

// Writes bw.force for body `b` at time t (springs act within [t_begin, t_end]).
void compute_nodal_loads(const BodyModel& body, int b, std::span<const ForceFieldDef> fields,
                         std::span<const SpringModel> springs, const NodalLoadDrive& drive, Real t,
                         BodyWorkspace& bw);

// The potential of those loads besides gravity [J] at bw.x: -sum f . x_i of the uniform force
// fields, and each active spring's 1/2 k |target - x|^2, linear past its max_force (the
// potential of the clamped pull). With it the stability guard counts what a moving spring
// target or a switched-on field gives as work done by the inputs (docs/architecture.md,
// "Stability guard"). Dampers are not potentials: they only take energy.
Real nodal_load_potential(const BodyModel& body, int b, std::span<const ForceFieldDef> fields,
                          std::span<const SpringModel> springs, const NodalLoadDrive& drive, Real t,
                          const BodyWorkspace& bw);

}  // namespace pbm
