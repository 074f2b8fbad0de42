// Inputs: what a user does during play (DESIGN §1), read by step() and nothing else.
#pragma once

#include <vector>

#include "core/types.h"

namespace pbm {

// The mouse spring of sec. 6.4: a spring-damper from a body node to a target point.
struct MouseSpring {
  int body = 0;
  int node = 0;
  Vec3 target = Vec3::Zero();  // [m], world
  Real stiffness = 0;          // [N/m]
  Real damping = 0;            // [N s/m]
};

struct Inputs {
  std::vector<MouseSpring> springs;
};

}  // namespace pbm
