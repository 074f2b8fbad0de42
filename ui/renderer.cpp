#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "embedded_shaders.h"
#include "shader_program.h"
#include "shadow_casters.h"

namespace pbm {
namespace {

using Clock = std::chrono::steady_clock;
using Vec3f = Eigen::Vector3f;
using Mat4f = Eigen::Matrix4f;

constexpr int kShadowSize = 1024;
// A 1024² map resolves about this many triangles of one body; more only cost time
// (shadow_casters.h).
constexpr std::size_t kMaxShadowCasterTriangles = 4096;
constexpr float kConstraintRedViolation = 0.01f;                       // [m]
const Vec3f kKeyDirection = Vec3f(0.45f, -0.35f, 0.82f).normalized();  // towards the key light
const Vec3f kFillDirection = Vec3f(-0.7f, 0.4f, 0.3f).normalized();

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// One vertex array with an interleaved (position, normal) buffer and two index buffers.
struct Mesh {
  GLuint vao = 0, vbo = 0, triangles = 0, edges = 0, casters = 0;
  GLsizei triangle_count = 0, edge_count = 0, caster_count = 0;
  std::size_t vertex_capacity = 0;
};

// A unit vector perpendicular to n, chosen the same way every time.
Vec3f perpendicular(const Vec3f& n) {
  const Vec3f axis = std::abs(n.y()) < 0.9f ? Vec3f::UnitY() : Vec3f::UnitX();
  return n.cross(axis).normalized();
}

}  // namespace

struct Renderer::Impl {
  const gl::Functions& gl;
  GLuint shadow = 0, surface = 0, ground = 0, line = 0, sky = 0;
  GLuint empty_vao = 0;  // the sky's triangle comes from gl_VertexID
  std::vector<Mesh> bodies;
  Mesh scratch;  // obstacles and springs, rebuilt each frame
  GLuint shadow_fbo = 0, shadow_texture = 0;
  GLuint msaa_fbo = 0, msaa_color = 0, msaa_depth = 0;
  GLuint resolve_fbo = 0, resolve_color = 0, resolve_depth = 0;
  int width = 0, height = 0, samples_in_use = 0;
  RenderTimes times;
  std::vector<float> vertices;  // scratch for uploads
  // Per plane of the last upload (in obstacle order): its grid lines and its shadow patch.
  struct PlaneParts {
    GLint grid_first = 0, patch_first = 0;
    GLsizei grid_count = 0, patch_count = 0;
  };
  std::vector<PlaneParts> planes;

  explicit Impl(const gl::Functions& functions) : gl(functions) {}

  GLint uniform(GLuint program, const char* name) const {
    return gl.GetUniformLocation(program, name);
  }
  void set(GLuint p, const char* name, const Mat4f& m) const {
    gl.UniformMatrix4fv(uniform(p, name), 1, GL_FALSE, m.data());
  }
  void set(GLuint p, const char* name, const Vec3f& v) const {
    gl.Uniform3f(uniform(p, name), v.x(), v.y(), v.z());
  }
  void set(GLuint p, const char* name, float x) const { gl.Uniform1f(uniform(p, name), x); }
  void set(GLuint p, const char* name, int x) const { gl.Uniform1i(uniform(p, name), x); }

