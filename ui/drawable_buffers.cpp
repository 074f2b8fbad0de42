#include "drawable_buffers.h"

#include <algorithm>

#include "colour_bar.h"
#include "shadow_casters.h"

namespace pbm {
namespace {

using Vec3f = Eigen::Vector3f;

// A 1024² shadow map resolves about this many triangles of one mesh; more only cost time
// (shadow_casters.h).
constexpr std::size_t kMaxShadowCasterTriangles = 4096;
constexpr int kColoredFloats = 6;  // position, colour

// 1 + the largest vertex index of the topology: how many positions it needs.
std::size_t vertices_needed(const draw::MeshTopology& t) {
  int largest = -1;
  for (const auto& triangle : t.triangles) {
    for (int k : triangle) largest = std::max(largest, k);
  }
  for (const auto& edge : t.edges) largest = std::max({largest, edge[0], edge[1]});
  return static_cast<std::size_t>(largest + 1);
}

// Bounds of every scene-layer solid but the planes: where shadows are cast from when the
// snapshot names no focus (a hand-made snapshot).
draw::Bounds scene_solid_bounds(const draw::Snapshot& s) {
  draw::Bounds b;
  for (const draw::Mesh& m : s.meshes) {
    if (!m.positions) continue;
    for (const Vec3f& x : *m.positions) b.add(m.rotation * x + m.offset);
  }
  for (const draw::Primitive& p : s.primitives) {
    if (p.layer != draw::Layer::scene) continue;
    const draw::Bounds pb = primitive_bounds(p);
    b.add(pb.min);
    b.add(pb.max);
  }
  for (const draw::HeightField& f : s.height_fields) {
    if (f.layer != draw::Layer::scene || f.heights.empty()) continue;
    const auto [lo, hi] = std::minmax_element(f.heights.begin(), f.heights.end());
    b.add(f.origin + Vec3f(0, 0, *lo));
    b.add(f.origin + Vec3f(static_cast<float>(f.nx - 1) * f.cell.x(),
                           static_cast<float>(f.ny - 1) * f.cell.y(), *hi));
  }
  return b;
}

}  // namespace

DrawableBuffers::DrawableBuffers(const gl::Functions& gl) : gl_(gl) {
  create_buffer(planes_, kSolidFloats);
  create_buffer(colored_, kColoredFloats);
  for (std::size_t shape = 0; shape < unit_primitives_.size(); ++shape) {
    const std::vector<float> unit =
        unit_primitive_vertices(static_cast<draw::PrimitiveShape>(shape));
    create_buffer(unit_primitives_[shape], kPrimitiveFloats);
    upload_vertices(unit_primitives_[shape], unit);
    unit_primitive_vertices_[shape] = static_cast<GLsizei>(unit.size() / kPrimitiveFloats);
  }
}

DrawableBuffers::~DrawableBuffers() {
  for (VertexBuffer& b : smooth_) delete_buffer(b);
  for (auto& [key, t] : topologies_) delete_topology(t);
  for (auto& [key, f] : flats_) delete_buffer(f.vertices);
  for (VertexBuffer& b : unit_primitives_) delete_buffer(b);
  for (HeightFieldBuffers& f : fields_) {
    delete_buffer(f.vertices);
    if (f.triangles) gl_.DeleteBuffers(1, &f.triangles);
  }
  delete_buffer(planes_);
  delete_buffer(colored_);
}

// `floats` a vertex: position at 0, then a normal or a colour at 1 (3 floats), then the
// primitives' stretch at 2.
void DrawableBuffers::create_buffer(VertexBuffer& b, int floats) {
  gl_.GenVertexArrays(1, &b.vao);
  gl_.GenBuffers(1, &b.vbo);
  gl_.BindVertexArray(b.vao);
  gl_.BindBuffer(GL_ARRAY_BUFFER, b.vbo);
  const auto stride = static_cast<GLsizei>(floats * sizeof(float));
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(3 * sizeof(float)));
  gl_.EnableVertexAttribArray(1);
  if (floats == kPrimitiveFloats) {
    gl_.VertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride,
                            reinterpret_cast<void*>(6 * sizeof(float)));
    gl_.EnableVertexAttribArray(2);
  }
  gl_.BindVertexArray(0);
}
void DrawableBuffers::delete_buffer(VertexBuffer& b) {
  gl_.DeleteBuffers(1, &b.vbo);
  gl_.DeleteVertexArrays(1, &b.vao);
  b = VertexBuffer{};
}
void DrawableBuffers::upload_vertices(VertexBuffer& b, const std::vector<float>& data) {
  gl_.BindBuffer(GL_ARRAY_BUFFER, b.vbo);
  const std::size_t bytes = data.size() * sizeof(float);
  if (bytes > b.capacity) {
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), data.data(), GL_STREAM_DRAW);
    b.capacity = bytes;
  } else {
    gl_.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data.data());
  }
}
// Index data through the array target: with no vertex array bound there is no element binding.
template <class T>
GLuint DrawableBuffers::index_buffer(const std::vector<T>& data) {
  GLuint b = 0;
  gl_.GenBuffers(1, &b);
  gl_.BindBuffer(GL_ARRAY_BUFFER, b);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                 GL_STATIC_DRAW);
  return b;
}
void DrawableBuffers::delete_topology(TopologyBuffers& t) {
  for (GLuint* b : {&t.triangles, &t.edges, &t.casters}) {
    if (*b) gl_.DeleteBuffers(1, b);
  }
}

