// Rotational spring of a hinge (sec. 6.4, the spring-loaded see-saw): E = 1/2 k (theta - theta_0)^2
// about the hinge axis n, the form of the global stiffness energy (3.31). theta is the angle from
// body b's reference vector to body a's about n = R_a axis_a,
//   theta = atan2(n . (e_b x e_a), e_b . e_a),  e_a = R_a reference_a, e_b = R_b reference_b,
// so the generalized force is the torque tau = -(k (theta - theta_0) + c n . (w_a - w_b)) n on a
// (body frame: R_a^T tau in its omega rows) and -tau on b.
#pragma once

#include <vector>

#include "constrain/constraint_model.h"
#include "deform/body_dynamics.h"

namespace pbm {

// theta [rad] of the hinge at the kinematics in `bodies`.
Real hinge_angle(const HingeSpringModel& hinge, const std::vector<BodyWorkspace>& bodies);

// Sum of 1/2 k (theta - theta_0)^2 over the model's hinges [J].
Real hinge_spring_energy(const ConstrainedSystem& system, const std::vector<BodyWorkspace>& bodies);

// rates += the response of each body to its hinge torques: second order, A^+ of the generalized
// force; first order (3.51), (nu A)^+. force and delta: scratch per body, k entries each.
void add_hinge_spring_rates(const ConstrainedSystem& system, const VecX& v,
                            std::vector<BodyWorkspace>& bodies, std::vector<VecX>& force,
                            std::vector<VecX>& delta, VecX& rates);

}  // namespace pbm
