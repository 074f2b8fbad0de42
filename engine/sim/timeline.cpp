#include "sim/timeline.h"

namespace pbm {
namespace {

// What one cached frame costs: its vectors' heap blocks, the entry itself and the two map nodes
// that index it (about four pointers of tree links each). An estimate, but proportional to the
// real footprint, which is all a budget needs.
std::size_t entry_bytes(const State& state, const FrameStats& stats) {
  constexpr std::size_t kMapLinks = 4 * sizeof(void*);
  std::size_t n = kMapLinks + sizeof(int) + sizeof(State) + sizeof(FrameStats) +
                  sizeof(std::uint64_t) + sizeof(std::size_t);  // frames_ node
  n += kMapLinks + sizeof(std::uint64_t) + sizeof(int);         // by_age_ node
  n += sizeof(Real) * static_cast<std::size_t>(state.q.size() + state.v.size());
  for (const BodyFrameStats& body : stats.bodies) {
    n += sizeof(BodyFrameStats) + sizeof(Real) * static_cast<std::size_t>(body.q_s.size());
  }
  // A liquid's grid and markers are most of a liquid scene's state (a 64^3 grid: tens of MB).
  for (const LiquidState& liquid : state.liquids) n += liquid_state_bytes(liquid);
  n += sizeof(LiquidFrameStats) * stats.liquids.size();
  return n;
}

}  // namespace

Timeline::Timeline(std::size_t budget_bytes) : budget_(budget_bytes) {}

void Timeline::erase(std::map<int, Entry>::iterator it) {
  bytes_ -= it->second.bytes;
  by_age_.erase(it->second.serial);
  frames_.erase(it);
}

void Timeline::store(int frame, const State& state, const FrameStats& stats) {
  if (auto it = frames_.find(frame); it != frames_.end()) erase(it);
  Entry& entry = frames_[frame];
  entry.state = state;
  entry.stats = stats;
  entry.serial = next_serial_++;
  entry.bytes = entry_bytes(state, stats);
  bytes_ += entry.bytes;
  by_age_.emplace(entry.serial, frame);
  // Oldest first; by_age_'s last entry is the frame just stored and is never a candidate.
  auto oldest = by_age_.begin();
  while (bytes_ > budget_ && std::next(oldest) != by_age_.end()) {
    const int victim = oldest->second;
    ++oldest;
    if (victim != 0) erase(frames_.find(victim));
  }
}

const State* Timeline::find(int frame) const {
  const auto it = frames_.find(frame);
  return it == frames_.end() ? nullptr : &it->second.state;
}

const FrameStats* Timeline::stats(int frame) const {
  const auto it = frames_.find(frame);
  return it == frames_.end() ? nullptr : &it->second.stats;
}

int Timeline::nearest_at_or_before(int frame) const {
  auto it = frames_.upper_bound(frame);
  if (it == frames_.begin()) return -1;
  return std::prev(it)->first;
}

void Timeline::drop_after(int frame) {
  auto it = frames_.upper_bound(frame);
  while (it != frames_.end()) {
    const auto next = std::next(it);
    erase(it);
    it = next;
  }
}

void Timeline::clear() {
  frames_.clear();
  by_age_.clear();
  bytes_ = 0;
}

std::vector<std::pair<int, int>> Timeline::ranges() const {
  std::vector<std::pair<int, int>> runs;
  for (const auto& [frame, entry] : frames_) {
    if (!runs.empty() && runs.back().second + 1 == frame) {
      runs.back().second = frame;
    } else {
      runs.emplace_back(frame, frame);
    }
  }
  return runs;
}

}  // namespace pbm
