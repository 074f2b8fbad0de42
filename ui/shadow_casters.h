#pragma once
// A coarse copy of a dense body mesh for the shadow pass. A shadow map of 1024² texels cannot
// resolve more than a few thousand triangles of one body, yet on a software rasterizer every
// triangle of the shadow pass costs setup and binning. Vertex clustering merges the vertices
// that fall in one cell of a uniform grid into one of them, so the coarse mesh indexes the same
// vertex buffer and follows the deformation frame by frame with no extra upload.
#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace pbm {

// Triangles of `triangles` (indices into `positions`) with vertices merged by clusters so that at
// most about `max_triangles` remain; the input itself when it has no more than that. Merged
// triangles that collapse or repeat are dropped. Deterministic.
std::vector<std::array<int, 3>> shadow_caster_triangles(
    const std::vector<Eigen::Vector3f>& positions, const std::vector<std::array<int, 3>>& triangles,
    std::size_t max_triangles);

}  // namespace pbm
