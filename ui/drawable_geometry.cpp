#include "drawable_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace pbm {
namespace {

using draw::Vec3f;

// Latitude bands (even, so that the capsule has an equator) and longitude segments of the unit
// sphere and capsule: smooth to the eye at the sizes figures and markers are drawn.
constexpr int kRings = 24;
constexpr int kSegments = 48;

void push(std::vector<float>& out, const Vec3f& p, const Vec3f& n) {
  out.insert(out.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()});
}
void push(std::vector<float>& out, const Vec3f& p, const Vec3f& n, float stretch) {
  out.insert(out.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), stretch});
}

// Rows of a latitude-longitude grid on the unit sphere, north pole first: the polar angle of
// each row and its stretch. Consecutive rows are joined by a band of quads.
struct Row {
  float theta = 0;
  float stretch = 0;
};

std::vector<float> lat_long_vertices(const std::vector<Row>& rows) {
  std::vector<float> out;
  const float pi = std::numbers::pi_v<float>;
  auto at = [&](const Row& row, int j) {
    const float phi = 2 * pi * static_cast<float>(j % kSegments) / kSegments;
    return Vec3f(std::sin(row.theta) * std::cos(phi), std::sin(row.theta) * std::sin(phi),
                 std::cos(row.theta));
  };
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const Row &top = rows[i], &bottom = rows[i + 1];
    for (int j = 0; j < kSegments; ++j) {
      const Vec3f a = at(top, j), b = at(bottom, j), c = at(bottom, j + 1), d = at(top, j + 1);
      // Counter-clockwise seen from outside; the pole rows' collapsed triangle is left out.
      if (top.theta > 0) {
        push(out, a, a, top.stretch);
        push(out, b, b, bottom.stretch);
        push(out, d, d, top.stretch);
      }
      if (bottom.theta < pi) {
        push(out, d, d, top.stretch);
        push(out, b, b, bottom.stretch);
        push(out, c, c, bottom.stretch);
      }
    }
  }
  return out;
}

std::vector<float> sphere_vertices(bool capsule) {
  const float pi = std::numbers::pi_v<float>;
  std::vector<Row> rows;
  for (int i = 0; i <= kRings; ++i) {
    const float theta = pi * static_cast<float>(i) / kRings;
    if (!capsule) {
      rows.push_back({theta, 0});
      continue;
    }
    if (2 * i <= kRings) rows.push_back({theta, 1});
    if (2 * i >= kRings) rows.push_back({theta, -1});  // the equator twice: the band
  }
  return lat_long_vertices(rows);
}

std::vector<float> cylinder_vertices() {
  std::vector<float> out;
  const float pi = std::numbers::pi_v<float>;
  auto rim = [&](int j) {
    const float phi = 2 * pi * static_cast<float>(j % kSegments) / kSegments;
    return Vec3f(std::cos(phi), std::sin(phi), 0);
  };
  const Vec3f up = Vec3f::UnitZ();
  for (int j = 0; j < kSegments; ++j) {
    const Vec3f r0 = rim(j), r1 = rim(j + 1);
    const Vec3f a = r0 - up, b = r1 - up, c = r1 + up, d = r0 + up;
    for (const Vec3f* corner : {&a, &b, &c, &a, &c, &d}) {
      push(out, *corner, Vec3f(corner->x(), corner->y(), 0), 0);
    }
    push(out, up, up, 0);  // top cap
    push(out, d, up, 0);
    push(out, c, up, 0);
    push(out, -up, -up, 0);  // bottom cap
    push(out, b, -up, 0);
    push(out, a, -up, 0);
  }
  return out;
}

std::vector<float> box_vertices() {
  std::vector<float> out;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      const Vec3f n = sign * Vec3f::Unit(axis);
      const Vec3f u = Vec3f::Unit((axis + 1) % 3), v = n.cross(u);
      auto corner = [&](float su, float sv) { return Vec3f(n + su * u + sv * v); };
      const Vec3f c[4] = {corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)};
      for (int k : {0, 1, 2, 0, 2, 3}) push(out, c[k], n, 0);
    }
  }
  return out;
}

}  // namespace

void smooth_mesh_vertices(const std::vector<Vec3f>& positions,
                          const std::vector<std::array<int, 3>>& triangles,
                          std::vector<float>& out) {
  const std::size_t n = positions.size();
  std::vector<Vec3f> normals(n, Vec3f::Zero());
  for (const std::array<int, 3>& t : triangles) {
    const Vec3f& a = positions[t[0]];
    const Vec3f face = (positions[t[1]] - a).cross(positions[t[2]] - a);
    for (int k = 0; k < 3; ++k) normals[t[k]] += face;
  }
  out.resize(kSolidFloats * n);
  for (std::size_t i = 0; i < n; ++i) {
    const float len = normals[i].norm();
    const Vec3f normal = len > 0 ? Vec3f(normals[i] / len) : Vec3f::UnitZ();
    for (int k = 0; k < 3; ++k) {
      out[kSolidFloats * i + k] = positions[i][k];
      out[kSolidFloats * i + 3 + k] = normal[k];
    }
  }
}

void flat_mesh_vertices(const std::vector<Vec3f>& positions, const draw::MeshTopology& topology,
                        std::vector<float>& out) {
  out.clear();
  out.reserve(kSolidFloats * (3 * topology.triangles.size() + 2 * topology.edges.size()));
  for (const std::array<int, 3>& t : topology.triangles) {
    const Vec3f &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    const Vec3f n = (b - a).cross(c - a).normalized();
    push(out, a, n);
    push(out, b, n);
    push(out, c, n);
  }
  for (const std::array<int, 2>& e : topology.edges) {
    push(out, positions[e[0]], Vec3f::Zero());
    push(out, positions[e[1]], Vec3f::Zero());
  }
}

