// The studio's trade panel runs the speed-versus-accuracy sweep (engine/sim/tradeoff.h) of the
// open scene on a thread of its own, so the UI stays live: progress is read while it runs, a
// cancel flag stops it after the run in progress, and the report is taken when it is done.
// Applying a point is one scene edit (the whole scene), so it undoes in one step.
#pragma once

#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "sim/tradeoff.h"

namespace pbm {

struct TradeoffProgressView {
  bool running = false;
  int done = 0, total = 0;
  std::string label;  // the run in progress
};

class TradeoffJob {
 public:
  TradeoffJob() = default;
  ~TradeoffJob();  // cancels and joins
  TradeoffJob(const TradeoffJob&) = delete;
  TradeoffJob& operator=(const TradeoffJob&) = delete;

  // Starts a sweep of `scene` (a copy is kept) with the knobs named; a sweep still running is
  // cancelled first.
  void start(const Scene& scene, const std::vector<std::string>& knobs, Real seconds);
  void cancel();
  TradeoffProgressView progress() const;
  // The finished sweep's report (once), or nothing while it runs or after a failure (error()).
  std::optional<TradeoffReport> take_report();
  std::string error() const;
  std::vector<std::string> notes() const;

 private:
  void join();
  mutable std::mutex mutex_;
  std::thread thread_;
  std::atomic<bool> cancel_{false};
  TradeoffProgressView progress_;
  std::optional<TradeoffReport> report_;
  std::string error_;
  std::vector<std::string> notes_;
};

// The scene JSON that applies a point of the sweep to `scene`: its solver.dt, integrator,
// tolerance and resolution, with shape_inertia_time held at the scene's, as the sweep measured.
nlohmann::json scene_with_setting(const Scene& scene, const TradeoffSetting& setting);

}  // namespace pbm