// The topology's buffers, made on first sight (casters from these positions).
const DrawableBuffers::TopologyBuffers& DrawableBuffers::topology_buffers(
    const std::shared_ptr<const draw::MeshTopology>& topology,
    const std::vector<Vec3f>& positions) {
  auto it = topologies_.find(topology.get());
  if (it != topologies_.end() && it->second.source.expired()) {
    delete_topology(it->second);
    topologies_.erase(it);
    it = topologies_.end();
  }
  if (it == topologies_.end()) {
    TopologyBuffers t;
    t.source = topology;
    gl_.BindVertexArray(0);
    t.triangles = index_buffer(topology->triangles);
    t.edges = index_buffer(topology->edges);
    t.triangle_count = static_cast<GLsizei>(3 * topology->triangles.size());
    t.edge_count = static_cast<GLsizei>(2 * topology->edges.size());
    t.vertices_needed = vertices_needed(*topology);
    if (positions.size() >= t.vertices_needed) {
      const auto coarse =
          shadow_caster_triangles(positions, topology->triangles, kMaxShadowCasterTriangles);
      t.casters = index_buffer(coarse);
      t.caster_count = static_cast<GLsizei>(3 * coarse.size());
    }
    it = topologies_.emplace(topology.get(), std::move(t)).first;
  }
  it->second.used = true;
  return it->second;
}

const DrawableBuffers::FlatBuffers& DrawableBuffers::flat_buffers(const draw::Mesh& m) {
  const std::pair<const void*, const void*> key{m.positions.get(), m.topology.get()};
  auto it = flats_.find(key);
  if (it != flats_.end() && (it->second.positions.expired() || it->second.topology.expired())) {
    delete_buffer(it->second.vertices);
    flats_.erase(it);
    it = flats_.end();
  }
  if (it == flats_.end()) {
    FlatBuffers f;
    f.positions = m.positions;
    f.topology = m.topology;
    create_buffer(f.vertices, kSolidFloats);
    if (m.positions->size() >= vertices_needed(*m.topology)) {  // else a broken mesh: nothing
      flat_mesh_vertices(*m.positions, *m.topology, vertices_);
      upload_vertices(f.vertices, vertices_);
      f.triangle_vertices = static_cast<GLsizei>(3 * m.topology->triangles.size());
      f.edge_vertices = static_cast<GLsizei>(2 * m.topology->edges.size());
    }
    it = flats_.emplace(key, std::move(f)).first;
  }
  it->second.used = true;
  return it->second;
}

// Frees what no drawable of the last frame used (a closed scene, an edited model).
void DrawableBuffers::release_unused() {
  for (auto it = topologies_.begin(); it != topologies_.end();) {
    if (it->second.used) {
      it->second.used = false;
      ++it;
    } else {
      delete_topology(it->second);
      it = topologies_.erase(it);
    }
  }
  for (auto it = flats_.begin(); it != flats_.end();) {
    if (it->second.used) {
      it->second.used = false;
      ++it;
    } else {
      delete_buffer(it->second.vertices);
      it = flats_.erase(it);
    }
  }
}

void DrawableBuffers::upload_meshes(const draw::Snapshot& s) {
  std::size_t slot = 0;
  // Smooth meshes (the bodies) before flat ones (obstacles): what stands in front is drawn
  // first, so that more of what it hides fails the depth test before shading.
  for (const draw::Shading shading : {draw::Shading::smooth, draw::Shading::flat}) {
    for (const draw::Mesh& m : s.meshes) {
      if (m.shading != shading || !m.positions || !m.topology) continue;
      const std::vector<Vec3f>& positions = *m.positions;
      Solid solid{.rotation = m.rotation, .offset = m.offset, .material = m.material};
      if (shading == draw::Shading::smooth) {
        const TopologyBuffers& t = topology_buffers(m.topology, positions);
        if (positions.size() < t.vertices_needed) continue;  // a broken mesh: skip, not crash
        if (slot == smooth_.size()) create_buffer(smooth_.emplace_back(), kSolidFloats);
        smooth_mesh_vertices(positions, m.topology->triangles, vertices_);
        upload_vertices(smooth_[slot], vertices_);
        solid.vao = smooth_[slot++].vao;
        solid.triangles = t.triangles;
        solid.count = t.triangle_count;
        solid.casters = t.caster_count > 0 ? t.casters : t.triangles;
        solid.caster_count = t.caster_count > 0 ? t.caster_count : t.triangle_count;
        solid.edges = t.edges;
        solid.edge_count = t.edge_count;
      } else {
        const FlatBuffers& f = flat_buffers(m);
        solid.vao = f.vertices.vao;
        solid.count = solid.caster_count = f.triangle_vertices;
        solid.edge_first = f.triangle_vertices;
        solid.edge_count = f.edge_vertices;
      }
      solids.push_back(solid);
    }
  }
  while (smooth_.size() > slot) {
    delete_buffer(smooth_.back());
    smooth_.pop_back();
  }
}

