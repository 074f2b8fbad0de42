#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <Eigen/Geometry>

#include "drawable_buffers.h"
#include "drawable_geometry.h"
#include "render_targets.h"
#include "shader_program.h"

namespace pbm {
namespace {

using Clock = std::chrono::steady_clock;
using Vec3f = Eigen::Vector3f;
using Mat3f = Eigen::Matrix3f;
using Mat4f = Eigen::Matrix4f;

const Vec3f kKeyDirection = Vec3f(0.45f, -0.35f, 0.82f).normalized();  // towards the key light
const Vec3f kFillDirection = Vec3f(-0.7f, 0.4f, 0.3f).normalized();
const Vec3f kWireColor(0.08f, 0.08f, 0.1f);
const Vec3f kGroundAlbedo(0.62f, 0.60f, 0.56f);

}  // namespace

struct Renderer::Impl {
  const gl::Functions& gl;
  RenderTargets targets{gl};
  GLuint shadow = 0, bare = 0, surface = 0, ground = 0, line = 0, colored = 0, sky = 0;
  GLuint empty_vao = 0;  // the sky's triangle comes from gl_VertexID
  DrawableBuffers buffers{gl};
  RenderTimes times;

  explicit Impl(const gl::Functions& functions) : gl(functions) {}

  GLint uniform(GLuint program, const char* name) const {
    return gl.GetUniformLocation(program, name);
  }
  void set(GLuint p, const char* name, const Mat4f& m) const {
    gl.UniformMatrix4fv(uniform(p, name), 1, GL_FALSE, m.data());
  }
  void set(GLuint p, const char* name, const Mat3f& m) const {
    gl.UniformMatrix3fv(uniform(p, name), 1, GL_FALSE, m.data());
  }
  void set(GLuint p, const char* name, const Vec3f& v) const {
    gl.Uniform3f(uniform(p, name), v.x(), v.y(), v.z());
  }
  void set(GLuint p, const char* name, float x) const { gl.Uniform1f(uniform(p, name), x); }
  void set(GLuint p, const char* name, int x) const { gl.Uniform1i(uniform(p, name), x); }
  void place(GLuint p, const Solid& s) const {
    set(p, "u_rotation", s.rotation);
    set(p, "u_offset", s.offset);
    set(p, "u_scale", s.scale);
    set(p, "u_stretch", s.stretch);
  }

  // A solid's triangles with the bound program, or the shadow pass's copy of them.
  void draw_elements_or_arrays(const Solid& s, GLuint elements, GLsizei count) const {
    gl.BindVertexArray(s.vao);
    if (elements) {
      gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, elements);
      gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
    } else {
      gl.DrawArrays(GL_TRIANGLES, s.first, count);
    }
  }
  void draw_triangles(const Solid& s) const { draw_elements_or_arrays(s, s.triangles, s.count); }
  void draw_shadow_casters(const Solid& s) const {
    draw_elements_or_arrays(s, s.casters, s.caster_count);
  }

  // Where shadows can fall: a sphere around the casters (centre, reach) that the key light's
  // orthographic frustum covers.
  Mat4f light_view_proj() const {
    const draw::Bounds& casters = buffers.casters;
    const Vec3f centre =
        casters.empty() ? Vec3f::Zero() : Vec3f(0.5f * (casters.min + casters.max));
    const float radius =
        casters.empty() ? 10.0f : std::max(0.5f * (casters.max - casters.min).norm(), 0.5f);
    const float reach = 3.0f * radius;
    Camera light;
    light.target = centre;
    light.position = centre + 4.0f * reach * kKeyDirection;
    light.up = std::abs(kKeyDirection.z()) > 0.99f ? Vec3f::UnitY() : Vec3f::UnitZ();
    return orthographic_matrix(-reach, reach, -reach, reach, 0.1f, 8.0f * reach) *
           view_matrix(light);
  }

