// `pbm bench drag`: the cost of one mouse-drag move (sec. 6.4's mouse spring, engine/sim/runner.h)
// on a scene, against what a move cost when every move recompiled the scene (a new Simulation
// from the scene with the key added), measured side by side in one run.
#pragma once

#include <string>

namespace pbm {

int run_bench_drag(const std::string& scene_file, int moves);

}  // namespace pbm
