// Timeline cache (docs/architecture.md, "Timeline"): exact restore, the memory budget (oldest
// stored evicted first, frame 0 and the newest never), the ranges the studio draws, and dropping
// after an edit.
#include <gtest/gtest.h>

#include "sim/timeline.h"

namespace pbm {
namespace {

// A state whose bits say which frame (and which version of it) it is.
State state_of(int frame, Real version = 0) {
  State s;
  s.time = frame / 30.0;
  s.q = VecX::LinSpaced(100, frame, frame + 1) * (1 + version);
  s.v = VecX::Constant(99, frame + 0.25 + version);
  return s;
}

FrameStats stats_of(int frame) {
  FrameStats stats;
  stats.time = frame / 30.0;
  stats.kinetic = frame;
  stats.bodies.resize(1);
  stats.bodies[0].q_s = VecX::Constant(6, frame);
  return stats;
}

bool same(const State& a, const State& b) {
  return hash_state(a) == hash_state(b) && a.time == b.time && a.q == b.q && a.v == b.v;
}

using Ranges = std::vector<std::pair<int, int>>;

// Bytes one frame of this size costs, as the timeline counts it.
std::size_t frame_bytes() {
  Timeline probe(std::size_t{1} << 30);
  probe.store(0, state_of(0), stats_of(0));
  return probe.bytes();
}

TEST(Timeline, StoresAndRestoresExactly) {
  Timeline timeline(std::size_t{1} << 30);
  for (int f = 0; f <= 10; ++f) timeline.store(f, state_of(f), stats_of(f));
  ASSERT_NE(timeline.find(7), nullptr);
  EXPECT_TRUE(same(*timeline.find(7), state_of(7)));
  EXPECT_EQ(timeline.stats(7)->kinetic, 7);
  EXPECT_EQ(timeline.find(11), nullptr);
  EXPECT_EQ(timeline.stats(-1), nullptr);
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 10}}));
  EXPECT_EQ(timeline.bytes(), 11 * frame_bytes());
}

TEST(Timeline, BudgetEvictsTheOldestStoredButNeverFrameZero) {
  const std::size_t one = frame_bytes();
  ASSERT_GT(one, 199 * sizeof(Real));    // at least its q and v
  Timeline timeline(5 * one + one / 2);  // room for five frames
  for (int f = 0; f <= 20; ++f) {
    timeline.store(f, state_of(f), stats_of(f));
    EXPECT_LE(timeline.bytes(), timeline.budget());
  }
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 0}, {17, 20}}));
  EXPECT_EQ(timeline.bytes(), 5 * one);
  EXPECT_TRUE(same(*timeline.find(0), state_of(0)));

  // Storing a frame again makes it the newest: 17 is now the oldest after 0.
  timeline.store(18, state_of(18, 1), stats_of(18));
  timeline.store(21, state_of(21), stats_of(21));
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 0}, {18, 21}}));
  EXPECT_TRUE(same(*timeline.find(18), state_of(18, 1)));
  // Oldest now: 19, 20, 18, 21; a re-simulated early frame evicts 19, not the re-stored 18.
  timeline.store(5, state_of(5), stats_of(5));
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 0}, {5, 5}, {18, 18}, {20, 21}}));
}

TEST(Timeline, BudgetBelowOneFrameKeepsFrameZeroAndTheNewest) {
  Timeline timeline(1);
  for (int f = 0; f <= 4; ++f) timeline.store(f, state_of(f), stats_of(f));
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 0}, {4, 4}}));
  EXPECT_EQ(timeline.bytes(), 2 * frame_bytes());
}

TEST(Timeline, NearestAtOrBeforeAndDropAfter) {
  Timeline timeline(std::size_t{1} << 30);
  for (int f : {0, 1, 2, 3, 7, 8, 12}) timeline.store(f, state_of(f), stats_of(f));
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 3}, {7, 8}, {12, 12}}));
  EXPECT_EQ(timeline.nearest_at_or_before(-1), -1);
  EXPECT_EQ(timeline.nearest_at_or_before(0), 0);
  EXPECT_EQ(timeline.nearest_at_or_before(6), 3);
  EXPECT_EQ(timeline.nearest_at_or_before(7), 7);
  EXPECT_EQ(timeline.nearest_at_or_before(100), 12);

  timeline.drop_after(7);
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 3}, {7, 7}}));
  EXPECT_EQ(timeline.bytes(), 5 * frame_bytes());
  EXPECT_EQ(timeline.find(8), nullptr);
  EXPECT_EQ(timeline.nearest_at_or_before(100), 7);

  // Dropped frames no longer count against the budget's age order: storing more evicts only
  // frames still held.
  timeline.drop_after(0);
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 0}}));
  EXPECT_EQ(timeline.bytes(), frame_bytes());

  timeline.clear();
  EXPECT_TRUE(timeline.ranges().empty());
  EXPECT_EQ(timeline.bytes(), 0u);
  EXPECT_EQ(timeline.nearest_at_or_before(100), -1);
}

TEST(Timeline, EvictionAfterDropSkipsDroppedFrames) {
  const std::size_t one = frame_bytes();
  Timeline timeline(3 * one + one / 2);  // three frames
  for (int f = 0; f <= 2; ++f) timeline.store(f, state_of(f), stats_of(f));
  timeline.drop_after(1);
  timeline.store(5, state_of(5), stats_of(5));
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 1}, {5, 5}}));
  timeline.store(6, state_of(6), stats_of(6));
  EXPECT_EQ(timeline.ranges(), (Ranges{{0, 0}, {5, 6}}));
}

}  // namespace
}  // namespace pbm
