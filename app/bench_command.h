// `pbm bench deform`: µs per step of our jello-ball against Bullet's btSoftBody ellipsoid with
// the same node count and dt, measured side by side in one run (machines here are noisy).
#pragma once

#include <string>

namespace pbm {

struct BenchOptions {
  std::string what;
  int steps = 40;
  int max_nodes = 16386;
  int max_constraints = 1000;  // `pbm bench constraints`: largest k
  std::string scene = "scenes/jello-ball.json";
};

int run_bench(const BenchOptions& options);

}  // namespace pbm
