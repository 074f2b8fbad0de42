#include "constrain/constraint_model.h"

#include <algorithm>
#include <numeric>
#include <set>
#include <utility>

#include "core/error.h"
#include "core/quaternion.h"

namespace pbm {
namespace {

// Above these alpha dt the stabilizing terms of (7.14) dominate a step of the explicit
// integrator (sec. 7.2's caveat): Euler's error per step in e^(-alpha dt) passes ~10 % at 0.5;
// rk4 follows the exponential closely to about 1.
constexpr Real kStiffGainEuler = 0.5;
constexpr Real kStiffGainRungeKutta = 1.0;

ConstraintPoint compile_end(const std::string& file, std::span<const BodyModel> bodies,
                            const ConstraintEndDef& def, const std::string& path) {
  ConstraintPoint end;
  if (def.body < 0) {
    end.point = def.world;
    return end;
  }
  if (def.body >= static_cast<int>(bodies.size())) {
    throw Error(file, path + ".body", "no such body");
  }
  end.body = def.body;
  const BodyModel& body = bodies[def.body];
  if (def.point) {
    end.point = *def.point;
  } else if (def.node >= 0) {
    if (def.node >= body.n_nodes()) throw Error(file, path + ".node", "no such node");
    end.node = def.node;
  } else if (def.material_point) {
    end.node = nearest_node(body.tessellation, *def.material_point);
  } else {
    throw Error(file, path, "needs node, material_point or point");
  }
  return end;
}

Mat3 initial_rotation(std::span<const BodyDef> body_defs, int body) {
  return body < 0 ? Mat3::Identity()
                  : rotation_from_quaternion(body_defs[static_cast<std::size_t>(body)].orientation);
}

// Union-find over bodies: a constraint joining two bodies already connected (other than through
// a constraint between the same pair, as a hinge's two points are) closes a loop, and then N's
// sparsity is no longer that of a tree.
int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

ConstraintSystemModel build_constraints(std::span<const ConstraintDef> defs,
                                        std::span<const BodyDef> body_defs,
                                        std::span<const BodyModel> bodies,
                                        const ConstraintSettings& settings,
                                        const std::string& file) {
  ConstraintSystemModel system;
  system.solver = settings.solver;
  const Real alpha_default = settings.alpha;
  const Real beta_default = settings.beta.value_or(alpha_default);
  for (std::size_t c = 0; c < defs.size(); ++c) {
    const ConstraintDef& def = defs[c];
    const std::string path = "constraints[" + std::to_string(c) + "]";
    PointConstraintModel point;
    point.name = def.name;
    point.source = static_cast<int>(c);
    point.alpha = def.alpha.value_or(alpha_default);
    point.beta = def.beta.value_or(def.alpha ? point.alpha : beta_default);
    point.ends[0] = compile_end(file, bodies, def.a, path + ".a");
    point.ends[1] = compile_end(file, bodies, def.b, path + ".b");
    if (point.ends[0].body < 0) throw Error(file, path + ".a", "must be a body point");
    for (const ConstraintPoint& end : point.ends) {
      if (end.body >= 0 && bodies[end.body].order != bodies[point.ends[0].body].order) {
        throw Error(file, path + ".b.body",
                    "both bodies of a constraint need the same dynamics order (the first-order "
                    "model (7.4) constrains velocities, the second-order model (7.3) "
                    "accelerations)");
      }
    }
    if (def.kind == ConstraintKind::point) {
      system.points.push_back(point);
      continue;
    }
    // Hinge: the axis through each end's point, in that end's frame at the initial state.
    const Mat3 R_a = initial_rotation(body_defs, def.a.body);
    const Mat3 R_b = initial_rotation(body_defs, def.b.body);
    const Vec3 axis_a = R_a.transpose() * def.axis;
    const Vec3 axis_b = R_b.transpose() * def.axis;
    const Real h = 0.5 * def.length;
    for (const Real side : {-1.0, 1.0}) {
      PointConstraintModel on_axis = point;
      on_axis.ends[0].point += side * h * axis_a;
      on_axis.ends[1].point += side * h * axis_b;
      system.points.push_back(on_axis);
    }
    HingeSpringModel spring;
    spring.name = def.name;
    spring.body_a = def.a.body;
    spring.body_b = def.b.body;
    spring.axis_a = axis_a;
    const Vec3 e = def.axis.unitOrthogonal();
    spring.reference_a = R_a.transpose() * e;
    spring.reference_b = R_b.transpose() * e;
    spring.stiffness = def.stiffness;
    spring.rest_angle = def.rest_angle;
    spring.damping = def.damping;
    system.hinges.push_back(spring);
  }

  std::vector<int> parent(bodies.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::set<std::pair<int, int>> joined;
  for (const PointConstraintModel& point : system.points) {
    const int a = point.ends[0].body, b = point.ends[1].body;
    if (b < 0 || a == b) continue;
    if (!joined.insert({std::min(a, b), std::max(a, b)}).second) continue;
    const int ra = find_root(parent, a), rb = find_root(parent, b);
    if (ra == rb && !system.has_loop) {
      system.has_loop = true;
      if (system.solver == ConstraintSolverKind::sparse) {
        system.solver = ConstraintSolverKind::dense;
        system.notes.push_back("constraint '" + point.name +
                               "' closes a loop: using the dense solver instead of the sparse one");
      }
    }
    parent[ra] = rb;
  }

  // The implicit integrator advances constraints with Euler's update (integrate/integrators.h).
  const bool euler = settings.integrator == IntegratorKind::euler ||
                     settings.integrator == IntegratorKind::implicit;
  const Real limit = euler ? kStiffGainEuler : kStiffGainRungeKutta;
  for (const PointConstraintModel& point : system.points) {
    const Real gain = std::max(point.alpha, point.beta) * settings.dt;
    if (gain > limit) {
      system.notes.push_back("constraint '" + point.name + "': alpha dt = " + std::to_string(gain) +
                             " > " + std::to_string(limit) + " is stiff for the " +
                             (euler ? "euler" : "runge-kutta") +
                             " integrator (sec. 7.2): lower alpha or dt");
      break;
    }
  }
  return system;
}

}  // namespace pbm
