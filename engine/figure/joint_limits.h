// Joint limits (sec. 15.1.1's "joint limits (with their own impact)"): a revolute, prismatic or
// universal DOF kept within [lower, upper], a spherical joint's swing kept within a cone and its
// twist within [-twist_limit, twist_limit]. A
// limit watches a coordinate x(q) whose rate is a row g of v: a DOF's q with g = e_k, or the swing
// angle theta between the child's z axis and the joint frame's, cos theta = R_zz (R the joint's
// rotation, child to joint frame), whose rate is a . omega with a = (w x z) / |w x z|, w = R^T z
// the joint frame's z in the child's (omega in the child's frame, as the joint's v), or the
// twist psi = 2 atan2(z, w) about the child's z of the joint's quaternion (w, x, y, z) (the
// swing-twist decomposition q = swing twist), whose rate is g . omega with
// g = (zx - wy, wx + zy, w^2 + z^2) / (w^2 + z^2). Like a segment's contact (sec. 15.3), in two
// stages:
//  - an impact when the coordinate arrives at a limit faster than the figure's impact_speed: the
//    generalized impulse p along its row g (in place of the contact Jacobian) that leaves it at
//    -e times its rate, (15.2) in joint space: (G H^-1 G^T) p = -(1 + e) G q-dot for the limits
//    reached together, each p
//    pushing back into the range (projected Gauss-Seidel where the equalities' solution would
//    pull); q-dot += H^-1 G^T p;
//  - past the limit, a spring-damper tau = -k x - c x-dot on the DOF's overshoot x, that only
//    pushes. Its stiffness is the stiffest the scene's step integrates well: k = I (0.5 / dt)^2
//    with I = 1 / (H^-1)_kk the DOF's apparent inertia at the initial pose (a swing: the least
//    over the swing's directions, across the child's z), critically damped
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
  bool swing = false;  // a spherical joint's cone (q_index: its quaternion, v_index: omega)
  bool twist = false;  // a spherical joint's twist (q_index, v_index as a swing's)
  int q_index = 0, v_index = 0;  // in the figure's q and v
  Real lower = 0, upper = 0;     // [rad or m]; a swing: lower = -infinity, upper = the cone
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

// The limit's coordinate at q (a DOF's q, the swing or the twist angle [rad]) and its row g of v
// (1 entry at v_index for a DOF; 3 for a swing or a twist), the coordinate's rate being
// g . v[v_index ..].
Real limit_coordinate(const JointLimit& limit, const Real* q);
Vec3 limit_row(const JointLimit& limit, const Real* q);

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
