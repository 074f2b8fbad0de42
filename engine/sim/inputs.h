// Inputs: what the user does during play that the Model does not hold yet (docs/architecture.md,
// "Inputs"), a parameter of every step. Each input sets a track's value from a time on, exactly
// as a step key of that track would: the runner records every input into the scene as that key,
// so the frames computed live and the frames of the saved scene replayed (where the keys are
// part of the Model) are bit-identical. A mouse drag is such an input (sim/runner.h).
#pragma once

#include <vector>

#include "core/types.h"

namespace pbm {

struct TrackInput {
  int track = 0;   // index into Model::tracks (scene order)
  Real time = 0;   // from when [s]
  Real value = 0;  // what the track holds from then on
};

// A joint controller's target set from the control panel (sim/runner.h, ControlSet): from `time`
// on, the controller's desired position is value + rate (t - time), exactly as the key the runner
// records into its `live` keys (control/controller_def.h, LiveKey).
struct ControlInput {
  int figure = 0;      // index into Model::figures
  int controller = 0;  // index into its controllers
  Real time = 0;
  Real value = 0;
  Real rate = 0;
};

// A site actuator's target set by a mouse drag on a figure (sim/runner.h, SpringMove): from `time`
// on its path holds `target`, exactly as the step keys the runner records into its x, y, z.
struct SiteTargetInput {
  int figure = 0;
  int actuator = 0;  // index into its site actuators
  Real time = 0;
  Vec3 target = Vec3::Zero();
};

struct Inputs {
  std::vector<TrackInput> tracks;             // at most one per track
  std::vector<ControlInput> controls;         // at most one per controller
  std::vector<SiteTargetInput> site_targets;  // at most one per site actuator
};

}  // namespace pbm
