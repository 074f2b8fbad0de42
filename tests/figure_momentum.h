// A figure's total spatial momentum about the world origin, [angular; linear], for the tests that
// check momentum through impacts (tests/test_figure_impact.cpp,
// tests/test_figure_collisions_world.cpp).
#pragma once

#include <vector>

#include "figure_points.h"

namespace pbm::test {

inline Vec6 momentum(const FigureModel& figure, const Real* q, const Real* v) {
  const FigurePose pose = pose_of(figure, q, v);
  Vec6 total = Vec6::Zero();
  for (int i = 0; i < figure.size(); ++i) {
    const ForceVector h = force_from_vec6(pose.ws.inertia[i] * pose.ws.v[i]);
    total += to_vec6(transform_force(inverse(pose.world[i]), h));
  }
  return total;
}

inline Vec6 momentum(const FigureModel& figure, const VecX& q, const VecX& v) {
  return momentum(figure, q.data(), v.data());
}

}  // namespace pbm::test