  void create_mesh(Mesh& m) {
    gl.GenVertexArrays(1, &m.vao);
    gl.GenBuffers(1, &m.vbo);
    gl.GenBuffers(1, &m.triangles);
    gl.GenBuffers(1, &m.edges);
    gl.GenBuffers(1, &m.casters);
    gl.BindVertexArray(m.vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                           reinterpret_cast<void*>(3 * sizeof(float)));
    gl.EnableVertexAttribArray(1);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.triangles);
    gl.BindVertexArray(0);
  }
  void delete_mesh(Mesh& m) {
    gl.DeleteBuffers(1, &m.vbo);
    gl.DeleteBuffers(1, &m.triangles);
    gl.DeleteBuffers(1, &m.edges);
    gl.DeleteBuffers(1, &m.casters);
    gl.DeleteVertexArrays(1, &m.vao);
    m = Mesh{};
  }
  // Positions and normals (6 floats a vertex) into m's vertex buffer.
  void upload_vertices(Mesh& m, const std::vector<float>& data) {
    gl.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
    const std::size_t bytes = data.size() * sizeof(float);
    if (bytes > m.vertex_capacity) {
      gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), data.data(), GL_STREAM_DRAW);
      m.vertex_capacity = bytes;
    } else {
      gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data.data());
    }
  }

  void ensure_targets(const RenderOptions& o) {
    GLint max_samples = 1;
    gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
    const int samples = std::clamp(o.samples, 1, std::max(1, static_cast<int>(max_samples)));
    if (o.width == width && o.height == height && samples == samples_in_use) return;
    release_targets();
    width = o.width;
    height = o.height;
    samples_in_use = samples;
    gl.GenFramebuffers(1, &resolve_fbo);
    gl.GenRenderbuffers(1, &resolve_color);
    gl.GenRenderbuffers(1, &resolve_depth);
    gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
    gl.BindRenderbuffer(GL_RENDERBUFFER, resolve_color);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                               resolve_color);
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
  void release_targets() {
    for (GLuint* fbo : {&msaa_fbo, &resolve_fbo}) {
      if (*fbo) gl.DeleteFramebuffers(1, fbo);
      *fbo = 0;
    }
    for (GLuint* rb : {&msaa_color, &msaa_depth, &resolve_color, &resolve_depth}) {
      if (*rb) gl.DeleteRenderbuffers(1, rb);
      *rb = 0;
    }
  }
  void check_framebuffer(const char* what) const {
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error(std::string("the ") + what + " framebuffer is incomplete (size " +
                               std::to_string(width) + "x" + std::to_string(height) + ")");
    }
  }
  GLuint draw_target() const { return samples_in_use > 1 ? msaa_fbo : resolve_fbo; }
  void resolve() const {
    if (samples_in_use <= 1) return;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo);
    gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }

  // Smooth normals (area-weighted face normals) and positions of every body into its mesh.
  void upload_bodies(const Snapshot& s) {
    while (bodies.size() > s.bodies.size()) {
      delete_mesh(bodies.back());
      bodies.pop_back();
    }
    while (bodies.size() < s.bodies.size()) {
      bodies.emplace_back();
      create_mesh(bodies.back());
    }
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
      const BodySnapshot& body = s.bodies[b];
      Mesh& m = bodies[b];
      const std::size_t n = body.positions.size();
      std::vector<Vec3f> normals(n, Vec3f::Zero());
      for (const std::array<int, 3>& t : body.triangles) {
        const Vec3f& a = body.positions[t[0]];
        const Vec3f face = (body.positions[t[1]] - a).cross(body.positions[t[2]] - a);
        for (int k = 0; k < 3; ++k) normals[t[k]] += face;
      }
      vertices.resize(6 * n);
      for (std::size_t i = 0; i < n; ++i) {
        const float len = normals[i].norm();
        const Vec3f normal = len > 0 ? Vec3f(normals[i] / len) : Vec3f::UnitZ();
        for (int k = 0; k < 3; ++k) {
          vertices[6 * i + k] = body.positions[i][k];
          vertices[6 * i + 3 + k] = normal[k];
        }
      }
      upload_vertices(m, vertices);
      const auto triangle_count = static_cast<GLsizei>(3 * body.triangles.size());
      const auto edge_count = static_cast<GLsizei>(2 * body.edges.size());
      if (triangle_count != m.triangle_count || edge_count != m.edge_count) {
        gl.BindVertexArray(m.vao);
        gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.triangles);
        gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, triangle_count * sizeof(int), body.triangles.data(),
                      GL_STATIC_DRAW);
        gl.BindVertexArray(0);
        // Through the array target: with no vertex array bound there is no element binding.
        gl.BindBuffer(GL_ARRAY_BUFFER, m.edges);
        gl.BufferData(GL_ARRAY_BUFFER, edge_count * sizeof(int), body.edges.data(), GL_STATIC_DRAW);
        const std::vector<std::array<int, 3>> casters =
            shadow_caster_triangles(body.positions, body.triangles, kMaxShadowCasterTriangles);
        m.caster_count = static_cast<GLsizei>(3 * casters.size());
        gl.BindBuffer(GL_ARRAY_BUFFER, m.casters);
        gl.BufferData(GL_ARRAY_BUFFER, m.caster_count * sizeof(int), casters.data(),
                      GL_STATIC_DRAW);
        m.triangle_count = triangle_count;
        m.edge_count = edge_count;
      }
    }
  }

  // Obstacles as triangles (planes: 2, boxes: 12, meshes: theirs) into the scratch mesh; first[k],
  // count[k] per obstacle. Then the springs' segments as plain positions after them.
  void upload_scene_geometry(const Snapshot& s, std::vector<GLint>& first,
                             std::vector<GLsizei>& count, GLint& springs_first) {
    vertices.clear();
    auto vertex = [&](const Vec3f& p, const Vec3f& n) {
      vertices.insert(vertices.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()});
    };
    first.clear();
    count.clear();
    planes.clear();
    for (const ObstacleSnapshot& o : s.obstacles) {
      if (o.kind == ObstacleKind::plane) {
        const Vec3f u = perpendicular(o.normal), v = o.normal.cross(u);
        auto rectangle = [&](float u0, float u1, float v0, float v1) {
          const Vec3f corners[4] = {o.point + u0 * u + v0 * v, o.point + u1 * u + v0 * v,
                                    o.point + u1 * u + v1 * v, o.point + u0 * u + v1 * v};
          for (int k : {0, 1, 2, 0, 2, 3}) vertex(corners[k], o.normal);
        };
        const float a = 0.5f * o.size.x(), b = 0.5f * o.size.y();
        rectangle(-a, a, -b, b);
        // The 1 m grid as lines, at whole plane coordinates.
        PlaneParts parts;
        parts.grid_first = static_cast<GLint>(vertices.size() / 6);
        for (float c = std::ceil(-a); c <= a; c += 1.0f) {
          vertex(o.point + c * u - b * v, o.normal);
          vertex(o.point + c * u + b * v, o.normal);
        }
        for (float c = std::ceil(-b); c <= b; c += 1.0f) {
          vertex(o.point - a * u + c * v, o.normal);
          vertex(o.point + a * u + c * v, o.normal);
        }
        parts.grid_count = static_cast<GLsizei>(vertices.size() / 6) - parts.grid_first;
        // The patch where shadows can fall: the bodies' bounding box cast along the key light
        // onto the plane, with a margin for the filter, clipped to the drawn plane.
        float u0 = a, u1 = -a, v0 = b, v1 = -b;
        const float along = kKeyDirection.dot(o.normal);
        if (!s.bodies.empty() && along > 0.05f) {
          const Vec3f lo = s.bodies_min(), hi = s.bodies_max();
          for (int corner = 0; corner < 8; ++corner) {
            const Vec3f x((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                          (corner & 4) ? hi.z() : lo.z());
            // Corners below the plane project too: the box is loose, the body inside may not be.
            const float above = (x - o.point).dot(o.normal);
            const Vec3f d = x - above / along * kKeyDirection - o.point;
            u0 = std::min(u0, d.dot(u));
            u1 = std::max(u1, d.dot(u));
            v0 = std::min(v0, d.dot(v));
            v1 = std::max(v1, d.dot(v));
          }
          const float margin = 0.5f;  // the filter's blur and the box's looseness
          u0 = std::max(-a, u0 - margin);
          u1 = std::min(a, u1 + margin);
          v0 = std::max(-b, v0 - margin);
          v1 = std::min(b, v1 + margin);
        }
        parts.patch_first = static_cast<GLint>(vertices.size() / 6);
        if (u0 < u1 && v0 < v1) rectangle(u0, u1, v0, v1);
        parts.patch_count = static_cast<GLsizei>(vertices.size() / 6) - parts.patch_first;
        planes.push_back(parts);
        first.push_back(parts.grid_first - 6);
        count.push_back(6);
        continue;
      }
      first.push_back(static_cast<GLint>(vertices.size() / 6));
      if (o.kind == ObstacleKind::mesh) {
        auto placed = [&o](int k) -> Vec3f {
          return o.mesh_rotation * o.mesh->vertices[k].cast<float>() + o.mesh_offset;
        };
        for (const std::array<int, 3>& t : o.mesh->triangles) {
          const Vec3f a = placed(t[0]);
          const Vec3f b = placed(t[1]);
          const Vec3f c = placed(t[2]);
          const Vec3f n = (b - a).cross(c - a).normalized();
          vertex(a, n);
          vertex(b, n);
          vertex(c, n);
        }
      } else {
        for (int axis = 0; axis < 3; ++axis) {
          for (float sign : {-1.0f, 1.0f}) {
            const Vec3f n_local = sign * Vec3f::Unit(axis);
            const Vec3f u_local = Vec3f::Unit((axis + 1) % 3), v_local = n_local.cross(u_local);
            const Vec3f n = o.rotation * n_local;
            auto corner = [&](float su, float sv) {
              const Vec3f local =
                  (n_local + su * u_local + sv * v_local).cwiseProduct(o.half_extents);
              return Vec3f(o.point + o.rotation * local);
            };
            const Vec3f c[4] = {corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)};
            for (int k : {0, 1, 2, 0, 2, 3}) vertex(c[k], n);
          }
        }
      }
      count.push_back(static_cast<GLsizei>(vertices.size() / 6) - first.back());
    }
    springs_first = static_cast<GLint>(vertices.size() / 6);
    for (const SpringSnapshot& spring : s.springs) {
      vertex(spring.from, Vec3f::UnitZ());
      vertex(spring.to, Vec3f::UnitZ());
    }
    for (const ConstraintSnapshot& c : s.constraints) {  // right after the springs
      vertex(c.a, Vec3f::UnitZ());
      vertex(c.b, Vec3f::UnitZ());
    }
    if (!vertices.empty()) upload_vertices(scratch, vertices);
  }

  // Where shadows can fall: a sphere around the bodies (centre, reach) that the key light's
  // orthographic frustum covers.
  static void shadow_region(const Snapshot& s, Vec3f& centre, float& reach) {
    const Vec3f lo = s.bodies_min(), hi = s.bodies_max();
    centre = s.bodies.empty() ? Vec3f::Zero() : Vec3f(0.5f * (lo + hi));
    const float radius = s.bodies.empty() ? 10.0f : std::max(0.5f * (hi - lo).norm(), 0.5f);
    reach = 3.0f * radius;
  }
  Mat4f light_view_proj(const Snapshot& s) const {
    Vec3f centre;
    float reach = 0;
    shadow_region(s, centre, reach);
    Camera light;
    light.target = centre;
    light.position = centre + 4.0f * reach * kKeyDirection;
    light.up = std::abs(kKeyDirection.z()) > 0.99f ? Vec3f::UnitY() : Vec3f::UnitZ();
    return orthographic_matrix(-reach, reach, -reach, reach, 0.1f, 8.0f * reach) *
           view_matrix(light);
  }

  void ensure_shadow_map() {
    if (shadow_fbo) return;
    gl.GenTextures(1, &shadow_texture);
    gl.BindTexture(GL_TEXTURE_2D, shadow_texture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowSize, kShadowSize, 0,
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
};

Renderer::Renderer(const gl::Functions& gl) : impl_(std::make_unique<Impl>(gl)) {
  Impl& r = *impl_;
  r.shadow = link_program(gl, "shadow");
  r.surface = link_program(gl, "surface");
  r.ground = link_program(gl, "ground");
  r.line = link_program(gl, "line");
  r.sky = link_program(gl, "sky");
  gl.GenVertexArrays(1, &r.empty_vao);
  r.create_mesh(r.scratch);
}

Renderer::~Renderer() {
  Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  for (Mesh& m : r.bodies) r.delete_mesh(m);
  r.delete_mesh(r.scratch);
  r.release_targets();
  if (r.shadow_fbo) gl.DeleteFramebuffers(1, &r.shadow_fbo);
  if (r.shadow_texture) gl.DeleteTextures(1, &r.shadow_texture);
  for (GLuint p : {r.shadow, r.surface, r.ground, r.line, r.sky}) gl.DeleteProgram(p);
  gl.DeleteVertexArrays(1, &r.empty_vao);
}

void Renderer::render(const Snapshot& s, const Camera& camera, const RenderOptions& o) {
  Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  r.ensure_targets(o);
  r.ensure_shadow_map();
  auto t0 = Clock::now();
  r.upload_bodies(s);
  std::vector<GLint> first;
  std::vector<GLsizei> count;
  GLint springs_first = 0;
  r.upload_scene_geometry(s, first, count, springs_first);
  r.times.upload = seconds_since(t0);
  t0 = Clock::now();

  const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  const Mat4f view_proj =
      perspective_matrix(camera.fov, aspect, 0.05f, 500.0f) * view_matrix(camera);
  const Mat4f light = r.light_view_proj(s);

  // Shadow pass: bodies, boxes and meshes cast; planes only receive.
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.DepthMask(GL_TRUE);
  gl.Disable(GL_CULL_FACE);
  if (o.shadows) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, r.shadow_fbo);
    gl.Viewport(0, 0, kShadowSize, kShadowSize);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(2.0f, 4.0f);
    gl.UseProgram(r.shadow);
    r.set(r.shadow, "u_light_view_proj", light);
    for (const Mesh& m : r.bodies) {
      gl.BindVertexArray(m.vao);
      gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.casters);
      gl.DrawElements(GL_TRIANGLES, m.caster_count, GL_UNSIGNED_INT, nullptr);
      gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.triangles);
    }
    gl.BindVertexArray(r.scratch.vao);
    for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
      if (s.obstacles[k].kind != ObstacleKind::plane) {
        gl.DrawArrays(GL_TRIANGLES, first[k], count[k]);
      }
    }
    gl.Disable(GL_POLYGON_OFFSET_FILL);
  }

  gl.BindFramebuffer(GL_FRAMEBUFFER, r.draw_target());
  gl.Viewport(0, 0, o.width, o.height);
  // One full clear: on llvmpipe it is a per-tile flag, where scissored clears (the old banded
  // sky) cost half a bare frame. The sky is drawn last, behind everything.
  gl.ClearColor(0, 0, 0, 1);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.UseProgram(r.surface);
  r.set(r.surface, "u_view_proj", view_proj);
  r.set(r.surface, "u_light_view_proj", light);
  r.set(r.surface, "u_camera", camera.position);
  r.set(r.surface, "u_key_direction", kKeyDirection);
  r.set(r.surface, "u_fill_direction", kFillDirection);
  r.set(r.surface, "u_shadows", o.shadows ? 1 : 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, r.shadow_texture);
  r.set(r.surface, "u_shadow_map", 0);
  // Bodies first: the planes behind them then fail the depth test before shading.
  if (o.wireframe) {
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(1.0f, 1.0f);
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    r.set(r.surface, "u_base_color", s.bodies[b].color);
    r.set(r.surface, "u_roughness", s.bodies[b].roughness);
    gl.BindVertexArray(r.bodies[b].vao);
    gl.DrawElements(GL_TRIANGLES, r.bodies[b].triangle_count, GL_UNSIGNED_INT, nullptr);
  }
  gl.Disable(GL_POLYGON_OFFSET_FILL);

  // Boxes and meshes with the surface shader.
  gl.BindVertexArray(r.scratch.vao);
  r.set(r.surface, "u_base_color", Vec3f(0.45f, 0.52f, 0.62f));
  r.set(r.surface, "u_roughness", 0.6f);
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    if (s.obstacles[k].kind != ObstacleKind::plane) gl.DrawArrays(GL_TRIANGLES, first[k], count[k]);
  }
  // Planes cover most of the image, and on a software rasterizer their fill is the cost. Their
  // lighting is constant (the normal is), so most of each is one flat colour (tone mapped here,
  // as the shaders do), its grid lines, and only the patch where shadows can fall is shaded per
  // pixel by ground.frag (LEQUAL, in front of the base by its polygon offset).
  auto tone_map = [](const Vec3f& c) { return Vec3f((c.array() / (1.0f + c.array())).sqrt()); };
  const Vec3f albedo(0.62f, 0.60f, 0.56f);
  std::size_t plane = 0;
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    const ObstacleSnapshot& ob = s.obstacles[k];
    if (ob.kind != ObstacleKind::plane) continue;
    const Impl::PlaneParts& parts = r.planes[plane++];
    // The camera sees a plane from its normal's side or through it; light it from that side.
    const Vec3f n =
        (camera.position - ob.point).dot(ob.normal) >= 0 ? ob.normal : Vec3f(-ob.normal);
    const float key = std::max(n.dot(kKeyDirection), 0.0f);
    const float fill = std::max(n.dot(kFillDirection), 0.0f);
    const float sky = 0.5f + 0.5f * n.z();
    const Vec3f shade = Vec3f(0.55f, 0.65f, 0.8f) * 0.45f * fill +
                        Vec3f(0.10f, 0.09f, 0.08f) * (1 - sky) + Vec3f(0.22f, 0.25f, 0.30f) * sky;
    const Vec3f lit = Vec3f(1.0f, 0.96f, 0.9f) * 2.2f * key;
    const Vec3f light_sum = shade + lit;
    gl.BindVertexArray(r.scratch.vao);
    gl.UseProgram(r.line);
    r.set(r.line, "u_view_proj", view_proj);
    r.set(r.line, "u_point_size", 1.0f);
    r.set(r.line, "u_color", tone_map(albedo.cwiseProduct(light_sum)));
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(1.0f, 1.0f);
    gl.DrawArrays(GL_TRIANGLES, first[k], count[k]);
    gl.DepthFunc(GL_LEQUAL);
    r.set(r.line, "u_color", tone_map(Vec3f(0.55f * albedo.cwiseProduct(light_sum))));
    gl.DrawArrays(GL_LINES, parts.grid_first, parts.grid_count);
    if (o.shadows && parts.patch_count > 0) {
      // Not pushed back like the base: its corners differ, so at equal offsets the two
      // interpolated depths would fight.
      gl.Disable(GL_POLYGON_OFFSET_FILL);
      gl.UseProgram(r.ground);
      r.set(r.ground, "u_view_proj", view_proj);
      r.set(r.ground, "u_light_view_proj", light);
      r.set(r.ground, "u_shadows", 1);
      r.set(r.ground, "u_shadow_map", 0);
      r.set(r.ground, "u_base_color", albedo);
      r.set(r.ground, "u_lit", lit);
      r.set(r.ground, "u_shade", shade);
      r.set(r.ground, "u_bias", 0.002f + 0.006f * (1.0f - key));
      const Vec3f u = perpendicular(ob.normal);
      r.set(r.ground, "u_grid_origin", ob.point);
      r.set(r.ground, "u_grid_u", u);
      r.set(r.ground, "u_grid_v", Vec3f(ob.normal.cross(u)));
      gl.DrawArrays(GL_TRIANGLES, parts.patch_first, parts.patch_count);
    }
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
  }

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

  gl.UseProgram(r.line);
  r.set(r.line, "u_view_proj", view_proj);
  r.set(r.line, "u_point_size", 1.0f);
  if (o.wireframe) {
    r.set(r.line, "u_color", Vec3f(0.08f, 0.08f, 0.1f));
    for (const Mesh& m : r.bodies) {
      gl.BindVertexArray(m.vao);
      gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.edges);
      gl.DrawElements(GL_LINES, m.edge_count, GL_UNSIGNED_INT, nullptr);
      gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.triangles);
    }
  }
  if (!s.springs.empty()) {
    gl.Disable(GL_DEPTH_TEST);
    gl.Enable(GL_PROGRAM_POINT_SIZE);
    gl.BindVertexArray(r.scratch.vao);
    r.set(r.line, "u_color", Vec3f(0.95f, 0.85f, 0.2f));
    const auto n = static_cast<GLsizei>(2 * s.springs.size());
    gl.DrawArrays(GL_LINES, springs_first, n);
    r.set(r.line, "u_point_size", 7.0f);
    gl.DrawArrays(GL_POINTS, springs_first, n);
    gl.Disable(GL_PROGRAM_POINT_SIZE);
    gl.Enable(GL_DEPTH_TEST);
  }
  if (!s.constraints.empty()) {
    // Constraints join points on or inside the parts: drawn over them, green when held, turning
    // red as the violation |C| reaches kConstraintRedViolation.
    gl.Disable(GL_DEPTH_TEST);
    gl.Enable(GL_PROGRAM_POINT_SIZE);
    gl.BindVertexArray(r.scratch.vao);
    r.set(r.line, "u_point_size", 5.0f);
    const GLint constraints_first = springs_first + static_cast<GLint>(2 * s.springs.size());
    for (std::size_t k = 0; k < s.constraints.size(); ++k) {
      const float t = std::clamp(s.constraints[k].violation / kConstraintRedViolation, 0.0f, 1.0f);
      r.set(r.line, "u_color", Vec3f(0.25f + 0.7f * t, 0.9f - 0.7f * t, 0.35f - 0.15f * t));
      const auto at = constraints_first + static_cast<GLint>(2 * k);
      gl.DrawArrays(GL_LINES, at, 2);
      gl.DrawArrays(GL_POINTS, at, 2);
    }
    gl.Disable(GL_PROGRAM_POINT_SIZE);
    gl.Enable(GL_DEPTH_TEST);
  }
  gl.BindVertexArray(0);
  r.resolve();
  gl.Finish();
  r.times.draw = seconds_since(t0);
}

