#include "bench_drag.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/wall_clock.h"
#include "scene/scene_json.h"
#include "sim/runner.h"
#include "sim/simulation.h"

namespace pbm {

int run_bench_drag(const std::string& scene_file, int moves) {
  Scene scene;
  try {
    scene = load_scene(scene_file);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (scene.bodies.empty()) {
    spdlog::error("{}: bodies: the drag benchmark needs a body to pull", scene_file);
    return 2;
  }
  // The drag begins at frame 10 on node 0 of the first body; each frame then gets two moves at
  // its time (the first adds a key to the target tracks, the second replaces it), as a mouse
  // does between two frames.
  RunnerCore core(scene);
  core.apply(Seek{10});
  if (const std::string refused = core.apply(SpringBegin{0, 0, Vec3(0, 0, 3)}); !refused.empty()) {
    spdlog::error("{}", refused);
    return 1;
  }
  double move_seconds = 0, rebuild_seconds = 0, worst_move = 0;
  int n = 0;
  for (int i = 0; i < moves; ++i) {
    core.apply(StepFrame{});
    for (int j = 0; j < 2; ++j) {
      const auto t0 = WallClock::now();
      const std::string refused = core.apply(SpringMove{Vec3(0.01 * i, 0, 3 + 0.001 * j)});
      const double s = seconds_since(t0);
      if (!refused.empty()) {
        spdlog::error("{}", refused);
        return 1;
      }
      move_seconds += s;
      worst_move = std::max(worst_move, s);
      ++n;
    }
    // What a move cost when it recompiled the scene: a Simulation of the scene as recorded now.
    const auto t0 = WallClock::now();
    const auto rebuilt = std::make_unique<Simulation>(core.scene());
    rebuild_seconds += seconds_since(t0);
  }
  const double move = 1e6 * move_seconds / n, rebuild = 1e6 * rebuild_seconds / moves;
  std::printf("bench drag: '%s', %d moves over %d frames\n", scene.name.c_str(), n, moves);
  std::printf("%24s %12.1f us (worst %.1f us)\n", "one drag move", move, 1e6 * worst_move);
  std::printf("%24s %12.1f us\n", "recompiling the scene", rebuild);
  std::printf("%24s %12.1f x\n", "ratio", rebuild / move);
  return 0;
}

}  // namespace pbm
