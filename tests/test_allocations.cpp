// No heap allocation in the steady-state step (docs/architecture.md, "The step"): every scratch
// is sized when the workspace is built or first used, so a frame of a resting body or of
// assembled parts allocates nothing. The test binary interposes glibc's allocation functions
// (so Eigen's aligned allocations, which do not go through operator new, are counted too) and
// counts the calls made inside advance_frame.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdio>
#include <cstring>
#include <optional>

#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace {

// Plain globals: the interposed functions run before main and on every thread, where
// thread_local storage may not exist yet. The test itself is single-threaded.
bool g_counting = false;
long g_allocations = 0;

}  // namespace

// Out of line, so that a debugger can stop on it: `break pbm_counted_allocation` shows where an
// allocation inside a step comes from.
extern "C" __attribute__((noinline)) void pbm_counted_allocation() {
  ++g_allocations;
  asm volatile("");
}

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);

void* malloc(std::size_t size) {
  if (g_counting) pbm_counted_allocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  if (g_counting) pbm_counted_allocation();
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) {
  if (g_counting) pbm_counted_allocation();
  return __libc_realloc(pointer, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  if (g_counting) pbm_counted_allocation();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  if (g_counting) pbm_counted_allocation();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** pointer, std::size_t alignment, std::size_t size) {
  if (g_counting) pbm_counted_allocation();
  *pointer = __libc_memalign(alignment, size);
  return *pointer ? 0 : 12;  // ENOMEM
}
}

namespace pbm {
namespace {

std::string scene_path(const std::string& name) {
  return std::string(PBM_SOURCE_DIR) + "/scenes/" + name + ".json";
}

// Allocations inside `frames` calls of advance_frame after `warm_up` frames.
long allocations_in_frames(const std::string& scene, int warm_up, int frames,
                           std::optional<IntegratorKind> integrator = std::nullopt) {
  Scene loaded = load_scene(scene_path(scene));
  if (integrator) loaded.solver.integrator = *integrator;
  Simulation sim(loaded);
  for (int f = 0; f < warm_up; ++f) {
    const FrameResult r = advance_frame(sim);
    EXPECT_TRUE(r.ok) << r.message;
  }
  long total = 0;
  for (int f = 0; f < frames; ++f) {
    g_allocations = 0;
    g_counting = true;
    const FrameResult r = advance_frame(sim);
    g_counting = false;
    EXPECT_TRUE(r.ok) << r.message;
    total += g_allocations;
    if (g_allocations)
      std::printf("  frame %d: %ld\n", warm_up + f, static_cast<long>(g_allocations));
  }
  std::printf("%s: %ld heap allocations in %d frames after %d\n", scene.c_str(), total, frames,
              warm_up);
  return total;
}

// The counter counts: a frame of a fresh simulation allocates (its first measurement sizes the
// stats and the caches), so a zero below is not the counter failing.
TEST(Allocations, TheCounterSeesTheFirstFrame) {
  Simulation sim(load_scene(scene_path("jello-ball")));
  g_allocations = 0;
  g_counting = true;
  std::vector<double>* probe = new std::vector<double>(10);
  advance_frame(sim);
  g_counting = false;
  delete probe;
  EXPECT_GT(g_allocations, 1);
}

TEST(Allocations, RestingJelloBallStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("jello-ball", 240, 100), 0);
}

// The implicit integrator: its factor is made once (one substep length) and its compliant
// contact's scratch grows to the contact it meets, then stays.
TEST(Allocations, RestingJelloBallStepsWithoutAllocatingUnderTheImplicitIntegrator) {
  EXPECT_EQ(allocations_in_frames("jello-ball", 240, 100, IntegratorKind::implicit), 0);
}

TEST(Allocations, AssembledSnowmanStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("snowman", 60, 100), 0);
}

// A figure's step: the articulated-body method on the workspace sized once (sec. 15.2).
TEST(Allocations, PendulumChainStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("pendulum-chain", 2, 30), 0);
}

// Controlled figures: MRAC's state rates and torques, the frame's controller samples.
TEST(Allocations, WaistUnderMracStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("waist-step", 2, 20), 0);
}

// A figure's arm striking a deformable body (sim/segment_body_collisions.h): the strike is in
// frames 15-20, the ball's fall onto the floor after it.
TEST(Allocations, ASwingIntoAJelloBallStepsWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("figure-and-jello", 2, 40), 0);
}

// An impulse event (frame 9, t = 0.3 s) and the fall with its impacts on the ground after it.
TEST(Allocations, TheSoldiersShotAndFallStepWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("soldier", 2, 40), 0);
}

// Site actuators (the marionette's strings) and servos of a motion-capture clip.
TEST(Allocations, StringsAndMotionCaptureStepWithoutAllocating) {
  EXPECT_EQ(allocations_in_frames("marionette", 2, 30), 0);
  EXPECT_EQ(allocations_in_frames("mocap-wave", 2, 30), 0);
}

}  // namespace
}  // namespace pbm
