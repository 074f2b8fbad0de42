#include "figure/figure_build.h"

#include <cmath>
#include <numbers>
#include <unordered_map>

#include "core/error.h"
#include "core/quaternion.h"
#include "figure/figure_controllers.h"
#include "figure/mocap_retarget.h"

namespace pbm {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

bool finite(const Vec3& v) {
  return v.allFinite();
}

// A direction from the file: any nonzero finite length, normalized.
Vec3 unit_axis(const Vec3& axis, const std::string& file, const std::string& path) {
  const Real length = axis.norm();
  if (!std::isfinite(length) || !(length > 1e-12)) {
    throw Error(file, path, "must be a nonzero finite vector");
  }
  return axis / length;
}

Mat3 rotation_of(const Vec4& q, const std::string& file, const std::string& path) {
  if (!q.allFinite() || !(q.norm() > 1e-12)) {
    throw Error(file, path, "must be a nonzero finite quaternion (w, x, y, z)");
  }
  return rotation_from_quaternion(q);
}

}  // namespace

Real shape_volume(const SegmentShapeDef& shape) {
  const Real r = shape.size.x();
  switch (shape.kind) {
    case SegmentShapeKind::box:
      return 8 * shape.size.prod();
    case SegmentShapeKind::sphere:
      return 4.0 / 3.0 * kPi * r * r * r;
    case SegmentShapeKind::cylinder:
      return kPi * r * r * 2 * shape.size.z();
    case SegmentShapeKind::capsule:
      return kPi * r * r * 2 * shape.size.z() + 4.0 / 3.0 * kPi * r * r * r;
  }
  return 0;
}

Mat3 shape_inertia(const SegmentShapeDef& shape, Real m) {
  const Real r = shape.size.x(), r2 = r * r;
  switch (shape.kind) {
    case SegmentShapeKind::box:
      return solid_box_inertia(m, shape.size).I_c;
    case SegmentShapeKind::sphere:
      return solid_sphere_inertia(m, r).I_c;
    case SegmentShapeKind::cylinder:
      return solid_cylinder_inertia(m, r, 2 * shape.size.z()).I_c;
    case SegmentShapeKind::capsule: {
      // The straight part and the two hemispheres share m by volume; each hemisphere has 2/5 m r^2
      // about a diameter of its base, and its centre 3 r / 8 from the base.
      const Real L = 2 * shape.size.z();
      const Real v_cylinder = kPi * r2 * L, v_sphere = 4.0 / 3.0 * kPi * r2 * r;
      const Real m_c = m * v_cylinder / (v_cylinder + v_sphere), m_s = m - m_c;
      const Real across =
          m_c * (3 * r2 + L * L) / 12 + m_s * (0.4 * r2 + L * L / 4 + 3 * L * r / 8);
      return Vec3(across, across, m_c * r2 / 2 + m_s * 0.4 * r2).asDiagonal();
    }
  }
  return Mat3::Zero();
}

namespace {

// CompiledFigure::self_pairs: every pair of segments but a segment with itself, its parent or its
// children (they touch at their joint by design) and the pairs named in non_colliding.
std::vector<std::uint8_t> self_collision_pairs(const FigureDef& def, const FigureModel& figure,
                                               const std::unordered_map<std::string, int>& index,
                                               const std::string& file, const std::string& path) {
  const int n = figure.size();
  std::vector<std::uint8_t> pairs(static_cast<std::size_t>(n * n), def.self_collisions ? 1 : 0);
  const auto clear = [&](int a, int b) { pairs[a * n + b] = pairs[b * n + a] = 0; };
  for (int i = 0; i < n; ++i) {
    clear(i, i);
    if (figure.segments[i].parent >= 0) clear(i, figure.segments[i].parent);
  }
  for (std::size_t k = 0; k < def.non_colliding.size(); ++k) {
    const std::string at = path + ".non_colliding[" + std::to_string(k) + "]";
    const auto find = [&](const std::string& name, const char* key) {
      const auto found = index.find(name);
      if (found == index.end())
        throw Error(file, at + "." + key, "no segment is named '" + name + "'");
      return found->second;
    };
    const int a = find(def.non_colliding[k].a, "a"), b = find(def.non_colliding[k].b, "b");
    if (a == b) throw Error(file, at + ".b", "names the same segment as a");
    clear(a, b);
  }
  if (!(std::isfinite(def.friction) && def.friction >= 0))
    throw Error(file, path + ".friction", "must be finite and >= 0");
  return pairs;
}

}  // namespace

