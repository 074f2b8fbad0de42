// The plain superquadric's Jacobian J_i = ds_i/dq_s (2.9) by its structure, for the passes over
// every node and every contact point (deform/body_dynamics.cpp, collide/rigid_contact.cpp).
#pragma once

#include "deform/body_dynamics.h"

namespace pbm {

// The plain superquadric's J_i (2.9) has 11 non-zeros of 18 (superquadric_kinematics in
// deform/body_dynamics.cpp writes them): row x
// of e depends on (a0, a1, eps1, eps2), row y on (a0, a2, eps1, eps2), row z on (a0, a3, eps1).
[[gnu::always_inline]] inline bool sparse_superquadric(const BodyModel& body) {
  return body.shape == ShapeKind::superquadric && body.n_s == kSuperquadricParameters;
}

// J_i^T y added to out, and J_i g, over those non-zeros; J points at node i's block of Jt (rows
// x, y, z of J_i).
[[gnu::always_inline]] inline void add_superquadric_Jt_y(const Real* J, const Vec3& y, Real* out) {
  const Real* x = J;
  const Real* u = J + kSuperquadricParameters;
  const Real* z = J + 2 * kSuperquadricParameters;
  out[0] += x[0] * y[0] + u[0] * y[1] + z[0] * y[2];
  out[1] += x[1] * y[0];
  out[2] += u[2] * y[1];
  out[3] += z[3] * y[2];
  out[4] += x[4] * y[0] + u[4] * y[1] + z[4] * y[2];
  out[5] += x[5] * y[0] + u[5] * y[1];
}
[[gnu::always_inline]] inline Vec3 superquadric_J_times(const Real* J, const Real* g) {
  const Real* x = J;
  const Real* u = J + kSuperquadricParameters;
  const Real* z = J + 2 * kSuperquadricParameters;
  return Vec3(x[0] * g[0] + x[1] * g[1] + x[4] * g[4] + x[5] * g[5],
              u[0] * g[0] + u[2] * g[2] + u[4] * g[4] + u[5] * g[5],
              z[0] * g[0] + z[3] * g[3] + z[4] * g[4]);
}
[[gnu::always_inline]] inline const Real* node_J(const BodyWorkspace& ws, int i) {
  return ws.Jt.data() + 3 * kSuperquadricParameters * i;
}

}  // namespace pbm
