#include "shadow_casters.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace pbm {
namespace {

using Triangles = std::vector<std::array<int, 3>>;

// Each vertex mapped to the first vertex (lowest index) of its grid cell; cells of edge h.
Triangles cluster(const std::vector<Eigen::Vector3f>& p, const Triangles& triangles,
                  const Eigen::Vector3f& lo, float h) {
  std::map<std::array<long, 3>, int> representative;
  std::vector<int> to(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3f c = ((p[i] - lo) / h).array().floor();
    const std::array<long, 3> key{static_cast<long>(c.x()), static_cast<long>(c.y()),
                                  static_cast<long>(c.z())};
    to[i] = representative.emplace(key, static_cast<int>(i)).first->second;
  }
  Triangles out;
  std::set<std::array<int, 3>> seen;  // a triangle and its rotations count once
  for (const std::array<int, 3>& t : triangles) {
    const std::array<int, 3> m{to[t[0]], to[t[1]], to[t[2]]};
    if (m[0] == m[1] || m[1] == m[2] || m[0] == m[2]) continue;
    const int first = static_cast<int>(std::min_element(m.begin(), m.end()) - m.begin());
    const std::array<int, 3> key{m[first], m[(first + 1) % 3], m[(first + 2) % 3]};
    if (seen.insert(key).second) out.push_back(m);
  }
  return out;
}

}  // namespace

Triangles shadow_caster_triangles(const std::vector<Eigen::Vector3f>& positions,
                                  const Triangles& triangles, std::size_t max_triangles) {
  if (triangles.size() <= max_triangles || positions.empty()) return triangles;
  Eigen::Vector3f lo = positions.front(), hi = positions.front();
  for (const Eigen::Vector3f& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const float extent = (hi - lo).maxCoeff();
  if (!(extent > 0.0f)) return triangles;
  // A closed surface over G³ cells keeps about 2·(occupied cells) triangles; shrink G until the
  // budget holds. Each try is linear in the mesh, and this runs only when the topology changes.
  for (float cells = 4.0f * std::sqrt(static_cast<float>(max_triangles)); cells >= 2.0f;
       cells *= 0.8f) {
    Triangles coarse = cluster(positions, triangles, lo, extent / cells);
    if (coarse.size() <= max_triangles) return coarse;
  }
  return cluster(positions, triangles, lo, extent);
}

}  // namespace pbm
