// Step 5 of 16.5: the tentative velocities u~, v~, w~ of every face with liquid on a side and no
// wall or inflow on either, from the velocities at the substep's start: the book's explicit
// finite differences of the Navier-Stokes equations (16.1), (16.2), or a semi-Lagrangian
// backtrace of the convective terms with the same gravity, pressure and viscous terms.
#pragma once

#include <vector>

#include "liquid/liquid_model.h"

namespace pbm {

struct MomentumInput {
  const std::vector<CellFlag>& flags;
  const std::vector<Real> (&face_scale)[3];  // 1/theta on faces to Surface cells (ghost fluid)
  const MacField& previous;                  // at the substep's start, boundaries set
  const std::vector<Real>& pressure;         // kinematic, at the substep's start
  Vec3 gravity;
  Real dt = 0;
};

void update_momentum(const LiquidModel& model, const MomentumInput& in, MacField& out);

}  // namespace pbm
