// Joint limits (sec. 15.1.1's "joint limits (with their own impact)"): a revolute, prismatic or
// universal DOF kept within [lower, upper]. Like a segment's contact (sec. 15.3), in two stages:
//  - an impact when the DOF arrives at a limit faster than the figure's impact_speed: the
//    generalized impulse p along the DOF's coordinate direction (a row e_k of the identity in
//    place of the contact Jacobian) that leaves it at -e times its velocity, (15.2) in joint
//    space: (G H^-1 G^T) p = -(1 + e) G q-dot for the DOFs at their limits together, each p
//    pushing back into the range (projected Gauss-Seidel where the equalities' solution would
//    pull); q-dot += H^-1 G^T p;
//  - past the limit, a spring-damper tau = -k x - c x-dot on the DOF's overshoot x, that only
//    pushes. Its stiffness is the stiffest the scene's step integrates well: k = I (0.5 / dt)^2
//    with I = 1 / (H^-1)_kk the DOF's apparent inertia at the initial pose, critically damped
//    (c = 2 sqrt(k I)); so a limit holds a load tau within tau / k = 4 tau dt^2 / I, and
//    tightening dt makes it harder, converging on the hard limit.
#pragma once

#include <vector>

#include "figure/figure_def.h"
#include "figure/figure_impact.h"
#include "figure/figure_model.h"

namespace pbm {

struct JointLimit {
  int segment = 0, dof = 0;
  int q_index = 0, v_index = 0;  // in the figure's q and v
  Real lower = 0, upper = 0;     // [rad or m]
  Real restitution = 0;
  Real stiffness = 0, damping = 0;  // of the spring past the limit (size_joint_limits)
};

// The figure's limits from its segments' joints. Throws pbm::Error naming
// `path`.segments[i].joint.lower / .upper / .limit_restitution.
std::vector<JointLimit> compile_joint_limits(const FigureDef& def, const FigureModel& figure,
                                             const std::string& file, const std::string& path);

// Sets each limit's spring for a step dt from the DOF's apparent inertia at q0.
void size_joint_limits(const FigureModel& figure, const VecX& q0, Real dt,
                       std::vector<JointLimit>& limits);

// Adds the springs past the limits to tau (n_v), but not at the DOFs arriving faster than
// impact_speed (their impact comes first).
void add_joint_limit_forces(const std::vector<JointLimit>& limits, const Real* q, const Real* v,
                            Real impact_speed, Real* tau);

// Their potential energy [J].
Real joint_limit_energy(const std::vector<JointLimit>& limits, const Real* q);

// The impact stage: the DOFs past a limit and moving out faster than impact_speed have their
// impact together, v changed in place. Returns how many DOFs had one.
int resolve_limit_impacts(const FigureModel& figure, const std::vector<JointLimit>& limits,
                          const Real* q, Real* v, Real impact_speed, ImpactWorkspace& ws);

}  // namespace pbm
