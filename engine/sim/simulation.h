// The one setup path (docs/architecture.md, "Simulation"): a scene compiled into its Model, the
// World of its subsystems, a Workspace sized for them, the initial State and its measurement.
// The command line, the benchmarks, the renderer, the runner and the tests all start here.
#pragma once

#include "scene/scene.h"
#include "sim/frame_stats.h"
#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/world.h"

namespace pbm {

struct Simulation {
  // Throws pbm::Error (file, JSON path) when the scene does not compile.
  explicit Simulation(const Scene& scene);
  // The world holds the model's address: a Simulation stays where it was made.
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const Model model;
  const World world;
  Workspace ws;
  State state;
  Inputs inputs;
  FrameStats stats;  // of `state`: its measurement, then every frame's
};

// One frame of the simulation with its inputs (advance_frame of sim/world.h into sim.stats).
FrameResult advance_frame(Simulation& sim);

}  // namespace pbm
