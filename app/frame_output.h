// What `pbm simulate` writes per frame: states (JSON lines, bit-exact doubles), statistics
// (stats.json) and the deformed surface of every body (mesh sequence).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "sim/world.h"

namespace pbm {

// One JSON object per line: {"frame":k,"time":t,"bodies":[{"name":..,"q":[..],"v":[..]}]}.
// Doubles are printed with 17 significant digits, so equal states give equal bytes.
std::string state_json_line(const Model& model, const State& state, long frame);

// stats.json: per frame time, wall time, substeps, energies, minimum obstacle distance, every
// stage's and every present subsystem's time, and each body's q_s.
std::string frame_stats_json(const World& world, const FrameStats& stats, long frame);

}  // namespace pbm
