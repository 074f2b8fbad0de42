// The renderer on its own OSMesa context: what the command line and the tests draw with.
#pragma once

#include <memory>

#include "osmesa_context.h"
#include "renderer.h"

namespace pbm {

struct HeadlessRenderer {
  OsmesaContext context;  // first: the renderer needs it current
  Renderer renderer{context.functions()};
};

// A headless renderer, or nullptr after logging why there is none (no core profile, a GL below
// 3.3, a shader that does not compile).
std::unique_ptr<HeadlessRenderer> open_headless_renderer();

}  // namespace pbm