  void shadow_pass(const Mat4f& light) const {
    gl.BindFramebuffer(GL_FRAMEBUFFER, targets.shadow_fbo);
    gl.Viewport(0, 0, kShadowMapSize, kShadowMapSize);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(2.0f, 4.0f);
    gl.UseProgram(shadow);
    set(shadow, "u_view_proj", light);
    // Meshes, primitives and height fields cast; planes only receive.
    for (const Solid& s : buffers.solids) {
      if (s.layer != draw::Layer::scene || s.material.opacity < 1) continue;
      place(shadow, s);
      draw_shadow_casters(s);
    }
    gl.Disable(GL_POLYGON_OFFSET_FILL);
  }

  void use_surface(const Mat4f& view_proj, const Mat4f& light, const Camera& camera,
                   bool shadows) const {
    gl.UseProgram(surface);
    set(surface, "u_view_proj", view_proj);
    set(surface, "u_light_view_proj", light);
    set(surface, "u_camera", camera.position);
    set(surface, "u_key_direction", kKeyDirection);
    set(surface, "u_fill_direction", kFillDirection);
    set(surface, "u_shadows", shadows ? 1 : 0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, targets.shadow_texture);
    set(surface, "u_shadow_map", 0);
  }
  void draw_lit(const Solid& s) const {
    set(surface, "u_base_color", s.material.color);
    set(surface, "u_roughness", s.material.roughness);
    set(surface, "u_opacity", s.material.opacity);
    place(surface, s);
    draw_triangles(s);
  }

  void draw_planes(const draw::Snapshot& s, const Mat4f& view_proj, const Mat4f& light,
                   const Camera& camera, bool shadows) const;
  void draw_overlay(const Mat4f& view_proj, const Mat4f& light, const Camera& camera,
                    bool shadows) const;
  void draw_colored(const Mat4f& view_proj, draw::Layer layer) const;
  void draw_screen(int width, int height) const;
};

// Planes cover most of the image, and on a software rasterizer their fill is the cost. Their
// lighting is constant (the normal is), so most of each is one flat colour (tone mapped here,
// as the shaders do), its grid lines, and only the patch where shadows can fall is shaded per
// pixel by ground.frag (LEQUAL, in front of the base by its polygon offset).
void Renderer::Impl::draw_planes(const draw::Snapshot& s, const Mat4f& view_proj,
                                 const Mat4f& light, const Camera& camera, bool shadows) const {
  auto tone_map = [](const Vec3f& c) { return Vec3f((c.array() / (1.0f + c.array())).sqrt()); };
  for (std::size_t k = 0; k < s.planes.size(); ++k) {
    const draw::Plane& plane = s.planes[k];
    const PlaneParts& parts = buffers.planes[k];
    // The camera sees a plane from its normal's side or through it; light it from that side.
    const Vec3f n = (camera.position - plane.point).dot(plane.normal) >= 0 ? plane.normal
                                                                           : Vec3f(-plane.normal);
    const float key = std::max(n.dot(kKeyDirection), 0.0f);
    const float fill = std::max(n.dot(kFillDirection), 0.0f);
    const float sky_term = 0.5f + 0.5f * n.z();
    const Vec3f shade = Vec3f(0.55f, 0.65f, 0.8f) * 0.45f * fill +
                        Vec3f(0.10f, 0.09f, 0.08f) * (1 - sky_term) +
                        Vec3f(0.22f, 0.25f, 0.30f) * sky_term;
    const Vec3f lit = Vec3f(1.0f, 0.96f, 0.9f) * 2.2f * key;
    const Vec3f light_sum = shade + lit;
    gl.BindVertexArray(buffers.planes_vao());
    gl.UseProgram(line);
    set(line, "u_view_proj", view_proj);
    set(line, "u_point_size", 1.0f);
    set(line, "u_color", tone_map(kGroundAlbedo.cwiseProduct(light_sum)));
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(1.0f, 1.0f);
    gl.DrawArrays(GL_TRIANGLES, parts.quad_first, parts.quad_count);
    gl.DepthFunc(GL_LEQUAL);
    set(line, "u_color", tone_map(Vec3f(0.55f * kGroundAlbedo.cwiseProduct(light_sum))));
    gl.DrawArrays(GL_LINES, parts.grid_first, parts.grid_count);
    if (shadows && parts.patch_count > 0) {
      // Not pushed back like the base: its corners differ, so at equal offsets the two
      // interpolated depths would fight.
      gl.Disable(GL_POLYGON_OFFSET_FILL);
      gl.UseProgram(ground);
      set(ground, "u_view_proj", view_proj);
      set(ground, "u_light_view_proj", light);
      set(ground, "u_shadows", 1);
      set(ground, "u_shadow_map", 0);
      set(ground, "u_base_color", kGroundAlbedo);
      set(ground, "u_lit", lit);
      set(ground, "u_shade", shade);
      set(ground, "u_bias", 0.002f + 0.006f * (1.0f - key));
      const Vec3f u = plane_axis(plane.normal);
      set(ground, "u_grid_origin", plane.point);
      set(ground, "u_grid_u", u);
      set(ground, "u_grid_v", Vec3f(plane.normal.cross(u)));
      gl.DrawArrays(GL_TRIANGLES, parts.patch_first, parts.patch_count);
    }
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
  }
}

