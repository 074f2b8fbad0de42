// Every deformable body of a scene at one moment, as the stages that couple bodies see them
// (collisions between bodies, self-collision, constraints): their models, their workspaces and
// the whole state vectors they own slices of. A view, made where a stage is called; it owns
// nothing.
#pragma once

#include <span>

#include "core/types.h"
#include "deform/body_model.h"
#include "deform/body_workspace.h"

namespace pbm {

struct BodySet {
  std::span<const BodyModel> models;  // in scene order
  std::span<BodyWorkspace> ws;        // one per model
  VecX& q;                            // State::q (every body's slice)
  VecX& v;                            // State::v
  Real time = 0;                      // of q and v [s]
  int size() const { return static_cast<int>(models.size()); }
};

}  // namespace pbm
