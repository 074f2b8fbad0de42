#include "collide/mesh_obstacle.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pbm {
namespace {

constexpr std::size_t kMaxTriangles = 20'000;
// The grid is built by a pass over the triangles per sample: at most this many such pairs.
constexpr double kMaxSampleTriangles = 2e8;
constexpr int kMaxCellsAlongLongestSide = 48;

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const Real denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Solid angle of triangle abc seen from p (Van Oosterom and Strackee), signed by orientation.
Real solid_angle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 x = a - p, y = b - p, z = c - p;
  const Real lx = x.norm(), ly = y.norm(), lz = z.norm();
  const Real numerator = x.dot(y.cross(z));
  const Real denominator = lx * ly * lz + x.dot(y) * lz + y.dot(z) * lx + z.dot(x) * ly;
  return 2 * std::atan2(numerator, denominator);
}

Real sample(const MeshObstacle& m, int i, int j, int k) {
  i = std::clamp(i, 0, m.samples[0] - 1);
  j = std::clamp(j, 0, m.samples[1] - 1);
  k = std::clamp(k, 0, m.samples[2] - 1);
  return m.distance[(static_cast<std::size_t>(k) * m.samples[1] + j) * m.samples[0] + i];
}

// Trilinear interpolation of the grid at x and its gradient.
Real interpolate(const MeshObstacle& m, const Vec3& x, Vec3* gradient) {
  const Vec3 g = (x - m.grid_origin) / m.cell;
  std::array<int, 3> base{};
  Vec3 t;
  for (int a = 0; a < 3; ++a) {
    const Real clamped = std::clamp(g[a], Real(0), Real(m.samples[a] - 1) - 1e-9);
    base[a] = static_cast<int>(std::floor(clamped));
    t[a] = clamped - base[a];
  }
  Real c[2][2][2];
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di)
        c[dk][dj][di] = sample(m, base[0] + di, base[1] + dj, base[2] + dk);
  auto lerp = [](Real a, Real b, Real s) { return a + (b - a) * s; };
  const Real x00 = lerp(c[0][0][0], c[0][0][1], t[0]), x01 = lerp(c[0][1][0], c[0][1][1], t[0]);
  const Real x10 = lerp(c[1][0][0], c[1][0][1], t[0]), x11 = lerp(c[1][1][0], c[1][1][1], t[0]);
  const Real y0 = lerp(x00, x01, t[1]), y1 = lerp(x10, x11, t[1]);
  if (gradient != nullptr) {
    const Real dx0 = lerp(c[0][0][1] - c[0][0][0], c[0][1][1] - c[0][1][0], t[1]);
    const Real dx1 = lerp(c[1][0][1] - c[1][0][0], c[1][1][1] - c[1][1][0], t[1]);
    const Real dy0 = x01 - x00, dy1 = x11 - x10;
    *gradient = Vec3(lerp(dx0, dx1, t[2]), lerp(dy0, dy1, t[2]), y1 - y0) / m.cell;
  }
  return lerp(y0, y1, t[2]);
}

}  // namespace

Real mesh_exact_signed_distance(const MeshObstacle& m, const Vec3& x) {
  Real nearest = 1e300, winding = 0;
  for (const std::array<int, 3>& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    nearest = std::min(nearest, (x - closest_on_triangle(x, a, b, c)).squaredNorm());
    winding += solid_angle(x, a, b, c);
  }
  const bool inside = std::abs(winding) > 2 * std::numbers::pi;  // |w| > 1/2 of 4 pi
  return inside ? -std::sqrt(nearest) : std::sqrt(nearest);
}

std::shared_ptr<const MeshObstacle> load_mesh_obstacle(const std::string& path,
                                                       const Mat3& rotation, const Vec3& position,
                                                       Real scale) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (scene == nullptr) throw std::runtime_error(importer.GetErrorString());
  auto mesh = std::make_shared<MeshObstacle>();
  mesh->rotation = rotation;
  mesh->position = position;
  for (unsigned int mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* part = scene->mMeshes[mi];
    const int offset = static_cast<int>(mesh->vertices.size());
    for (unsigned int v = 0; v < part->mNumVertices; ++v) {
      const aiVector3D& p = part->mVertices[v];
      mesh->vertices.push_back(position + rotation * (scale * Vec3(p.x, p.y, p.z)));
    }
    for (unsigned int f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      mesh->triangles.push_back({offset + static_cast<int>(face.mIndices[0]),
                                 offset + static_cast<int>(face.mIndices[1]),
                                 offset + static_cast<int>(face.mIndices[2])});
    }
  }
  if (mesh->triangles.empty()) throw std::runtime_error("the file has no triangles");
  if (mesh->triangles.size() > kMaxTriangles) {
    throw std::runtime_error("more than " + std::to_string(kMaxTriangles) +
                             " triangles; simplify the mesh");
  }
  mesh->lower = mesh->upper = mesh->vertices[0];
  for (const Vec3& v : mesh->vertices) {
    mesh->lower = mesh->lower.cwiseMin(v);
    mesh->upper = mesh->upper.cwiseMax(v);
  }
  const Vec3 extent = mesh->upper - mesh->lower;
  const int cells =
      std::clamp(static_cast<int>(
                     std::cbrt(kMaxSampleTriangles / static_cast<double>(mesh->triangles.size()))),
                 8, kMaxCellsAlongLongestSide);
  mesh->cell = std::max(extent.maxCoeff(), Real(1e-6)) / cells;
  // Two cells of margin: nodes approaching the surface read a field that is not clamped.
  mesh->grid_origin = mesh->lower - Vec3::Constant(2 * mesh->cell);
  for (int a = 0; a < 3; ++a) {
    mesh->samples[a] = static_cast<int>(std::ceil(extent[a] / mesh->cell)) + 5;
  }
  mesh->distance.resize(static_cast<std::size_t>(mesh->samples[0]) * mesh->samples[1] *
                        mesh->samples[2]);
  std::size_t index = 0;
  for (int k = 0; k < mesh->samples[2]; ++k) {
    for (int j = 0; j < mesh->samples[1]; ++j) {
      for (int i = 0; i < mesh->samples[0]; ++i) {
        const Vec3 x = mesh->grid_origin + mesh->cell * Vec3(i, j, k);
        mesh->distance[index++] = mesh_exact_signed_distance(*mesh, x);
      }
    }
  }
  return mesh;
}

Real mesh_signed_distance(const MeshObstacle& m, const Vec3& x, Vec3& normal) {
  Vec3 gradient;
  Real d = interpolate(m, x, &gradient);
  // Outside the grid the field is clamped: add the distance to the grid's box.
  const Vec3 grid_upper =
      m.grid_origin + m.cell * Vec3(m.samples[0] - 1, m.samples[1] - 1, m.samples[2] - 1);
  const Vec3 beyond = (m.grid_origin - x).cwiseMax(x - grid_upper).cwiseMax(0.0);
  if (beyond.squaredNorm() > 0) {
    d += beyond.norm();
    const Vec3 centre = 0.5 * (m.grid_origin + grid_upper);
    gradient = (x - centre).normalized();
  }
  const Real length = gradient.norm();
  normal = length > 0 ? Vec3(gradient / length) : Vec3::UnitZ();
  return d;
}

}  // namespace pbm
