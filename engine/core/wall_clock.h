// Wall time for the cost reports (stage times, collision phases): the steady clock, never the
// system clock, so a clock adjustment cannot make a stage cost negative. Costs are reported, never
// used by the physics: nothing that reads this changes a result.
#pragma once

#include <chrono>

namespace pbm {

using WallClock = std::chrono::steady_clock;

// Seconds elapsed since t0.
inline double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

}  // namespace pbm