CompiledFigure build_figure_model(const FigureDef& def, const std::string& file,
                                  const std::string& path) {
  CompiledFigure out;
  FigureModel& figure = out.model;
  figure.name = def.name;
  const int n = static_cast<int>(def.segments.size());
  if (n == 0) throw Error(file, path + ".segments", "a figure needs at least one segment");
  std::unordered_map<std::string, int> index;
  for (int i = 0; i < n; ++i) {
    const std::string at = path + ".segments[" + std::to_string(i) + "]";
    if (!index.emplace(def.segments[i].name, i).second) {
      throw Error(file, at + ".name", "'" + def.segments[i].name + "' names an earlier segment");
    }
  }
  for (int i = 0; i < n; ++i) {
    const SegmentDef& d = def.segments[i];
    const std::string at = path + ".segments[" + std::to_string(i) + "]";
    SegmentModel s;
    s.name = d.name;
    if (!d.parent.empty()) {
      const auto found = index.find(d.parent);
      if (found == index.end()) {
        throw Error(file, at + ".parent", "no segment is named '" + d.parent + "'");
      }
      // Follow the parents up: a chain that comes back here is a cycle; one that reaches a root
      // only through later segments is a tree listed out of order.
      int j = found->second;
      for (int steps = 0; j >= 0 && steps <= n; ++steps) {
        if (j == i)
          throw Error(file, at + ".parent", "the parents form a cycle through '" + d.name + "'");
        const std::string& up = def.segments[j].parent;
        j = up.empty() ? -1 : (index.count(up) ? index.at(up) : -1);
      }
      if (found->second > i) {
        throw Error(file, at + ".parent",
                    "'" + d.parent + "' must come before its child in the list");
      }
      s.parent = found->second;
    }
    // The joint frame on the parent: X_tree = joint_X_parent = (R^T, position).
    const JointDef& jd = d.joint;
    if (!finite(jd.position)) throw Error(file, at + ".joint.position", "must be finite");
    s.X_tree = SpatialTransform{
        rotation_of(jd.orientation, file, at + ".joint.orientation").transpose(), jd.position};
    s.joint.kind = jd.kind;
    const bool has_axis = jd.kind == JointKind::revolute || jd.kind == JointKind::prismatic ||
                          jd.kind == JointKind::universal;
    if (has_axis) s.joint.axis = unit_axis(jd.axis, file, at + ".joint.axis");
    if (jd.kind == JointKind::universal) {
      s.joint.axis2 = unit_axis(jd.axis2, file, at + ".joint.axis2");
    }
    if (!(jd.damping >= 0) || !std::isfinite(jd.damping)) {
      throw Error(file, at + ".joint.damping", "must be finite and >= 0");
    }
    s.damping = jd.damping;
    if (!(jd.stiffness >= 0) || !std::isfinite(jd.stiffness)) {
      throw Error(file, at + ".joint.stiffness", "must be finite and >= 0");
    }
    const bool sprung = has_axis || jd.kind == JointKind::spherical;
    if (jd.stiffness > 0 && !sprung) {
      throw Error(file, at + ".joint.stiffness", "a fixed or free joint has no spring");
    }
    s.stiffness = jd.stiffness;
    s.rest = jd.kind == JointKind::spherical ? Vec4(1, 0, 0, 0) : Vec4::Zero();
    if (!jd.rest.empty()) {
      const int n_rest = jd.kind == JointKind::spherical ? 4 : joint_v_size(jd.kind);
      if (!sprung || static_cast<int>(jd.rest.size()) != n_rest) {
        throw Error(file, at + ".joint.rest",
                    sprung ? "needs " + std::to_string(n_rest) + " numbers for this joint"
                           : std::string("a fixed or free joint has no spring"));
      }
      for (int k = 0; k < n_rest; ++k) s.rest[k] = jd.rest[k];
      if (!s.rest.allFinite()) throw Error(file, at + ".joint.rest", "must be finite");
      if (jd.kind == JointKind::spherical) {
        if (!(s.rest.norm() > 1e-12)) {
          throw Error(file, at + ".joint.rest", "the quaternion must be nonzero");
        }
        s.rest.normalize();
      }
    }
    // Mass and inertia from the geometry: the shape's inertia turned into the segment's axes.
    const SegmentShapeDef& shape = d.shape;
    if (!finite(shape.size) || !(shape.size.x() > 0) ||
        (shape.kind == SegmentShapeKind::box && !(shape.size.minCoeff() > 0)) ||
        ((shape.kind == SegmentShapeKind::cylinder || shape.kind == SegmentShapeKind::capsule) &&
         !(shape.size.z() > 0))) {
      throw Error(file, at + ".shape.size", "the shape's dimensions must be positive and finite");
    }
    if (!finite(shape.center)) throw Error(file, at + ".shape.center", "must be finite");
    const Real mass = d.mass > 0 ? d.mass : d.density * shape_volume(shape);
    if (!std::isfinite(d.mass) || d.mass < 0 || !(mass > 0) || !std::isfinite(mass)) {
      throw Error(file, at + (d.mass != 0 ? ".mass" : ".density"),
                  "the segment's mass must be positive and finite (mass, or density times the "
                  "shape's volume)");
    }
    const Mat3 R = rotation_of(shape.orientation, file, at + ".shape.orientation");
    s.inertia = SpatialInertia{mass, shape.center, R * shape_inertia(shape, mass) * R.transpose()};
    figure.segments.push_back(s);
  }
  finalize_figure_model(figure, file, path + ".segments");
  // Initial state: at rest unless q0 / v0 say otherwise, quaternions normalized.
  out.q0.resize(figure.n_q);
  out.v0.setZero(figure.n_v);
  figure_neutral_q(figure, out.q0.data());
  for (int i = 0; i < n; ++i) {
    const JointDef& jd = def.segments[i].joint;
    const SegmentModel& s = figure.segments[i];
    const std::string at = path + ".segments[" + std::to_string(i) + "].joint";
    const int n_q = joint_q_size(jd.kind), n_v = joint_v_size(jd.kind);
    if (!jd.q0.empty()) {
      if (static_cast<int>(jd.q0.size()) != n_q) {
        throw Error(file, at + ".q0", "needs " + std::to_string(n_q) + " numbers for this joint");
      }
      for (int k = 0; k < n_q; ++k) out.q0[s.q_offset + k] = jd.q0[k];
      if (!out.q0.segment(s.q_offset, n_q).allFinite())
        throw Error(file, at + ".q0", "must be finite");
      const bool quaternion = jd.kind == JointKind::spherical || jd.kind == JointKind::free;
      if (quaternion && !(out.q0.segment<4>(s.q_offset + n_q - 4).norm() > 1e-12)) {
        throw Error(file, at + ".q0", "the quaternion must be nonzero");
      }
    }
    if (!jd.v0.empty()) {
      if (static_cast<int>(jd.v0.size()) != n_v) {
        throw Error(file, at + ".v0", "needs " + std::to_string(n_v) + " numbers for this joint");
      }
      for (int k = 0; k < n_v; ++k) out.v0[s.v_offset + k] = jd.v0[k];
      if (!out.v0.segment(s.v_offset, n_v).allFinite())
        throw Error(file, at + ".v0", "must be finite");
    }
  }
  figure_normalize(figure, out.q0.data());
  out.self_pairs = self_collision_pairs(def, figure, index, file, path);
  out.limits = compile_joint_limits(def, figure, file, path);
  for (const JointLimit& l : out.limits) {
    const Real q = limit_coordinate(l, out.q0.data());
    if (q < l.lower || q > l.upper) {
      throw Error(file,
                  path + ".segments[" + std::to_string(l.segment) + "].joint." +
                      (def.segments[l.segment].joint.q0.empty() ? "lower" : "q0"),
                  l.swing ? "the initial swing " + std::to_string(q) + " rad is outside swing_limit"
                  : l.twist
                      ? "the initial twist " + std::to_string(q) + " rad is outside twist_limit"
                      : "the initial position " + std::to_string(q) + " is outside [lower, upper]");
    }
  }
  if (!def.mocap) {
    out.controllers = compile_figure_controllers(def, figure, file, path);
    out.site_actuators = compile_site_actuators(def, figure, file, path);
  } else {
    // The clip's servos and site actuators after the scene's own (retarget_mocap refuses what
    // would clash with them, at the mocap's keys).
    const MocapClip clip = load_figure_mocap(*def.mocap, file, path);
    MocapTracks tracks = retarget_mocap(def, figure, clip, file, path);
    FigureDef driven = def;
    for (ControllerDef& c : tracks.controllers) driven.controllers.push_back(std::move(c));
    for (SiteActuatorDef& a : tracks.site_actuators) driven.site_actuators.push_back(std::move(a));
    out.controllers = compile_figure_controllers(driven, figure, file, path);
    out.site_actuators = compile_site_actuators(driven, figure, file, path);
  }
  out.impulses = compile_impulses(def, figure, file, path);
  out.n_control = controller_state_size(out.controllers);
  // Without controllers, the work entry alone when site actuators or impulses put energy in.
  if (out.n_control == 0 && (!out.site_actuators.empty() || !out.impulses.empty())) {
    out.n_control = 1;
  }
  explicit_joint_force_limit(out);
  return out;
}

}  // namespace pbm