// What is drawn over the picture in pixels (the field sections' colour bars), from the image's
// top-right corner: x' = 1 + 2 x / width, y' = 1 - 2 y / height.
void Renderer::Impl::draw_screen(int width, int height) const {
  bool any = false;
  for (const ColoredRange& r : buffers.colored) any = any || r.screen;
  if (!any) return;
  Mat4f pixels = Mat4f::Identity();
  pixels(0, 0) = 2.0f / static_cast<float>(width);
  pixels(0, 3) = 1;
  pixels(1, 1) = -2.0f / static_cast<float>(height);
  pixels(1, 3) = 1;
  gl.Disable(GL_DEPTH_TEST);
  gl.UseProgram(colored);
  set(colored, "u_view_proj", pixels);
  set(colored, "u_point_size", 1.0f);
  gl.BindVertexArray(buffers.colored_vao());
  for (const ColoredRange& r : buffers.colored) {
    if (r.screen) gl.DrawArrays(GL_TRIANGLES, r.first, r.count);
  }
  gl.Enable(GL_DEPTH_TEST);
}

// Lines and points of one layer: the scene's hidden by what is in front, the overlay's over
// everything (a constraint between parts is seen through them).
void Renderer::Impl::draw_colored(const Mat4f& view_proj, draw::Layer layer) const {
  const bool over = layer == draw::Layer::overlay;
  if (over) gl.Disable(GL_DEPTH_TEST);
  gl.Enable(GL_PROGRAM_POINT_SIZE);
  gl.UseProgram(colored);
  set(colored, "u_view_proj", view_proj);
  gl.BindVertexArray(buffers.colored_vao());
  for (const ColoredRange& r : buffers.colored) {
    if (r.layer != layer || r.screen) continue;
    if (r.triangles) {
      gl.DrawArrays(GL_TRIANGLES, r.first, r.count);
      continue;
    }
    if (r.lines) {
      set(colored, "u_point_size", 1.0f);
      gl.DrawArrays(GL_LINES, r.first, r.count);
      if (!r.end_points) continue;
    }
    set(colored, "u_point_size", r.point_size);
    gl.DrawArrays(GL_POINTS, r.first, r.count);
  }
  gl.Disable(GL_PROGRAM_POINT_SIZE);
  if (over) gl.Enable(GL_DEPTH_TEST);
}

