#include "sim/simulation.h"

#include "sim/stages_liquid.h"

namespace pbm {

Simulation::Simulation(const Scene& scene)
    : model(build_model(scene)), world(make_world(model)), state(initial_state(model)) {
  init_workspace(world, ws);
  measure_state(world, inputs, state, ws, stats);
  if (!model.liquids.empty()) {
    stages::remove_covered_liquid(model, state, ws);
    measure_state(world, inputs, state, ws, stats);
  }
}

FrameResult advance_frame(Simulation& sim) {
  return advance_frame(sim.world, sim.inputs, sim.state, sim.ws, sim.stats);
}

}  // namespace pbm
