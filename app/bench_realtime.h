// `pbm bench realtime [folder]`: the real-time factor of every scene in a folder (default
// scenes/): simulated seconds per wall second over a run, and of the slowest frames. The studio
// steps the simulation on its own thread (engine/sim/runner.h) and plays at the scene's fps, so a
// scene plays in real time where every frame's step takes under 1 / fps.
#pragma once

#include <string>

namespace pbm {

int run_bench_realtime(const std::string& folder, double seconds);

}  // namespace pbm
