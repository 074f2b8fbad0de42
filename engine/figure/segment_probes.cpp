#include "figure/segment_probes.h"

#include <cmath>
#include <numbers>

#include "core/quaternion.h"

namespace pbm {

int segment_probes(const SegmentShapeDef& shape, SegmentProbes& probes) {
  const Mat3 R = rotation_from_quaternion(shape.orientation);  // shape -> segment axes
  const Real r = shape.size.x(), h = shape.size.z();
  const auto put = [&](int k, const Vec3& local, Real radius) {
    probes[k] = {shape.center + R * local, radius};
  };
  switch (shape.kind) {
    case SegmentShapeKind::sphere:
      put(0, Vec3::Zero(), r);
      return 1;
    case SegmentShapeKind::capsule:
      put(0, Vec3(0, 0, h), r);
      put(1, Vec3(0, 0, -h), r);
      return 2;
    case SegmentShapeKind::box:
      for (int k = 0; k < 8; ++k) {
        put(k,
            Vec3((k & 1 ? 1 : -1) * shape.size.x(), (k & 2 ? 1 : -1) * shape.size.y(),
                 (k & 4 ? 1 : -1) * shape.size.z()),
            0);
      }
      return 8;
    case SegmentShapeKind::cylinder:
      for (int k = 0; k < 8; ++k) {
        const Real angle = k * std::numbers::pi_v<Real> / 4;
        const Vec3 rim(r * std::cos(angle), r * std::sin(angle), 0);
        put(k, rim + Vec3(0, 0, h), 0);
        put(8 + k, rim - Vec3(0, 0, h), 0);
      }
      return 16;
  }
  return 0;
}

}  // namespace pbm
