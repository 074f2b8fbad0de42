// The knobs of collisions between bodies (sec. 5.2.2, collide/body_collisions.h) and which bodies
// they leave alone, on their own so that the Model can hold them without the collision code.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace pbm {

struct BodyCollisionOptions {
  bool enabled = true;
  // Proximity band [m]: triangles' boxes are fattened by it, and pairs closer than it are
  // contacts (speculative while apart). Small against the triangles' size.
  Real margin = 0.02;
  // A node found farther than this behind a face is taken for one on the far side of a thin
  // part, not a contact [m]. Larger than the deepest penetration one step can make.
  Real max_depth = 0.1;
  Real friction = 0.3;  // b_f of (5.13), >= 0
  // a of (5.11) between bodies, >= 0 (collide/body_push.h); 0 keeps the contacts inelastic only.
  Real elasticity = 0;
  bool self_collision = true;
  int iterations = 16;  // Gauss-Seidel sweeps of the impulses, and passes of the projection
};

struct BodyCollisionModel {
  BodyCollisionOptions options;
  // Body pairs (a < b) joined by a constraint (ch. 7): they touch at the joint by design, and
  // colliding them would fight the constraint force (Bullet's "disable collisions between linked
  // bodies" does the same).
  std::vector<std::array<int, 2>> joined;
  // Per body: an end of some constraint. A rigid or global part held so is not translated by the
  // projection: the constraint force, computed with the dynamics, cannot follow a jump of c, and
  // a see-saw knocked off its hinge by every landing ball would sink.
  std::vector<char> constrained;
  bool joined_pair(int a, int b) const {
    for (const std::array<int, 2>& pair : joined) {
      if ((pair[0] == a && pair[1] == b) || (pair[0] == b && pair[1] == a)) return true;
    }
    return false;
  }
};

}  // namespace pbm
