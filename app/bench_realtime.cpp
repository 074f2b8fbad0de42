#include "bench_realtime.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/error.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {

namespace fs = std::filesystem;

int run_bench_realtime(const std::string& folder, double seconds) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    const fs::path& p = entry.path();
    if (p.extension() == ".json" && p.filename() != "scene.schema.json") files.push_back(p);
  }
  if (ec || files.empty()) {
    spdlog::error("{}: no scene files ({})", folder, ec ? ec.message() : "none found");
    return 2;
  }
  std::sort(files.begin(), files.end());
  std::printf(
      "bench realtime: each scene for %.3g s (or its duration), frames stepped one after another "
      "as the studio's engine thread does; real-time factor = simulated s / wall s\n",
      seconds);
  std::printf("%-16s %6s %7s %10s %10s %10s %9s\n", "scene", "fps", "frames", "whole run",
              "95% frames", "slowest", "real time");
  int code = 0;
  for (const fs::path& file : files) {
    std::unique_ptr<Simulation> sim;
    try {
      sim = std::make_unique<Simulation>(load_scene(file.string()));
    } catch (const Error& e) {
      spdlog::error("{}", e.what());
      code = 2;
      continue;
    }
    const Real fps = sim->model.solver.fps;
    const long frames =
        std::max(1L, std::lround(std::min(seconds, sim->model.solver.duration) * fps));
    std::vector<double> wall;
    wall.reserve(static_cast<std::size_t>(frames));
    bool failed = false;
    for (long f = 0; f < frames; ++f) {
      const auto t0 = std::chrono::steady_clock::now();
      const FrameResult r = advance_frame(*sim);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      if (!r.ok) {
        spdlog::error("{}: frame {} failed: {}", file.string(), f + 1, r.message);
        failed = true;
        code = 1;
        break;
      }
    }
    if (failed) continue;
    double total = 0;
    for (double w : wall) total += w;
    std::vector<double> sorted = wall;
    std::sort(sorted.begin(), sorted.end());
    const double p95 = sorted[static_cast<std::size_t>(0.95 * (sorted.size() - 1))];
    const double frame = 1.0 / fps;
    const double whole = frames * frame / total;
    const double at_p95 = frame / p95;
    const double slowest = frame / sorted.back();
    std::printf("%-16s %6.3g %7ld %10.2f %10.2f %10.2f %9s\n", file.stem().string().c_str(), fps,
                frames, whole, at_p95, slowest, at_p95 >= 1 ? "yes" : "no");
  }
  return code;
}

}  // namespace pbm
