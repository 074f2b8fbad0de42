// The renderer's framebuffers: the image (multisampled when asked, resolved into a single-sample
// one that present() and read_rgb() read) and the key light's shadow map.
#pragma once

#include "gl_functions.h"

namespace pbm {

inline constexpr int kShadowMapSize = 1024;  // texels a side

struct RenderTargets {
  explicit RenderTargets(const gl::Functions& functions) : gl(functions) {}
  ~RenderTargets();
  RenderTargets(const RenderTargets&) = delete;
  RenderTargets& operator=(const RenderTargets&) = delete;

  // (Re)creates the image framebuffers when the size or the sample count changes; `samples` is
  // clamped to what the context offers. Throws std::runtime_error if one is incomplete.
  void ensure_image(int width, int height, int samples);
  // Creates the shadow map on first use: a depth texture compared in the sampler.
  void ensure_shadow_map();
  GLuint draw_target() const { return samples_in_use > 1 ? msaa_fbo : resolve_fbo; }
  // The multisampled image into the resolved one (nothing to do without MSAA).
  void resolve() const;

  const gl::Functions& gl;
  int width = 0, height = 0, samples_in_use = 0;
  GLuint msaa_fbo = 0, msaa_color = 0, msaa_depth = 0;
  GLuint resolve_fbo = 0, resolve_color = 0, resolve_depth = 0;
  GLuint shadow_fbo = 0, shadow_texture = 0;

 private:
  void release_image();
  void check_framebuffer(const char* what) const;
};

}  // namespace pbm
