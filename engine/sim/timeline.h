// Timeline cache (docs/architecture.md, "Timeline"): the State and stats of every frame computed,
// so that scrubbing to a cached frame restores it exactly and scrubbing elsewhere re-simulates only
// from the nearest cached frame before it. Bounded by a memory budget: when over it, the frames
// stored longest ago go first, except frame 0 (every re-simulation can start there) and the frame
// just stored (the runner's current frame).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "sim/state.h"
#include "sim/world.h"

namespace pbm {

class Timeline {
 public:
  explicit Timeline(std::size_t budget_bytes);

  // Keeps a copy of frame `frame`'s state and stats, replacing what was stored for it (a
  // replaced frame counts as newly stored), then evicts down to the budget.
  void store(int frame, const State& state, const FrameStats& stats);
  const State* find(int frame) const;         // nullptr if not cached
  const FrameStats* stats(int frame) const;   // nullptr if not cached
  int nearest_at_or_before(int frame) const;  // largest cached frame <= frame, or -1
  void drop_after(int frame);                 // forgets every frame > frame
  void clear();
  std::vector<std::pair<int, int>> ranges() const;  // cached frames as inclusive runs, ascending
  std::size_t bytes() const { return bytes_; }      // estimated heap and bookkeeping held
  std::size_t budget() const { return budget_; }

 private:
  struct Entry {
    State state;
    FrameStats stats;
    std::uint64_t serial = 0;  // when it was stored: smaller = older
    std::size_t bytes = 0;
  };
  void erase(std::map<int, Entry>::iterator it);

  std::size_t budget_;
  std::size_t bytes_ = 0;
  std::uint64_t next_serial_ = 0;
  std::map<int, Entry> frames_;
  std::map<std::uint64_t, int> by_age_;  // serial -> frame, oldest first
};

}  // namespace pbm
