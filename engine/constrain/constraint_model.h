// The constraints of a scene compiled for the solver (ch. 7): point-to-point constraints between
// body points or to world anchors (7.1)-(7.2), with their Baumgarte gains (7.14), and the
// rotational springs of hinges (sec. 6.4's spring-loaded see-saw). Part of the Model: constant
// while time runs.
//
// A hinge is two point constraints a `length` apart on its axis plus a HingeSpring. Its two
// points make N singular along the axis (equal and opposite axial forces at two points of the
// axis do no work), which the solver's small regularization handles (constraint_forces.h).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "constrain/constraint_def.h"
#include "core/types.h"
#include "deform/body_def.h"
#include "deform/body_model.h"
#include "integrate/integrators.h"

namespace pbm {

// One end of a constraint.
//   body < 0:   a world anchor, x = point (world frame)
//   node >= 0:  node `node` of the body, x = c + R (s + d) (3.3)
//   otherwise:  a point fixed in the body frame, x = c + R point
struct ConstraintPoint {
  int body = -1;
  int node = -1;
  Vec3 point = Vec3::Zero();
};

// C = x_a - x_b (7.21). End a is "one", end b is "two" in the algorithm of sec. 7.3.2.
struct PointConstraintModel {
  std::string name;  // the scene constraint's name (a hinge's two points share it)
  int source = 0;    // index into Scene::constraints
  std::array<ConstraintPoint, 2> ends;
  Real alpha = 0, beta = 0;  // Baumgarte gains of (7.14) [1/s]
};

// Rotational spring about a hinge axis, E = 1/2 k (theta - theta_0)^2, the form of the global
// stiffness energy 1/2 (q_s - q_s0)^T K_ss (q_s - q_s0) (3.31), sec. 6.4. theta is the angle of
// body a about the axis relative to body b (or the world), 0 at the initial state.
struct HingeSpringModel {
  std::string name;
  int body_a = 0, body_b = -1;       // body_b < 0: the world
  Vec3 axis_a = Vec3::UnitY();       // the axis in body a's frame
  Vec3 reference_a = Vec3::UnitX();  // a unit vector normal to the axis, body a's frame
  Vec3 reference_b = Vec3::UnitX();  // the same vector in body b's frame (or the world)
  Real stiffness = 0;                // k [N m/rad]
  Real rest_angle = 0;               // theta_0 [rad]
  Real damping = 0;                  // [N m s/rad], on the relative angular velocity
};

struct ConstraintSystemModel {
  std::vector<PointConstraintModel> points;
  std::vector<HingeSpringModel> hinges;
  ConstraintSolverKind solver = ConstraintSolverKind::dense;  // what runs (after the loop check)
  bool has_loop = false;  // the body graph of the constraints has a cycle
  // Notes for the stats panel and the CLI: a loop's fallback to the dense solver, Baumgarte gains
  // too stiff for the integrator's step.
  std::vector<std::string> notes;
  bool empty() const { return points.empty() && hinges.empty(); }
};

// What the constraint stages read: the constraints and the bodies they join (the Model's).
struct ConstrainedSystem {
  const ConstraintSystemModel& constraints;
  std::span<const BodyModel> bodies;
};

// The solver's settings a constraint system is compiled with (the scene's "solver" section).
struct ConstraintSettings {
  Real alpha = 10;           // default Baumgarte alpha [1/s]
  std::optional<Real> beta;  // default beta [1/s]; absent: alpha (7.16)
  ConstraintSolverKind solver = ConstraintSolverKind::dense;
  IntegratorKind integrator = IntegratorKind::euler;  // for the stiff-gain note
  Real dt = 0.001;                                    // substep [s], likewise
};

// Compiles the constraint definitions against the already built bodies (their definitions give
// the initial orientations hinge axes are measured in): resolves material points to nodes,
// splits hinges, picks the gains (per constraint, else the settings'; beta defaults to alpha),
// detects loops. Throws pbm::Error (file, "constraints[i]...") on what the parser cannot check.
ConstraintSystemModel build_constraints(std::span<const ConstraintDef> defs,
                                        std::span<const BodyDef> body_defs,
                                        std::span<const BodyModel> bodies,
                                        const ConstraintSettings& settings,
                                        const std::string& file);

}  // namespace pbm
