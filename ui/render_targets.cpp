#include "render_targets.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pbm {

RenderTargets::~RenderTargets() {
  release_image();
  if (shadow_fbo) gl.DeleteFramebuffers(1, &shadow_fbo);
  if (shadow_texture) gl.DeleteTextures(1, &shadow_texture);
}

void RenderTargets::ensure_image(int w, int h, int asked_samples) {
  GLint max_samples = 1;
  gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
  const int samples = std::clamp(asked_samples, 1, std::max(1, static_cast<int>(max_samples)));
  if (w == width && h == height && samples == samples_in_use) return;
  release_image();
  width = w;
  height = h;
  samples_in_use = samples;
  gl.GenFramebuffers(1, &resolve_fbo);
  gl.GenRenderbuffers(1, &resolve_color);
  gl.GenRenderbuffers(1, &resolve_depth);
  gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
  gl.BindRenderbuffer(GL_RENDERBUFFER, resolve_color);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color);
  gl.BindRenderbuffer(GL_RENDERBUFFER, resolve_depth);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, resolve_depth);
  check_framebuffer("image");
  if (samples > 1) {
    gl.GenFramebuffers(1, &msaa_fbo);
    gl.GenRenderbuffers(1, &msaa_color);
    gl.GenRenderbuffers(1, &msaa_depth);
    gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaa_color);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color);
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaa_depth);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width,
                                      height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth);
    check_framebuffer("multisampled image");
  }
}

void RenderTargets::release_image() {
  for (GLuint* fbo : {&msaa_fbo, &resolve_fbo}) {
    if (*fbo) gl.DeleteFramebuffers(1, fbo);
    *fbo = 0;
  }
  for (GLuint* rb : {&msaa_color, &msaa_depth, &resolve_color, &resolve_depth}) {
    if (*rb) gl.DeleteRenderbuffers(1, rb);
    *rb = 0;
  }
}

void RenderTargets::check_framebuffer(const char* what) const {
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(std::string("the ") + what + " framebuffer is incomplete (size " +
                             std::to_string(width) + "x" + std::to_string(height) + ")");
  }
}

void RenderTargets::resolve() const {
  if (samples_in_use <= 1) return;
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo);
  gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void RenderTargets::ensure_shadow_map() {
  if (shadow_fbo) return;
  gl.GenTextures(1, &shadow_texture);
  gl.BindTexture(GL_TEXTURE_2D, shadow_texture);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize, 0,
                GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  // Depth comparison in the sampler with linear filtering: each fetch is a 2x2 PCF.
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.GenFramebuffers(1, &shadow_fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture, 0);
  gl.DrawBuffer(GL_NONE);
  gl.ReadBuffer(GL_NONE);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("the shadow map framebuffer is incomplete");
  }
}

}  // namespace pbm
