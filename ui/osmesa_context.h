// A headless OpenGL core context on OSMesa (llvmpipe): no X server, no GPU. The renderer draws
// into its own framebuffers, so the context's buffer is only a token.
#pragma once

#include <memory>
#include <vector>

#include "gl_functions.h"

namespace pbm {

class OsmesaContext {
 public:
  // Creates a 3.3 core context and makes it current; throws std::runtime_error with what is
  // missing (OSMesa without core profiles, a version below 3.3).
  OsmesaContext();
  ~OsmesaContext();
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  const gl::Functions& functions() const { return gl_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  gl::Functions gl_;
};

}  // namespace pbm
