// The renderer's CPU side of every drawable kind (draw/snapshot.h): vertex data in the layouts the
// shaders read, with no GL, so each piece is testable on its own (tests/test_render.cpp).
//
// Solid vertex (surface.vert, shadow.vert): position, normal (6 floats); primitives add a
// stretch s (7 floats). A vertex is drawn at
//   x = R (scale * p + stretch * s e_z) + offset,   n = R (normal / scale)   (normalized)
// with (R, offset, scale, stretch) uniforms per drawable: a Mesh has (rotation, offset, 1, 0),
// a Primitive (rotation, center, and the scale and stretch of primitive_transform). All unit
// shapes have normals along an axis of their scale or a uniform scale, so normal / scale is the
// exact inverse-transpose of the stretch.
#pragma once

#include <array>
#include <vector>

#include "draw/snapshot.h"

namespace pbm {

inline constexpr int kSolidFloats = 6;      // position, normal
inline constexpr int kPrimitiveFloats = 7;  // position, normal, stretch

// Positions and area-weighted vertex normals of a smooth mesh, kSolidFloats a vertex, in the
// mesh's own frame (draw::Mesh::positions order). A vertex on no triangle gets +z.
void smooth_mesh_vertices(const std::vector<draw::Vec3f>& positions,
                          const std::vector<std::array<int, 3>>& triangles,
                          std::vector<float>& out);

// A flat mesh unindexed: three vertices a triangle with its face normal, then two a topology
// edge (normal zero) for the wireframe; kSolidFloats a vertex, in the mesh's own frame.
void flat_mesh_vertices(const std::vector<draw::Vec3f>& positions,
                        const draw::MeshTopology& topology, std::vector<float>& out);

// A unit shape, unindexed triangles, kPrimitiveFloats a vertex:
//   box       [-1, 1]^3, four vertices a face (as the renderer drew obstacle boxes before)
//   sphere    radius 1, latitude-longitude
//   cylinder  radius 1, z in [-1, 1], with caps
//   capsule   a unit sphere cut at its equator, the upper half with stretch +1 and the lower
//             with -1, joined by a band between the two copies of the equator: the shader moves
//             each half by +-(half length) e_z, so one unit capsule draws every length, and the
//             band becomes the cylinder (its normals are already horizontal). Scaling a unit
//             capsule instead would squash its hemispheres into half-ellipsoids.
std::vector<float> unit_primitive_vertices(draw::PrimitiveShape shape);

// Scale and stretch (see the header comment) that turn the unit shape into `p`'s.
struct PrimitiveTransform {
  draw::Vec3f scale{1, 1, 1};
  float stretch = 0;
};
PrimitiveTransform primitive_transform(const draw::Primitive& p);

// World bounds of a primitive (loose: its local box turned by its rotation).
draw::Bounds primitive_bounds(const draw::Primitive& p);

// Vertex (i, j) of the height field at index j nx + i: world position and the normal of the
// surface's central differences (one-sided at the border), kSolidFloats a vertex.
void height_field_vertices(const draw::HeightField& field, std::vector<float>& out);
// Two triangles a cell, counter-clockwise seen from +z.
std::vector<std::array<int, 3>> height_field_triangles(int nx, int ny);

// A plane as the renderer draws it (world vertices, kSolidFloats each): the quad of its drawn
// size (6 vertices from `quad_first`), its 1 m grid at whole plane coordinates as lines, and the
// patch where shadows can fall: `casters` (bounds of what casts) projected along the key light
// onto the plane with a margin, clipped to the quad (empty if there is nothing to cast or the
// light grazes the plane). The plane's in-plane axes are `u` = plane_axis(normal), v = n x u.
struct PlaneParts {
  int quad_first = 0, quad_count = 0;
  int grid_first = 0, grid_count = 0;
  int patch_first = 0, patch_count = 0;
};
PlaneParts append_plane_vertices(const draw::Plane& plane, const draw::Bounds& casters,
                                 const draw::Vec3f& key_direction, std::vector<float>& out);
// A unit vector perpendicular to n, chosen the same way every time.
draw::Vec3f plane_axis(const draw::Vec3f& n);

}  // namespace pbm
