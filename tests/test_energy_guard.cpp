// The run-level stability guard (issue 12, docs/architecture.md "Stability guard"): the total
// energy may not grow beyond the work of the inputs by more than solver.energy_tolerance of the
// run's largest kinetic + elastic energy. The per-frame bound alone (10x per frame) let a slow
// explosion through: the jello-ball at 128 rings with its mass spread evenly, stepped past its
// explicit limit, gained energy for a second at under 10x a frame and flew off.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

// A membrane mode just past its explicit limit (a stiff jello-ball at 32 rings, substeps of 1.03x
// the body's Euler limit, ten to a frame): the mode grows from round-off by a few times a frame,
// under the per-frame bound, the way the 128-ring ball did on the ground. The model is
// edited after compiling: sim/model.cpp would shorten the substep to the limit.
struct ForcedRun {
  Model model;
  World world;
  Workspace ws;
  State state;
  Inputs inputs;
  FrameStats stats;
  explicit ForcedRun(Model m) : model(std::move(m)), world(make_world(model)) {
    init_workspace(world, ws);
    state = initial_state(model);
  }
};

Model past_the_limit(Real energy_tolerance, int max_retries) {
  Scene scene = load_scene(PBM_SOURCE_DIR "/scenes/jello-ball.json");
  BodyDef& b = scene.bodies[0];
  b.tessellation.rings = b.tessellation.segments = 32;
  b.material.w0 *= 16;  // a membrane 16x stiffer: its limit, 0.024 s, below the scene's dt
  b.material.w1 *= 16;
  scene.obstacles.clear();  // falling freely: only the membrane's own mode grows
  scene.solver.energy_tolerance = energy_tolerance;
  scene.solver.max_retries = max_retries;
  Model m = build_model(scene);
  const Real h = 1.002 * m.bodies[0].stability.dt_euler;
  m.substep = h;
  m.solver.fps = 1.0 / (10 * h);
  return m;
}

TEST(EnergyGuard, ASlowExplosionStopsTheRunNamingTheBody) {
  // Without the run-level guard (a tolerance nothing reaches) only the per-frame bound watches.
  Real worst_ratio = 0, largest = 0;
  int frames_unguarded = 0;
  {
    ForcedRun run(past_the_limit(1e300, 0));
    for (; frames_unguarded < 400; ++frames_unguarded) {
      const Real before = run.stats.kinetic + run.stats.elastic;
      const FrameResult r = advance_frame(run.world, run.inputs, run.state, run.ws, run.stats);
      const Real after = run.stats.kinetic + run.stats.elastic;
      if (!r.ok) break;
      if (before > 1.0) worst_ratio = std::max(worst_ratio, after / before);
      largest = std::max(largest, after);
    }
    std::printf(
        "per-frame guard only: %d frames, kinetic + elastic energy up to %.3g J, at most "
        "%.2fx per frame\n",
        frames_unguarded, largest, worst_ratio);
  }
  EXPECT_GT(largest, 1e9);       // it explodes ...
  EXPECT_LT(worst_ratio, 10.0);  // ... under the per-frame bound
  {
    ForcedRun run(past_the_limit(0.25, 0));
    FrameResult failed;
    int frames = 0;
    for (; frames < 400; ++frames) {
      failed = advance_frame(run.world, run.inputs, run.state, run.ws, run.stats);
      if (!failed.ok) break;
    }
    std::printf("run-level guard, no retries: stopped after %d frames at %.3g J: %s\n", frames,
                run.stats.kinetic + run.stats.elastic, failed.message.c_str());
    ASSERT_FALSE(failed.ok);
    EXPECT_LT(frames, frames_unguarded);
    EXPECT_LT(run.stats.kinetic + run.stats.elastic, 2e5);  // the fall's 5e4 J, not 1e9
    EXPECT_NE(failed.message.find("body 'jello'"), std::string::npos) << failed.message;
    EXPECT_NE(failed.message.find("beyond the work of the inputs"), std::string::npos)
        << failed.message;
    EXPECT_TRUE(run.state.q.allFinite());
  }
  // With the default retries the guard refines it away: frames it rejects are redone in half
  // substeps, under the limit, where the mode decays; the run goes on with bounded energy.
  ForcedRun run(past_the_limit(0.25, 4));
  int retries = 0;
  Real most = 0;
  for (int f = 0; f < 60; ++f) {
    const FrameResult r = advance_frame(run.world, run.inputs, run.state, run.ws, run.stats);
    ASSERT_TRUE(r.ok) << r.message;
    retries += run.stats.retries;
    most = std::max(most, run.stats.kinetic + run.stats.elastic);
  }
  std::printf("run-level guard with retries: 60 frames, %d retries, at most %.3g J\n", retries,
              most);
  EXPECT_GT(retries, 0);
  EXPECT_LT(most, 2e5);
}

// The work the inputs do is not surplus: a ball hung on a spring whose target a track moves up
// and down gains and loses its energy many times over, with no damping anywhere, and the
// surplus stays a small fraction of it (what the symplectic Euler step itself exchanges).
TEST(EnergyGuard, WorkOfMovingSpringTargetsIsNotCountedAsSurplus) {
  BodyDef b = test::ball(DeformLevel::rigid, 8);
  Scene s = test::free_space(b);
  s.gravity = Vec3(0, 0, -9.81);
  s.solver.dt = 1e-3;
  s.solver.fps = 30;
  SpringDef spring;
  spring.body = 0;
  spring.node = 0;
  spring.stiffness = 400;
  spring.damping = 0;
  spring.target = Vec3(0, 0, 1);
  s.springs.push_back(spring);
  TrackDef track;
  track.target = "springs[0].target[2]";
  track.interpolation = Interpolation::smooth;
  track.keys = {{0.0, 1.0}, {0.5, 2.0}, {1.0, 0.5}, {1.5, 2.5}, {2.0, 1.0}};
  s.tracks.push_back(track);
  Simulation sim(s);
  Real most_energy = 0, least_energy = 1e300, worst = 0;
  for (int f = 0; f < 60; ++f) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    const FrameStats& st = sim.stats;
    const Real e = st.kinetic + st.elastic + st.potential;
    most_energy = std::max(most_energy, e);
    least_energy = std::min(least_energy, e);
    worst = std::max(worst, st.energy_surplus);
  }
  std::printf(
      "spring on a track: total energy between %.3f and %.3f J, largest surplus %.4f J "
      "(limit %.3f J)\n",
      least_energy, most_energy, worst, sim.stats.energy_limit);
  EXPECT_GT(most_energy - least_energy, 20.0);            // the track does that much work
  EXPECT_LT(worst, 0.02 * (most_energy - least_energy));  // none of it is surplus
}

}  // namespace
}  // namespace pbm