void Renderer::render_bare(const Snapshot& s, const Camera& camera, const RenderOptions& o) {
  Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  r.ensure_targets(o);
  r.upload_bodies(s);
  std::vector<GLint> first;
  std::vector<GLsizei> count;
  GLint springs_first = 0;
  r.upload_scene_geometry(s, first, count, springs_first);
  const auto t0 = Clock::now();
  const float aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  gl.BindFramebuffer(GL_FRAMEBUFFER, r.draw_target());
  gl.Viewport(0, 0, o.width, o.height);
  gl.Enable(GL_DEPTH_TEST);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.UseProgram(r.line);
  r.set(r.line, "u_view_proj",
        Mat4f(perspective_matrix(camera.fov, aspect, 0.05f, 500.0f) * view_matrix(camera)));
  r.set(r.line, "u_point_size", 1.0f);
  r.set(r.line, "u_color", Vec3f(0.8f, 0.3f, 0.3f));
  for (const Mesh& m : r.bodies) {
    gl.BindVertexArray(m.vao);
    gl.DrawElements(GL_TRIANGLES, m.triangle_count, GL_UNSIGNED_INT, nullptr);
  }
  gl.BindVertexArray(r.scratch.vao);
  for (std::size_t k = 0; k < s.obstacles.size(); ++k)
    gl.DrawArrays(GL_TRIANGLES, first[k], count[k]);
  gl.BindVertexArray(0);
  r.resolve();
  gl.Finish();
  r.times.draw = seconds_since(t0);
}

void Renderer::present(GLuint framebuffer) const {
  const Impl& r = *impl_;
  r.gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r.resolve_fbo);
  r.gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  r.gl.BlitFramebuffer(0, 0, r.width, r.height, 0, 0, r.width, r.height, GL_COLOR_BUFFER_BIT,
                       GL_NEAREST);
  r.gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

void Renderer::read_rgb(std::vector<unsigned char>& rgb) const {
  const Impl& r = *impl_;
  const gl::Functions& gl = r.gl;
  std::vector<unsigned char> rgba(4 * static_cast<std::size_t>(r.width) * r.height);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r.resolve_fbo);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, r.width, r.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  rgb.resize(3 * static_cast<std::size_t>(r.width) * r.height);
  for (int y = 0; y < r.height; ++y) {
    const unsigned char* src =
        rgba.data() + 4 * static_cast<std::size_t>(r.height - 1 - y) * r.width;
    unsigned char* dst = rgb.data() + 3 * static_cast<std::size_t>(y) * r.width;
    for (int x = 0; x < r.width; ++x) {
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
  return impl_->samples_in_use;
}

}  // namespace pbm
