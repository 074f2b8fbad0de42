// `pbm bench render`: ms per 1280x720 frame of a scene's first body at about 2k and 16k nodes,
// split into simulation, upload and draw, and in the same run a bare draw of the same triangles
// with a flat-colour shader (our overhead over the rasterizer).
#pragma once

#include <string>

namespace pbm {

int run_bench_render(const std::string& scene_path, int frames);

}  // namespace pbm
