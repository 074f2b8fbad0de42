#include "figure/segment_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/quaternion.h"

namespace pbm {

namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

// Bands of equal height on a sphere of radius r centred at `centre` between heights z0 < z1
// (relative to the centre, within [-r, r]), `bands` of them, each cut in `sectors`: a band's
// area is 2 pi r dz whatever its height (the hat-box theorem).
// The two-point Gauss rule's offsets from a band's middle, in band heights: exact for cubics.
constexpr Real kGauss[2] = {-0.28867513459481287, 0.28867513459481287};  // -+1 / (2 sqrt 3)

void sphere_zone(Real r, const Vec3& centre, Real z0, Real z1, int bands, int sectors,
                 std::vector<SurfacePatch>& out) {
  const Real dz = (z1 - z0) / bands;
  const Real area = kPi * r * dz / sectors;  // half a sector of the band: one Gauss point's
  for (int b = 0; b < bands; ++b) {
    for (const Real offset : kGauss) {
      const Real z = z0 + (b + 0.5 + offset) * dz;
      const Real ring = std::sqrt(std::max(Real(0), r * r - z * z));
      for (int s = 0; s < sectors; ++s) {
        const Real phi = (s + 0.5) * 2 * kPi / sectors;
        const Vec3 n(ring * std::cos(phi) / r, ring * std::sin(phi) / r, z / r);
        out.push_back({centre + r * n, area * n});
      }
    }
  }
}

// A cylinder's side of radius r between z0 < z1.
void cylinder_side(Real r, Real z0, Real z1, int rows, int sectors,
                   std::vector<SurfacePatch>& out) {
  const Real dz = (z1 - z0) / rows;
  const Real area = kPi * r * dz / sectors;
  for (int k = 0; k < rows; ++k) {
    for (const Real offset : kGauss) {
      const Real z = z0 + (k + 0.5 + offset) * dz;
      for (int s = 0; s < sectors; ++s) {
        const Real phi = (s + 0.5) * 2 * kPi / sectors;
        const Vec3 n(std::cos(phi), std::sin(phi), 0);
        out.push_back({Vec3(r * n.x(), r * n.y(), z), area * n});
      }
    }
  }
}

// A disc of radius r at height z facing `side` (+1 or -1) along z, in rings of equal area.
void disc(Real r, Real z, Real side, int rings, int sectors, std::vector<SurfacePatch>& out) {
  const Real area = kPi * r * r / (rings * sectors);
  for (int k = 0; k < rings; ++k) {
    // The radius halving the ring's area: its area's centre along the radius, near enough.
    const Real rho = r * std::sqrt((k + 0.5) / rings);
    for (int s = 0; s < sectors; ++s) {
      const Real phi = (s + 0.5) * 2 * kPi / sectors;
      out.push_back({Vec3(rho * std::cos(phi), rho * std::sin(phi), z), Vec3(0, 0, side * area)});
    }
  }
}

// The face of a box of half extents `half` whose outward normal is +-axis a, in n x n squares.
void box_face(const Vec3& half, int a, Real side, int n, std::vector<SurfacePatch>& out) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const Real area = 4 * half[b] * half[c] / (n * n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      Vec3 x;
      x[a] = side * half[a];
      x[b] = half[b] * (-1 + (2 * i + 1.0) / n);
      x[c] = half[c] * (-1 + (2 * j + 1.0) / n);
      Vec3 an = Vec3::Zero();
      an[a] = side * area;
      out.push_back({x, an});
    }
  }
}

}  // namespace

void segment_surface_patches(const SegmentShapeDef& shape, int divisions,
                             std::vector<SurfacePatch>& patches) {
  patches.clear();
  const int n = std::max(1, divisions);
  const int sectors = 4 * n;
  const Real r = shape.size.x(), h = shape.size.z();
  // Rows along a straight side about as long as a sector is wide.
  const auto rows = [&](Real length) {
    const Real width = 2 * kPi * r / sectors;
    return std::clamp(static_cast<int>(std::ceil(length / width)), 1, 64 * n);
  };
  switch (shape.kind) {
    case SegmentShapeKind::box:
      for (int a = 0; a < 3; ++a) {
        box_face(shape.size, a, 1, n, patches);
        box_face(shape.size, a, -1, n, patches);
      }
      break;
    case SegmentShapeKind::sphere:
      sphere_zone(r, Vec3::Zero(), -r, r, 2 * n, sectors, patches);
      break;
    case SegmentShapeKind::cylinder:
      cylinder_side(r, -h, h, rows(2 * h), sectors, patches);
      disc(r, h, 1, n, sectors, patches);
      disc(r, -h, -1, n, sectors, patches);
      break;
    case SegmentShapeKind::capsule:
      cylinder_side(r, -h, h, rows(2 * h), sectors, patches);
      sphere_zone(r, Vec3(0, 0, h), 0, r, n, sectors, patches);
      sphere_zone(r, Vec3(0, 0, -h), -r, 0, n, sectors, patches);
      break;
  }
  const Mat3 R = rotation_from_quaternion(shape.orientation);  // shape -> segment axes
  for (SurfacePatch& p : patches) {
    p.point = shape.center + R * p.point;
    p.area_normal = R * p.area_normal;
  }
}

}  // namespace pbm
