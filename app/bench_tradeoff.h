// `pbm bench tradeoff <scene> [--knobs dt,integrator,tolerance,resolution]`: the measured trade
// of speed for accuracy (engine/sim/tradeoff.h) written as CSV and a PNG plot of error against
// wall time, the Pareto front drawn through it and the scene's own setting ringed.
#pragma once

#include <string>

namespace pbm {

struct TradeoffCommandOptions {
  std::string scene;
  std::string knobs = "dt,integrator,resolution";
  double seconds = 2;
  double reference_tolerance = 1e-7;
  std::string out = "out";  // folder of <scene name>-tradeoff.csv and .png
};

int run_bench_tradeoff(const TradeoffCommandOptions& options);

}  // namespace pbm