std::vector<float> unit_primitive_vertices(draw::PrimitiveShape shape) {
  switch (shape) {
    case draw::PrimitiveShape::box:
      return box_vertices();
    case draw::PrimitiveShape::sphere:
      return sphere_vertices(false);
    case draw::PrimitiveShape::capsule:
      return sphere_vertices(true);
    case draw::PrimitiveShape::cylinder:
      return cylinder_vertices();
  }
  return {};
}

PrimitiveTransform primitive_transform(const draw::Primitive& p) {
  const float r = p.half_size.x();
  switch (p.shape) {
    case draw::PrimitiveShape::box:
      return {p.half_size, 0};
    case draw::PrimitiveShape::sphere:
      return {Vec3f::Constant(r), 0};
    case draw::PrimitiveShape::capsule:
      return {Vec3f::Constant(r), p.half_size.z()};
    case draw::PrimitiveShape::cylinder:
      return {Vec3f(r, r, p.half_size.z()), 0};
  }
  return {};
}

draw::Bounds primitive_bounds(const draw::Primitive& p) {
  const PrimitiveTransform t = primitive_transform(p);
  const Vec3f local = t.scale + Vec3f(0, 0, t.stretch);
  const Vec3f reach = p.rotation.cwiseAbs() * local;
  draw::Bounds b;
  b.add(p.center - reach);
  b.add(p.center + reach);
  return b;
}

void height_field_vertices(const draw::HeightField& f, std::vector<float>& out) {
  out.resize(kSolidFloats * static_cast<std::size_t>(f.nx) * f.ny);
  auto h = [&](int i, int j) {
    return f.heights[static_cast<std::size_t>(std::clamp(j, 0, f.ny - 1)) * f.nx +
                     std::clamp(i, 0, f.nx - 1)];
  };
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) {
      // Central differences inside, one-sided at the border (the clamp repeats the edge value,
      // so the span is one cell there).
      const float dx = static_cast<float>(std::min(i + 1, f.nx - 1) - std::max(i - 1, 0));
      const float dy = static_cast<float>(std::min(j + 1, f.ny - 1) - std::max(j - 1, 0));
      const float slope_x = dx > 0 ? (h(i + 1, j) - h(i - 1, j)) / (dx * f.cell.x()) : 0.0f;
      const float slope_y = dy > 0 ? (h(i, j + 1) - h(i, j - 1)) / (dy * f.cell.y()) : 0.0f;
      const Vec3f n = Vec3f(-slope_x, -slope_y, 1).normalized();
      const Vec3f p = f.origin + Vec3f(static_cast<float>(i) * f.cell.x(),
                                       static_cast<float>(j) * f.cell.y(), h(i, j));
      float* v = out.data() + kSolidFloats * (static_cast<std::size_t>(j) * f.nx + i);
      for (int k = 0; k < 3; ++k) {
        v[k] = p[k];
        v[3 + k] = n[k];
      }
    }
  }
}

std::vector<std::array<int, 3>> height_field_triangles(int nx, int ny) {
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      t.push_back({a, b, c});
      t.push_back({a, c, d});
    }
  }
  return t;
}

Vec3f plane_axis(const Vec3f& n) {
  const Vec3f axis = std::abs(n.y()) < 0.9f ? Vec3f::UnitY() : Vec3f::UnitX();
  return n.cross(axis).normalized();
}

PlaneParts append_plane_vertices(const draw::Plane& o, const draw::Bounds& casters,
                                 const Vec3f& key_direction, std::vector<float>& out) {
  const Vec3f u = plane_axis(o.normal), v = o.normal.cross(u);
  auto count = [&] { return static_cast<int>(out.size() / kSolidFloats); };
  auto rectangle = [&](float u0, float u1, float v0, float v1) {
    const Vec3f corners[4] = {o.point + u0 * u + v0 * v, o.point + u1 * u + v0 * v,
                              o.point + u1 * u + v1 * v, o.point + u0 * u + v1 * v};
    for (int k : {0, 1, 2, 0, 2, 3}) push(out, corners[k], o.normal);
  };
  PlaneParts parts;
  const float a = 0.5f * o.size.x(), b = 0.5f * o.size.y();
  parts.quad_first = count();
  rectangle(-a, a, -b, b);
  parts.quad_count = count() - parts.quad_first;
  // The 1 m grid as lines, at whole plane coordinates.
  parts.grid_first = count();
  for (float c = std::ceil(-a); c <= a; c += 1.0f) {
    push(out, o.point + c * u - b * v, o.normal);
    push(out, o.point + c * u + b * v, o.normal);
  }
  for (float c = std::ceil(-b); c <= b; c += 1.0f) {
    push(out, o.point - a * u + c * v, o.normal);
    push(out, o.point + a * u + c * v, o.normal);
  }
  parts.grid_count = count() - parts.grid_first;
  float u0 = a, u1 = -a, v0 = b, v1 = -b;
  const float along = key_direction.dot(o.normal);
  if (!casters.empty() && along > 0.05f) {
    const Vec3f &lo = casters.min, &hi = casters.max;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3f x((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                    (corner & 4) ? hi.z() : lo.z());
      // Corners below the plane project too: the box is loose, the solid inside may not be.
      const float above = (x - o.point).dot(o.normal);
      const Vec3f d = x - above / along * key_direction - o.point;
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
  parts.patch_first = count();
  if (u0 < u1 && v0 < v1) rectangle(u0, u1, v0, v1);
  parts.patch_count = count() - parts.patch_first;
  return parts;
}

}  // namespace pbm
