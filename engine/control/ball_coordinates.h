// A spherical joint's exponential coordinates, through which the per-DOF controllers of sec. 15.4
// (MRAC (15.10)-(15.17), PD) drive a ball joint: the rotation vector r = log(R) of the joint's
// rotation R (child to joint frame; r is the same in both, R r = r), whose three components are
// three coordinates like a universal joint's two. With omega the joint's angular velocity in the
// child's frame (R-dot = R [omega]x), r-dot = J_r(r)^-1 omega, J_r the right Jacobian of SO(3),
//   J_r^-1 = I + [r]x / 2 + (1 / theta^2 - (1 + cos theta) / (2 theta sin theta)) [r]x^2,
// theta = |r|. A controller's force u on r_k does the work u r_k-dot = (u e_k^T J_r^-1) omega, so
// it enters the joint as the torque u (J_r^-T e_k). The chart covers rotations below pi from rest
// (the axis flips at pi), as a swing cone does; a target trajectory is followed there.
#pragma once

#include "core/types.h"

namespace pbm {

// r = log(R) of the unit quaternion (w, x, y, z) (q and -q: the same r, |r| <= pi).
Vec3 ball_rotation_vector(const Real* quaternion);

// J_r(r)^-1: r-dot = J_r^-1 omega (omega in the child's frame).
Mat3 ball_rate_map(const Vec3& r);

// The rotation vector nearest `previous` of the rotation r (r itself or r (1 - 2 pi / |r|), the
// same rotation turned the other way round), so that a sampled trajectory stays continuous.
Vec3 ball_rotation_vector_near(const Vec3& r, const Vec3& previous);

}  // namespace pbm
