// A figure's total spatial momentum about the world origin, [angular; linear], for the tests that
// check momentum through impacts (tests/test_figure_impact.cpp,
// tests/test_figure_collisions_world.cpp).
#pragma once

#include <vector>

#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"

namespace pbm::test {

inline Vec6 momentum(const FigureModel& figure, const Real* q, const Real* v) {
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  figure_kinematics(figure, q, v, ws);
  std::vector<SpatialTransform> world;
  segment_world_transforms(figure, ws, world);
  Vec6 total = Vec6::Zero();
  for (int i = 0; i < figure.size(); ++i) {
    const ForceVector h = force_from_vec6(ws.inertia[i] * ws.v[i]);
    total += to_vec6(transform_force(inverse(world[i]), h));
  }
  return total;
}

inline Vec6 momentum(const FigureModel& figure, const VecX& q, const VecX& v) {
  return momentum(figure, q.data(), v.data());
}

}  // namespace pbm::test
