// `pbm render`: simulates a scene and writes its frames as PNG files through the headless
// renderer (OSMesa), optionally encoded to a video by the ffmpeg program.
#pragma once

#include <optional>
#include <string>

namespace pbm {

struct RenderCommandOptions {
  std::string scene;
  std::string frames;             // "A:B", inclusive; empty = every frame of the scene
  std::optional<double> seconds;  // frames 0 .. T * fps
  std::string size = "1280x720";  // WxH
  std::string out = "out";        // folder for frame_NNNN.png
  std::string video;              // encode to this file with ffmpeg
  int samples = 4;                // MSAA
  bool overlays = false;          // springs, constraints, the finite elements' wireframe
};

int run_render(const RenderCommandOptions& options);

}  // namespace pbm
