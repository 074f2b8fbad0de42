#include "figure/figure_model.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/error.h"

namespace pbm {
namespace {

// Unit within rounding: axes come from files as three decimals, normalized by the reader.
constexpr Real kUnitTolerance = 1e-9;

bool unit(const Vec3& axis) {
  return std::abs(axis.norm() - 1) <= kUnitTolerance;
}

}  // namespace

void finalize_figure_model(FigureModel& figure, const std::string& file, const std::string& path) {
  int n_q = 0, n_v = 0;
  for (int i = 0; i < figure.size(); ++i) {
    SegmentModel& segment = figure.segments[i];
    const std::string at = path + "[" + std::to_string(i) + "]";
    if (segment.parent < -1 || segment.parent >= i) {
      throw Error(file, at + ".parent",
                  "the parent must be an earlier segment (or none, for a root): got " +
                      std::to_string(segment.parent));
    }
    const SpatialInertia& I = segment.inertia;
    if (!(I.m > 0) || !std::isfinite(I.m)) {
      throw Error(file, at + ".mass", "must be positive and finite, got " + std::to_string(I.m));
    }
    if (!I.c.allFinite() || !I.I_c.allFinite() ||
        (I.I_c - I.I_c.transpose()).norm() > 1e-9 * I.I_c.norm()) {
      throw Error(file, at + ".inertia", "must be a finite symmetric matrix");
    }
    // Positive definite: a segment with no rotational inertia about an axis would give the
    // articulated-body recursion a zero pivot where a joint turns it about that axis.
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(I.I_c, Eigen::EigenvaluesOnly);
    if (!(eigen.eigenvalues().minCoeff() > 0)) {
      throw Error(file, at + ".inertia",
                  "must be positive definite (smallest principal moment " +
                      std::to_string(eigen.eigenvalues().minCoeff()) + " kg m^2)");
    }
    const JointKind kind = segment.joint.kind;
    const bool has_axis =
        kind == JointKind::revolute || kind == JointKind::prismatic || kind == JointKind::universal;
    if (has_axis && !unit(segment.joint.axis)) {
      throw Error(file, at + ".joint.axis", "must be a unit vector");
    }
    if (kind == JointKind::universal &&
        (!unit(segment.joint.axis2) ||
         segment.joint.axis.cross(segment.joint.axis2).norm() < kUnitTolerance)) {
      throw Error(file, at + ".joint.axis2", "must be a unit vector not parallel to axis");
    }
    segment.q_offset = n_q;
    segment.v_offset = n_v;
    n_q += joint_q_size(kind);
    n_v += joint_v_size(kind);
  }
  figure.n_q = n_q;
  figure.n_v = n_v;
}

void figure_neutral_q(const FigureModel& figure, Real* q) {
  for (const SegmentModel& segment : figure.segments) {
    joint_neutral(segment.joint, q + segment.q_offset);
  }
}

void figure_q_dot(const FigureModel& figure, const Real* q, const Real* v, Real* q_dot) {
  for (const SegmentModel& segment : figure.segments) {
    joint_q_dot(segment.joint, q + segment.q_offset, v + segment.v_offset,
                q_dot + segment.q_offset);
  }
}

void figure_normalize(const FigureModel& figure, Real* q) {
  for (const SegmentModel& segment : figure.segments) {
    joint_normalize(segment.joint, q + segment.q_offset);
  }
}

}  // namespace pbm
