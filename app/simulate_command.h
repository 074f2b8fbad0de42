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
  // Each liquid's level set per frame as liquid_<name>_NNNNN.vdb (engine/liquid/
  // liquid_surface_mesh.h); empty = none.
  std::string vdb_dir;
  // The level set's voxel as a fraction of a liquid cell (0: the markers' half spacing) and its
  // smoothing passes, for --mesh-dir and --vdb-dir.
  double surface_voxel = 0;
  int surface_smoothing = 2;
};

// Exit codes: 0 ok, 1 simulation failed, 2 bad input (docs/architecture.md, "Errors and exit
// codes").
// With `materials`, each body's compiled material is printed: what converting a book scene's
// per-node numbers to mesh-independent ones needs (scenes/README.md, "Materials that converge").
int run_validate(const std::string& scene_path, bool materials = false);
int run_simulate(const SimulateOptions& options);

}  // namespace pbm
