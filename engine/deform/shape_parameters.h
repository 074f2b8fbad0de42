// The closed set of reference-shape kinds and what every layer needs to know of their
// parameters q_s (count, defaults, names, valid ranges): the scene reader and writer, the studio's
// inspector and the body model. A low header: it includes nothing of the scene or the dynamics.
//   superquadric (2.7)-(2.9), 6 parameters; taper_bend (2.10)-(2.12), 11; general: taper, bend,
//   shear and twist along three axes T2(T1(T3(e))) (2.13)-(2.27), 39.
#pragma once

#include <string>

#include "core/types.h"

namespace pbm {

enum class ShapeKind { superquadric, taper_bend, general };

// n_s: 6 (2.8), 11 (2.11) or 39 (2.27).
int shape_parameter_count(ShapeKind kind);

// The unit sphere: a0 = a1 = a2 = a3 = 1, eps1 = eps2 = 1, deformations 0, bend ranges 1.
VecX default_shape_parameters(ShapeKind kind);

// "a0", ..., "eps2", then "t1", "t2", "b1", "b2", "b3" (taper_bend) or "tau1".."tau3", "t1^2",
// ..., "s1^2", ..., "ba1^2", ..., "bl1^2", ..., "br1^2", ... (general, pair order of (2.27)).
std::string shape_parameter_name(ShapeKind kind, int index);

// Empty if value is valid for q_s(index), else why not (e.g. "must be > 0"). a0, a1..a3, eps > 0
// (a_i > 1 allowed for elongated shapes, unlike the book's a_i <= 1); tapers and bend locations
// in [-1, 1]; bend ranges in (0, 1]; bend amounts, twists and shears any finite value.
std::string check_shape_parameter(ShapeKind kind, int index, Real value);

}  // namespace pbm
