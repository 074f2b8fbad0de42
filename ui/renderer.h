// The renderer shared by the studio viewport and the headless path: draws a draw::Snapshot from a
// Camera with OpenGL 3.3 core through a loaded function table (gl_functions.h), into its own
// (multisampled) framebuffer. Key light with a shadow map, fill light, sky ambient, tone mapping,
// a background gradient. Every drawable kind has one generic path, so a subsystem that adds
// drawables needs no renderer change (docs/architecture.md, "Snapshot"):
//   meshes       smooth (normals recomputed every frame) or flat; what the renderer uploads for a
//                shared topology or a flat mesh's shared positions is kept while they live
//   planes       finite gridded quads, shaded per pixel only where shadows can fall
//   primitives   one unit shape per kind, tessellated once, placed per instance by uniforms
//   height fields, lines (maybe with a dot at each end), points
//   field sections  flat false-colour cells, and each one's colour bar over the picture (its
//                label and range in a bitmap font, colour_bar.h)
// The scene layer always; the overlay layer (springs, constraints, the meshes' element edges)
// only with RenderOptions::overlays. Scene-layer solids cast shadows.
#pragma once

#include <memory>
#include <vector>

#include "camera.h"
#include "draw/snapshot.h"
#include "gl_functions.h"

namespace pbm {

struct RenderOptions {
  int width = 1280, height = 720;
  int samples = 4;  // MSAA samples asked for (1 = none); clamped to what the context offers
  bool shadows = true;
  bool overlays = false;  // draw the overlay layer (draw::Layer::overlay) and the wireframe
};

struct RenderTimes {
  double upload = 0;  // [s] normals, vertex and index uploads of the last frame
  double draw = 0;    // [s] every pass of the last frame, to a finished image
};

class Renderer {
 public:
  // Compiles the embedded shaders; throws std::runtime_error with the GL info log on failure.
  // The context must stay current while the renderer lives.
  explicit Renderer(const gl::Functions& gl);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void render(const draw::Snapshot& snapshot, const Camera& camera, const RenderOptions& options);
  // The same scene-layer triangles (same framebuffer and samples) with a flat-colour shader and
  // nothing else: the rasterizer's own cost, against which `pbm bench render` measures ours.
  void render_bare(const draw::Snapshot& snapshot, const Camera& camera,
                   const RenderOptions& options);
  // Copies the last image into `framebuffer` (a window's, e.g. QOpenGLWidget's) at its origin.
  void present(GLuint framebuffer) const;
  // The last image, rows top to bottom, 8-bit RGB.
  void read_rgb(std::vector<unsigned char>& rgb) const;

  const RenderTimes& times() const;
  int samples() const;  // MSAA samples in use

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pbm
