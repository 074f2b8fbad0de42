// Stepping a Simulation one substep at a time with an observer on every stage hook, for the tests
// that catch the state just before and just after one stage (an impact, a collision).
#pragma once

#include <functional>

#include "sim/simulation.h"

namespace pbm::test {

// Steps sim by solver.dt, `observer` watching every hook, until done() holds after a substep
// (true) or max_substeps have run or a substep failed (false).
inline bool step_until(Simulation& sim, const StageObserver& observer,
                       const std::function<bool()>& done, int max_substeps) {
  int evaluations = 0;
  for (int step = 0; step < max_substeps; ++step) {
    if (!advance_substep(sim.world, sim.inputs, sim.state, sim.model.solver.dt, sim.ws, evaluations,
                         &observer)) {
      return false;
    }
    if (done()) return true;
  }
  return false;
}

}  // namespace pbm::test
