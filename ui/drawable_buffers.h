// What the GPU holds of a snapshot's drawables, and the frame's draw list the renderer's passes
// walk (renderer.cpp). Geometry that snapshots share (a mesh topology, a flat mesh's positions)
// is uploaded once and kept while its shared_ptr lives: entries are found by the drawable's
// address, an expired weak_ptr means that address now holds something new, and entries no
// drawable of a frame used are freed after it. What changes every frame (a deforming mesh's
// vertices, height fields, planes, lines and points) is uploaded again into buffers that only
// grow.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "draw/snapshot.h"
#include "drawable_geometry.h"
#include "gl_functions.h"

namespace pbm {

// A vertex array over one vertex buffer that grows as needed.
struct VertexBuffer {
  GLuint vao = 0, vbo = 0;
  std::size_t capacity = 0;  // [bytes]
};

// One solid of the frame as the passes draw it: indexed (element buffers) or a range of its
// vertex arrays, placed by the solid shaders' uniforms (drawable_geometry.h).
struct Solid {
  GLuint vao = 0;
  GLuint triangles = 0, casters = 0, edges = 0;  // element buffers; 0: arrays
  GLint first = 0, edge_first = 0;               // arrays
  GLsizei count = 0, caster_count = 0, edge_count = 0;
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();
  Eigen::Vector3f offset = Eigen::Vector3f::Zero();
  Eigen::Vector3f scale = Eigen::Vector3f::Ones();
  float stretch = 0;
  draw::Material material{};
  draw::Layer layer = draw::Layer::scene;
};

// A range of the coloured vertex buffer (position, colour): Lines (segments, maybe their end
// points), Points, or triangles (a field section's cells; with `screen`, a colour bar in pixels
// from the image's top-right corner, colour_bar.h).
struct ColoredRange {
  GLint first = 0;
  GLsizei count = 0;
  bool lines = true, end_points = false;
  bool triangles = false, screen = false;
  float point_size = 1;  // [pixels]: Points, or Lines' end points
  draw::Layer layer = draw::Layer::overlay;
};

class DrawableBuffers {
 public:
  // Uploads the unit primitives. The context must stay current while the buffers live.
  explicit DrawableBuffers(const gl::Functions& gl);
  ~DrawableBuffers();
  DrawableBuffers(const DrawableBuffers&) = delete;
  DrawableBuffers& operator=(const DrawableBuffers&) = delete;

  // Fills the frame below from the snapshot. Planes' shadow patches are cast along
  // `key_direction` from `casters`.
  void upload(const draw::Snapshot& snapshot, const Eigen::Vector3f& key_direction);

  // The frame. Solids: smooth meshes, flat meshes, primitives, height fields, each in snapshot
  // order (a mesh whose topology indexes past its positions is left out).
  std::vector<Solid> solids;
  std::vector<PlaneParts> planes;  // one per snapshot plane, in planes_vao
  std::vector<ColoredRange> colored;
  // What casts shadows: the snapshot's focus, or the scene-layer solids' bounds without one.
  draw::Bounds casters;
  GLuint planes_vao() const { return planes_.vao; }
  GLuint colored_vao() const { return colored_.vao; }

 private:
  // A shared topology of smooth meshes: its triangles, element edges and the shadow pass's
  // coarse copy (shadow_casters.h, made from the first positions drawn with it).
  struct TopologyBuffers {
    std::weak_ptr<const draw::MeshTopology> source;
    GLuint triangles = 0, edges = 0, casters = 0;
    GLsizei triangle_count = 0, edge_count = 0, caster_count = 0;  // indices
    std::size_t vertices_needed = 0;                               // 1 + the largest index
    bool used = false;                                             // by the frame being drawn
  };
  // A flat mesh unindexed (flat_mesh_vertices) for one pair of shared positions and topology:
  // a mesh obstacle is uploaded once, however it moves.
  struct FlatBuffers {
    std::weak_ptr<const std::vector<draw::Vec3f>> positions;
    std::weak_ptr<const draw::MeshTopology> topology;
    VertexBuffer vertices;
    GLsizei triangle_vertices = 0, edge_vertices = 0;
    bool used = false;
  };
  struct HeightFieldBuffers {
    VertexBuffer vertices;
    GLuint triangles = 0;
    int nx = 0, ny = 0;
    GLsizei index_count = 0;
  };

  // `floats` a vertex: position at 0, a normal or a colour at 1, the primitives' stretch at 2.
  void create_buffer(VertexBuffer& b, int floats);
  void delete_buffer(VertexBuffer& b);
  void upload_vertices(VertexBuffer& b, const std::vector<float>& data);
  template <class T>
  GLuint index_buffer(const std::vector<T>& data);
  void delete_topology(TopologyBuffers& t);
  const TopologyBuffers& topology_buffers(const std::shared_ptr<const draw::MeshTopology>& topology,
                                          const std::vector<draw::Vec3f>& positions);
  const FlatBuffers& flat_buffers(const draw::Mesh& mesh);
  void upload_meshes(const draw::Snapshot& s);
  void upload_primitives_and_fields(const draw::Snapshot& s);
  void upload_planes_and_colored(const draw::Snapshot& s, const Eigen::Vector3f& key_direction);
  void release_unused();

  const gl::Functions& gl_;
  std::vector<VertexBuffer> smooth_;  // per smooth mesh of the frame, in order
  std::map<const draw::MeshTopology*, TopologyBuffers> topologies_;
  std::map<std::pair<const void*, const void*>, FlatBuffers> flats_;  // (positions, topology)
  std::array<VertexBuffer, 4> unit_primitives_;                       // by draw::PrimitiveShape
  std::array<GLsizei, 4> unit_primitive_vertices_{};
  std::vector<HeightFieldBuffers> fields_;  // per height field of the frame, in order
  VertexBuffer planes_, colored_;
  std::vector<float> vertices_;  // scratch for uploads
};

}  // namespace pbm
