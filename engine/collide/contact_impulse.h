// One projected Gauss-Seidel update of a contact's accumulated impulse, shared by the contacts
// between bodies (body_collisions.h) and within one body (self_collision.h).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/types.h"

namespace pbm {

// j = (j_n, j_t1, j_t2) accumulated so far; u the pair's relative velocity in its basis (n, t1,
// t2); `allowed` the approach speed still permitted along n (a gap closing within the step);
// inverse_mass the pair's along n, t1, t2. The normal part stops the approach (inelastic, never
// pulling); the tangential part stops the slip within Coulomb's cone |j_t| <= b_f j_n (5.13).
inline Vec3 updated_contact_impulse(const Vec3& j_old, const Vec3& u, Real allowed,
                                    const Vec3& inverse_mass, Real friction) {
  Vec3 j = j_old;
  j[0] = std::max(0.0, j[0] - (u[0] + allowed) / inverse_mass[0]);
  if (friction > 0) {
    j[1] -= u[1] / inverse_mass[1];
    j[2] -= u[2] / inverse_mass[2];
    const Real jt = std::hypot(j[1], j[2]);
    const Real limit = friction * j[0];  // (5.13)
    if (jt > limit) {
      j[1] *= limit / jt;
      j[2] *= limit / jt;
    }
  } else {
    j[1] = j[2] = 0;
  }
  return j;
}

}  // namespace pbm
