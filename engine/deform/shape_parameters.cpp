#include "deform/shape_parameters.h"

#include <cmath>

#include "deform/axis_deformations.h"

namespace pbm {
namespace {

enum class ParameterRange { positive, unit_interval, unit_range, finite };

ParameterRange parameter_range(ShapeKind kind, int index) {
  if (index < 6) return ParameterRange::positive;  // a0..a3, eps1, eps2
  if (kind == ShapeKind::taper_bend) {
    switch (index) {
      case 6:  // t1
      case 7:  // t2
      case 9:  // b2
        return ParameterRange::unit_interval;
      case 10:  // b3
        return ParameterRange::unit_range;
      default:  // b1
        return ParameterRange::finite;
    }
  }
  if (index >= bend_range_index(1, 2)) return ParameterRange::unit_range;
  if (index >= bend_location_index(1, 2)) return ParameterRange::unit_interval;
  if (index >= taper_index(1, 2) && index < shear_index(1, 2)) return ParameterRange::unit_interval;
  return ParameterRange::finite;  // twists, shears, bend amounts
}

// "1^2" for the pair at position 0..5 of (2.27).
std::string pair_suffix(int position) {
  constexpr int kI[6] = {1, 1, 2, 2, 3, 3};
  constexpr int kJ[6] = {2, 3, 1, 3, 1, 2};
  return std::to_string(kI[position]) + "^" + std::to_string(kJ[position]);
}

}  // namespace

int shape_parameter_count(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::superquadric:
      return 6;
    case ShapeKind::taper_bend:
      return 11;
    case ShapeKind::general:
      return kAxisDeformationParameterCount;
  }
  return 0;
}

VecX default_shape_parameters(ShapeKind kind) {
  VecX q_s = VecX::Zero(shape_parameter_count(kind));
  q_s.head<6>().setOnes();
  if (kind == ShapeKind::taper_bend) q_s(10) = 1;           // b3
  if (kind == ShapeKind::general) q_s.tail<6>().setOnes();  // b^{rj}_i
  return q_s;
}

std::string shape_parameter_name(ShapeKind kind, int index) {
  constexpr const char* kSuperquadric[6] = {"a0", "a1", "a2", "a3", "eps1", "eps2"};
  constexpr const char* kTaperBend[5] = {"t1", "t2", "b1", "b2", "b3"};
  constexpr const char* kGeneralGroups[5] = {"t", "s", "ba", "bl", "br"};
  if (index < 0 || index >= shape_parameter_count(kind)) return "?";
  if (index < 6) return kSuperquadric[index];
  if (kind == ShapeKind::taper_bend) return kTaperBend[index - 6];
  if (index < 9) return "tau" + std::to_string(index - 5);
  const int group = (index - 9) / 6, position = (index - 9) % 6;
  return kGeneralGroups[group] + pair_suffix(position);
}

std::string check_shape_parameter(ShapeKind kind, int index, Real value) {
  if (index < 0 || index >= shape_parameter_count(kind)) {
    return "index out of range (" + std::to_string(shape_parameter_count(kind)) + " parameters)";
  }
  if (!std::isfinite(value)) return "must be finite";
  switch (parameter_range(kind, index)) {
    case ParameterRange::positive:
      return value > 0 ? "" : "must be > 0";
    case ParameterRange::unit_interval:
      return (value >= -1 && value <= 1) ? "" : "must be in [-1, 1]";
    case ParameterRange::unit_range:
      return (value > 0 && value <= 1) ? "" : "must be in (0, 1]";
    case ParameterRange::finite:
      return "";
  }
  return "";
}

}  // namespace pbm
