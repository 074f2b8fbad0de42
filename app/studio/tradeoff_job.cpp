#include "tradeoff_job.h"

#include "core/error.h"
#include "scene/scene_json.h"

namespace pbm {

TradeoffJob::~TradeoffJob() {
  cancel();
  join();
}

void TradeoffJob::join() {
  if (thread_.joinable()) thread_.join();
}

void TradeoffJob::cancel() {
  cancel_ = true;
}

void TradeoffJob::start(const Scene& scene, const std::vector<std::string>& knobs, Real seconds) {
  cancel();
  join();
  cancel_ = false;
  {
    const std::lock_guard lock(mutex_);
    progress_ = TradeoffProgressView{true, 0, 0, "starting"};
    report_.reset();
    error_.clear();
    notes_.clear();
  }
  thread_ = std::thread([this, scene, knobs, seconds] {
    try {
      TradeoffOptions options;
      options.seconds = seconds;
      std::vector<std::string> notes;
      options.knobs = default_knobs(scene, knobs, notes);
      {
        const std::lock_guard lock(mutex_);
        notes_ = notes;
      }
      auto progress = [this](int done, int total, const std::string& label) {
        const std::lock_guard lock(mutex_);
        progress_.done = done;
        progress_.total = total;
        progress_.label = label;
      };
      TradeoffReport report = run_tradeoff(scene, options, progress, &cancel_);
      const std::lock_guard lock(mutex_);
      if (report.cancelled) {
        error_ = "cancelled";
      } else {
        report_ = std::move(report);
      }
      progress_.running = false;
    } catch (const Error& e) {
      const std::lock_guard lock(mutex_);
      error_ = e.what();
      progress_.running = false;
    }
  });
}

TradeoffProgressView TradeoffJob::progress() const {
  const std::lock_guard lock(mutex_);
  return progress_;
}

std::optional<TradeoffReport> TradeoffJob::take_report() {
  const std::lock_guard lock(mutex_);
  std::optional<TradeoffReport> report = std::move(report_);
  report_.reset();
  return report;
}

std::string TradeoffJob::error() const {
  const std::lock_guard lock(mutex_);
  return error_;
}

std::vector<std::string> TradeoffJob::notes() const {
  const std::lock_guard lock(mutex_);
  return notes_;
}

nlohmann::json scene_with_setting(const Scene& scene, const TradeoffSetting& setting) {
  return nlohmann::json::parse(scene_to_json(apply_setting(scene, setting)));
}

}  // namespace pbm
