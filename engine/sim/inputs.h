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

struct Inputs {
  std::vector<TrackInput> tracks;  // at most one per track
};

}  // namespace pbm
