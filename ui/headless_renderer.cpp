#include "headless_renderer.h"

#include <spdlog/spdlog.h>

namespace pbm {

std::unique_ptr<HeadlessRenderer> open_headless_renderer() {
  try {
    return std::make_unique<HeadlessRenderer>();
  } catch (const std::exception& e) {
    spdlog::error("headless OpenGL: {}", e.what());
    return nullptr;
  }
}

}  // namespace pbm