// The editor's layer: the meshes' element edges (depth tested against the fills, which the
// scene pass pushed back), overlay solids, then overlay lines and points over everything.
void Renderer::Impl::draw_overlay(const Mat4f& view_proj, const Mat4f& light, const Camera& camera,
                                  bool shadows) const {
  gl.UseProgram(line);
  set(line, "u_point_size", 1.0f);
  set(line, "u_color", kWireColor);
  for (const Solid& s : buffers.solids) {
    if (s.edge_count == 0) continue;
    Mat4f model = Mat4f::Identity();
    model.topLeftCorner<3, 3>() = s.rotation;
    model.topRightCorner<3, 1>() = s.offset;
    set(line, "u_view_proj", Mat4f(view_proj * model));
    gl.BindVertexArray(s.vao);
    if (s.edges) {
      gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.edges);
      gl.DrawElements(GL_LINES, s.edge_count, GL_UNSIGNED_INT, nullptr);
    } else {
      gl.DrawArrays(GL_LINES, s.edge_first, s.edge_count);
    }
  }
  use_surface(view_proj, light, camera, shadows);
  for (const Solid& s : buffers.solids) {
    if (s.layer == draw::Layer::overlay) draw_lit(s);
  }
  draw_colored(view_proj, draw::Layer::overlay);
}

Renderer::Renderer(const gl::Functions& gl) : impl_(std::make_unique<Impl>(gl)) {
  Impl& r = *impl_;
  r.shadow = link_program(gl, "shadow");
  r.bare = link_program(gl, "shadow", "line");
  r.surface = link_program(gl, "surface");
  r.ground = link_program(gl, "ground");
  r.line = link_program(gl, "line");
  r.colored = link_program(gl, "colored");
  r.sky = link_program(gl, "sky");
  gl.GenVertexArrays(1, &r.empty_vao);
}

Renderer::~Renderer() {
  Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  for (GLuint p : {r.shadow, r.bare, r.surface, r.ground, r.line, r.colored, r.sky}) {
    gl.DeleteProgram(p);
  }
  gl.DeleteVertexArrays(1, &r.empty_vao);
}

void Renderer::render(const draw::Snapshot& s, const Camera& camera, const RenderOptions& o) {
  Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  r.targets.ensure_image(o.width, o.height, o.samples);
  r.targets.ensure_shadow_map();
  auto t0 = Clock::now();
  r.buffers.upload(s, kKeyDirection);
  r.times.upload = std::chrono::duration<double>(Clock::now() - t0).count();
  t0 = Clock::now();

  const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  const Mat4f view_proj =
      perspective_matrix(camera.fov, aspect, 0.05f, 500.0f) * view_matrix(camera);
  const Mat4f light = r.light_view_proj();

  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.DepthMask(GL_TRUE);
  gl.Disable(GL_CULL_FACE);
  if (o.shadows) r.shadow_pass(light);

  gl.BindFramebuffer(GL_FRAMEBUFFER, r.targets.draw_target());
  gl.Viewport(0, 0, o.width, o.height);
  // One full clear: on llvmpipe it is a per-tile flag, where scissored clears (the old banded
  // sky) cost half a bare frame. The sky is drawn last, behind everything.
  gl.ClearColor(0, 0, 0, 1);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  r.use_surface(view_proj, light, camera, o.shadows);
  // Solids before planes: the planes behind them then fail the depth test before shading. With
  // overlays, fills with element edges are pushed back so that their edges pass the depth test.
  for (const Solid& solid : r.buffers.solids) {
    if (solid.layer != draw::Layer::scene || solid.material.opacity < 1) continue;
    const bool wired = o.overlays && solid.edge_count > 0;
    if (wired) {
      gl.Enable(GL_POLYGON_OFFSET_FILL);
      gl.PolygonOffset(1.0f, 1.0f);
    }
    r.draw_lit(solid);
    if (wired) gl.Disable(GL_POLYGON_OFFSET_FILL);
  }
  r.draw_planes(s, view_proj, light, camera, o.shadows);
  r.draw_colored(view_proj, draw::Layer::scene);

  // The sky gradient at the far plane: the depth test passes only where nothing was drawn.
  gl.DepthFunc(GL_LEQUAL);
  gl.DepthMask(GL_FALSE);
  gl.UseProgram(r.sky);
  r.set(r.sky, "u_bottom", Vec3f(0.78f, 0.80f, 0.83f));
  r.set(r.sky, "u_top", Vec3f(0.36f, 0.45f, 0.58f));
  gl.BindVertexArray(r.empty_vao);
  gl.DrawArrays(GL_TRIANGLES, 0, 3);
  gl.DepthMask(GL_TRUE);
  gl.DepthFunc(GL_LESS);

  // Translucent solids over the opaque picture, depth-tested against it but not writing depth,
  // so a surface's far side shows through its near side. Unsorted: where two translucent layers
  // overlap, their order changes the blend a little.
  bool translucent = false;
  for (const Solid& solid : r.buffers.solids) {
    if (solid.layer != draw::Layer::scene || !(solid.material.opacity < 1)) continue;
    if (!translucent) {
      r.use_surface(view_proj, light, camera, o.shadows);
      gl.Enable(GL_BLEND);
      // The picture's alpha stays 1: the studio's window composes its framebuffer by it (as
      // premultiplied colour), so a blended alpha below 1 showed as false colours there.
      gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      gl.DepthMask(GL_FALSE);
      translucent = true;
    }
    r.draw_lit(solid);
  }
  if (translucent) {
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_BLEND);
  }

  if (o.overlays) r.draw_overlay(view_proj, light, camera, o.shadows);
  r.draw_screen(o.width, o.height);
  gl.BindVertexArray(0);
  r.targets.resolve();
  gl.Finish();
  r.times.draw = std::chrono::duration<double>(Clock::now() - t0).count();
}