void DrawableBuffers::upload_primitives_and_fields(const draw::Snapshot& s) {
  for (const draw::Primitive& p : s.primitives) {
    const int shape = static_cast<int>(p.shape);
    const PrimitiveTransform t = primitive_transform(p);
    solids.push_back({.vao = unit_primitives_[shape].vao,
                      .count = unit_primitive_vertices_[shape],
                      .caster_count = unit_primitive_vertices_[shape],
                      .rotation = p.rotation,
                      .offset = p.center,
                      .scale = t.scale,
                      .stretch = t.stretch,
                      .material = p.material,
                      .layer = p.layer});
  }
  std::size_t slot = 0;
  for (const draw::HeightField& f : s.height_fields) {
    if (f.nx < 2 || f.ny < 2 || f.heights.size() != static_cast<std::size_t>(f.nx) * f.ny) {
      continue;
    }
    if (slot == fields_.size()) create_buffer(fields_.emplace_back().vertices, kSolidFloats);
    HeightFieldBuffers& b = fields_[slot++];
    if (b.nx != f.nx || b.ny != f.ny) {
      if (b.triangles) gl_.DeleteBuffers(1, &b.triangles);
      gl_.BindVertexArray(0);
      const auto triangles = height_field_triangles(f.nx, f.ny);
      b.triangles = index_buffer(triangles);
      b.index_count = static_cast<GLsizei>(3 * triangles.size());
      b.nx = f.nx;
      b.ny = f.ny;
    }
    height_field_vertices(f, vertices_);
    upload_vertices(b.vertices, vertices_);
    solids.push_back({.vao = b.vertices.vao,
                      .triangles = b.triangles,
                      .casters = b.triangles,
                      .count = b.index_count,
                      .caster_count = b.index_count,
                      .material = f.material,
                      .layer = f.layer});
  }
  while (fields_.size() > slot) {
    delete_buffer(fields_.back().vertices);
    if (fields_.back().triangles) gl_.DeleteBuffers(1, &fields_.back().triangles);
    fields_.pop_back();
  }
}

// Planes (world vertices) and the lines and points (world positions, a colour each).
void DrawableBuffers::upload_planes_and_colored(const draw::Snapshot& s,
                                                const Vec3f& key_direction) {
  vertices_.clear();
  planes.clear();
  for (const draw::Plane& p : s.planes) {
    planes.push_back(append_plane_vertices(p, casters, key_direction, vertices_));
  }
  if (!vertices_.empty()) upload_vertices(planes_, vertices_);
  vertices_.clear();
  colored.clear();
  auto vertex = [&](const Vec3f& p, const Vec3f& c) {
    vertices_.insert(vertices_.end(), {p.x(), p.y(), p.z(), c.x(), c.y(), c.z()});
  };
  auto first = [&] { return static_cast<GLint>(vertices_.size() / kColoredFloats); };
  const Vec3f white = Vec3f::Ones();
  for (const draw::Lines& l : s.lines) {
    ColoredRange r{.first = first(),
                   .end_points = l.end_points,
                   .point_size = l.end_point_size,
                   .layer = l.layer};
    for (std::size_t k = 0; 2 * k + 1 < l.points.size(); ++k) {
      const Vec3f& c = k < l.colors.size() ? l.colors[k] : white;
      vertex(l.points[2 * k], c);
      vertex(l.points[2 * k + 1], c);
    }
    r.count = first() - r.first;
    if (r.count > 0) colored.push_back(r);
  }
  for (const draw::Points& p : s.points) {
    ColoredRange r{.first = first(), .lines = false, .point_size = p.size, .layer = p.layer};
    for (std::size_t k = 0; k < p.positions.size(); ++k) {
      vertex(p.positions[k], k < p.colors.size() ? p.colors[k] : white);
    }
    r.count = first() - r.first;
    if (r.count > 0) colored.push_back(r);
  }
  for (const draw::FieldSection& section : s.sections) {
    ColoredRange r{.first = first(), .lines = false, .triangles = true, .layer = section.layer};
    append_section_triangles(section, vertices_);
    r.count = first() - r.first;
    if (r.count > 0) colored.push_back(r);
  }
  for (std::size_t k = 0; k < s.sections.size(); ++k) {
    ColoredRange r{.first = first(), .lines = false, .triangles = true, .screen = true};
    append_colour_bar(s.sections[k], static_cast<int>(k), vertices_);
    r.count = first() - r.first;
    if (r.count > 0) colored.push_back(r);
  }
  if (!vertices_.empty()) upload_vertices(colored_, vertices_);
}

void DrawableBuffers::upload(const draw::Snapshot& s, const Vec3f& key_direction) {
  solids.clear();
  casters = s.focus.empty() ? scene_solid_bounds(s) : s.focus;
  upload_meshes(s);
  upload_primitives_and_fields(s);
  upload_planes_and_colored(s, key_direction);
  release_unused();
}

}  // namespace pbm
