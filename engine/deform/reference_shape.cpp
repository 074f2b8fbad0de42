#include "deform/reference_shape.h"

#include <cassert>
#include <cmath>

#include "deform/axis_deformations.h"
#include "deform/superquadric.h"
#include "deform/taper_bend.h"

namespace pbm {

void evaluate_reference_shape(ShapeKind kind, const Eigen::Ref<const VecX>& q_s, Real u, Real v,
                              Real w, Vec3& s, Mat3X* J) {
  evaluate_reference_shape(kind, q_s, superquadric_angles(u, v), w, s, J);
}

void evaluate_reference_shape(ShapeKind kind, const Eigen::Ref<const VecX>& q_s,
                              const SuperquadricAngles& angles, Real w, Vec3& s, Mat3X* J) {
  assert(q_s.size() == shape_parameter_count(kind));
  assert(J == nullptr || (J->rows() == 3 && J->cols() == q_s.size()));
  switch (kind) {
    case ShapeKind::superquadric: {
      SuperquadricJacobian J_e;
      evaluate_superquadric(q_s, angles, w, s, J != nullptr ? &J_e : nullptr);
      if (J != nullptr) J->leftCols<6>() = J_e;
      return;
    }
    case ShapeKind::taper_bend: {
      TaperBendJacobian J_s;
      evaluate_taper_bend(q_s, angles, w, s, J != nullptr ? &J_s : nullptr);
      if (J != nullptr) J->leftCols<11>() = J_s;
      return;
    }
    case ShapeKind::general: {
      AxisDeformationJacobian J_s;
      evaluate_axis_deformations(q_s, angles, w, s, J != nullptr ? &J_s : nullptr);
      if (J != nullptr) J->leftCols<kAxisDeformationParameterCount>() = J_s;
      return;
    }
  }
}

}  // namespace pbm
