// Determinism by construction (docs/architecture.md, "Determinism"): what changes a later frame
// lives in State (rk45's step size, the contact-step flag), so a re-simulation after a seek, a
// fresh workspace and a workspace that saw another history all give the same bits, with the
// adaptive integrators (rk45, the implicit one's adaptive step) and with contact step reduction
// on.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "scene/scene_json.h"
#include "sim/runner.h"
#include "sim/simulation.h"
#include "sim/state.h"

namespace pbm {
namespace {

enum class Variant { rk45, contact_step_reduction, adaptive_implicit };

// The jello-ball (coarse, 8 x 8) dropping onto its slope: contacts from about frame 10 on.
Scene scene_for(Variant variant) {
  Scene scene = load_scene(PBM_SOURCE_DIR "/scenes/jello-ball.json");
  scene.bodies[0].tessellation.rings = scene.bodies[0].tessellation.segments = 8;
  if (variant == Variant::rk45) {
    scene.solver.integrator = IntegratorKind::rk45;
    scene.solver.tolerance = 1e-5;
  } else if (variant == Variant::adaptive_implicit) {
    // sim/adaptive_step.h: the level and the calm count in State choose the next substep.
    scene.solver.integrator = IntegratorKind::implicit;
    scene.solver.adaptive = true;
    scene.solver.adaptive_tolerance = 1e-3;
  } else {
    scene.solver.contact_step_reduction = true;
    scene.solver.contact_dt_factor = 0.25;
  }
  return scene;
}

void run_frames(Simulation& sim, int frames) {
  for (int f = 0; f < frames; ++f) ASSERT_TRUE(advance_frame(sim).ok) << sim.state.time;
}

const char* name_of(Variant v) {
  switch (v) {
    case Variant::rk45:
      return "rk45";
    case Variant::contact_step_reduction:
      return "contact step reduction";
    default:
      return "adaptive implicit";
  }
}

class Determinism : public testing::TestWithParam<Variant> {};

// One straight run of 40 frames against (a) 20 frames, then the state alone carried into a new
// Simulation (a fresh workspace) for 20 more; (b) a run whose workspace first computed frames 20
// to 30 and was then sent back to frame 20's state (what a seek does); (c) the workspace thrown
// away and rebuilt at frame 20 in place.
TEST_P(Determinism, FreshAndReusedWorkspacesGiveTheSameBits) {
  const Scene scene = scene_for(GetParam());
  Simulation straight(scene);
  run_frames(straight, 20);
  const State at_20 = straight.state;
  int touched = 0;
  for (int f = 0; f < 20; ++f) {
    ASSERT_TRUE(advance_frame(straight).ok);
    touched += straight.state.contact_nodes > 0;
  }
  // What the variant carries in State is in play: rk45 remembers a step, contacts split steps.
  if (GetParam() == Variant::rk45) {
    EXPECT_GT(straight.state.rk45_step, 0.0);
  } else if (GetParam() == Variant::adaptive_implicit) {
    EXPECT_GT(straight.state.adaptive_level + straight.state.adaptive_calm, 0);
  } else {
    EXPECT_GE(touched, 3);  // it bounces on the slope: 4 of these frames touch
  }
  Simulation fresh(scene);
  fresh.state = at_20;
  run_frames(fresh, 20);
  EXPECT_EQ(hash_state(fresh.state), hash_state(straight.state));

  Simulation seeked(scene);
  run_frames(seeked, 30);
  seeked.state = at_20;
  run_frames(seeked, 20);
  EXPECT_EQ(hash_state(seeked.state), hash_state(straight.state));

  Simulation rebuilt(scene);
  run_frames(rebuilt, 20);
  std::destroy_at(&rebuilt.ws);  // a Workspace is not assignable: a new one in place
  std::construct_at(&rebuilt.ws);
  init_workspace(rebuilt.world, rebuilt.ws);
  run_frames(rebuilt, 20);
  EXPECT_EQ(hash_state(rebuilt.state), hash_state(straight.state));
  std::printf(
      "%s: state hash %016llx at frame 40, rk45 step %.3g s, adaptive level %d, %d frames with "
      "contacts\n",
      name_of(GetParam()), static_cast<unsigned long long>(hash_state(straight.state)),
      straight.state.rk45_step, straight.state.adaptive_level, touched);
}

// The runner with a cache too small to keep frames (only frame 0 and the newest): every seek
// re-simulates, from frame 0 or from where it stands, and lands on the bits of the first visit.
// Whether the runner's timeline holds `frame` (then a seek restores it instead of computing it).
bool cached(const RunnerCore& core, int frame) {
  for (const auto& [first, last] : core.timeline().ranges()) {
    if (first <= frame && frame <= last) return true;
  }
  return false;
}

TEST_P(Determinism, SeekAndResimulateInTheRunnerGivesTheSameBits) {
  RunnerCore core(scene_for(GetParam()), 1);
  ASSERT_EQ(core.apply(Seek{40}), "");
  const std::uint64_t first = hash_state(core.state());
  ASSERT_FALSE(cached(core, 25));  // the seek below computes it
  ASSERT_EQ(core.apply(Seek{25}), "");
  const std::uint64_t at_25 = hash_state(core.state());
  ASSERT_FALSE(cached(core, 40));
  ASSERT_EQ(core.apply(Seek{40}), "");
  EXPECT_EQ(hash_state(core.state()), first);
  ASSERT_FALSE(cached(core, 25));
  ASSERT_EQ(core.apply(Seek{25}), "");
  EXPECT_EQ(hash_state(core.state()), at_25);
  EXPECT_EQ(core.message(), "");
}

INSTANTIATE_TEST_SUITE_P(Variants, Determinism,
                         testing::Values(Variant::rk45, Variant::contact_step_reduction,
                                         Variant::adaptive_implicit),
                         [](const testing::TestParamInfo<Variant>& param) {
                           switch (param.param) {
                             case Variant::rk45:
                               return std::string("Rk45");
                             case Variant::contact_step_reduction:
                               return std::string("ContactStepReduction");
                             default:
                               return std::string("AdaptiveImplicit");
                           }
                         });

}  // namespace
}  // namespace pbm
