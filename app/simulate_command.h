// `pbm validate` and `pbm simulate`: scene in, simulated frames out (issue: foundation).
#pragma once

#include <optional>
#include <string>

namespace pbm {

struct SimulateOptions {
  std::string scene;
  std::optional<double> seconds;
  std::optional<long> frames;
  std::optional<double> dt;
  std::optional<std::string> integrator;
  std::optional<double> tolerance;
  std::string states_out;  // states.jsonl, empty = none
  std::string stats_out;   // stats.json, empty = none
  std::string mesh_dir;    // empty = none
  std::string mesh_format = "obj";
};

// Exit codes: 0 ok, 1 simulation failed, 2 bad input (docs/architecture.md, "Errors and exit
// codes").
// With `materials`, each body's compiled material is printed: what converting a book scene's
// per-node numbers to mesh-independent ones needs (scenes/README.md, "Materials that converge").
int run_validate(const std::string& scene_path, bool materials = false);
int run_simulate(const SimulateOptions& options);

}  // namespace pbm