void Renderer::render_bare(const draw::Snapshot& s, const Camera& camera, const RenderOptions& o) {
  Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  r.targets.ensure_image(o.width, o.height, o.samples);
  r.buffers.upload(s, kKeyDirection);
  const auto t0 = Clock::now();
  const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  gl.BindFramebuffer(GL_FRAMEBUFFER, r.targets.draw_target());
  gl.Viewport(0, 0, o.width, o.height);
  gl.Enable(GL_DEPTH_TEST);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.UseProgram(r.bare);
  r.set(r.bare, "u_view_proj",
        Mat4f(perspective_matrix(camera.fov, aspect, 0.05f, 500.0f) * view_matrix(camera)));
  r.set(r.bare, "u_color", Vec3f(0.8f, 0.3f, 0.3f));
  for (const Solid& solid : r.buffers.solids) {
    if (solid.layer != draw::Layer::scene) continue;
    r.place(r.bare, solid);
    r.draw_triangles(solid);
  }
  r.place(r.bare, Solid{});
  gl.BindVertexArray(r.buffers.planes_vao());
  for (const PlaneParts& parts : r.buffers.planes) {
    gl.DrawArrays(GL_TRIANGLES, parts.quad_first, parts.quad_count);
  }
  gl.BindVertexArray(0);
  r.targets.resolve();
  gl.Finish();
  r.times.draw = std::chrono::duration<double>(Clock::now() - t0).count();
}

void Renderer::present(GLuint framebuffer) const {
  const Impl& r = *impl_;
  const RenderTargets& t = r.targets;
  r.gl.BindFramebuffer(GL_READ_FRAMEBUFFER, t.resolve_fbo);
  r.gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  r.gl.BlitFramebuffer(0, 0, t.width, t.height, 0, 0, t.width, t.height, GL_COLOR_BUFFER_BIT,
                       GL_NEAREST);
  r.gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

void Renderer::read_rgb(std::vector<unsigned char>& rgb) const {
  const Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  const int width = r.targets.width, height = r.targets.height;
  std::vector<unsigned char> rgba(4 * static_cast<std::size_t>(width) * height);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r.targets.resolve_fbo);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  rgb.resize(3 * static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    const unsigned char* src = rgba.data() + 4 * static_cast<std::size_t>(height - 1 - y) * width;
    unsigned char* dst = rgb.data() + 3 * static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x) {
      dst[3 * x] = src[4 * x];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
}

const RenderTimes& Renderer::times() const {
  return impl_->times;
}
int Renderer::samples() const {
  return impl_->targets.samples_in_use;
}

}  // namespace pbm
