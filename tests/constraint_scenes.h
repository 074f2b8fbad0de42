// Small constrained scenes and measurements shared by the constraint tests (ch. 7): parts,
// constraint ends, the self-assembly scene, and |C| sampled per frame with its log-slope fit.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "scene_builders.h"
#include "sim/world.h"

namespace pbm::test::constraints {

inline BodyDef part(const std::string& name, DeformLevel level, const Vec3& position,
                    Real a0 = 0.2) {
  BodyDef b = test::ball(level, 4);
  b.name = name;
  b.q_s[0] = a0;
  b.q_s0 = b.q_s;
  b.position = position;
  test::set_uniform_mass(b, 1.0);
  return b;
}

inline ConstraintEndDef body_point(int body, const Vec3& p) {
  ConstraintEndDef end;
  end.body = body;
  end.point = p;
  return end;
}

inline ConstraintEndDef body_node(int body, int node) {
  ConstraintEndDef end;
  end.body = body;
  end.node = node;
  return end;
}

inline ConstraintEndDef world(const Vec3& x) {
  ConstraintEndDef end;
  end.world = x;
  return end;
}

inline ConstraintDef joint(const ConstraintEndDef& a, const ConstraintEndDef& b) {
  ConstraintDef c;
  c.name = "joint";
  c.a = a;
  c.b = b;
  return c;
}

inline void advance_to(Simulation& sim, Real t) {
  while (sim.state.time < t - 1e-12) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
  }
}

inline Real violation(Simulation& sim) {
  FrameStats stats;
  measure_state(sim.world, sim.inputs, sim.state, sim.ws, stats);
  return stats.constraint_violation;
}

// Two free parts whose joint starts 0.64 m open; nothing else acts. rk4: explicit Euler leaves a
// floor of |C| proportional to dt (2e-5 m at 1 ms, 2e-6 m at 0.1 ms here, with alpha = 5), where
// its O(dt^2) position error per step on the turning parts balances Baumgarte's feedback.
inline Scene assembly_scene(DynamicsOrder order, Real alpha) {
  Scene s;
  s.gravity = Vec3::Zero();
  s.solver.dt = 1e-3;
  s.solver.integrator =
      order == DynamicsOrder::second ? IntegratorKind::rk4 : IntegratorKind::euler;
  s.solver.fps = 50;
  s.solver.constraint_alpha = alpha;
  s.bodies.push_back(part("a", DeformLevel::rigid, Vec3(-0.5, 0, 0)));
  s.bodies.push_back(part("b", DeformLevel::rigid, Vec3(0.5, 0.2, 0.1)));
  for (BodyDef& b : s.bodies) {
    b.order = order;
    b.material.damping = order == DynamicsOrder::first ? 2.0 : 0.0;
  }
  s.constraints.push_back(joint(body_point(0, Vec3(0.2, 0, 0)), body_point(1, Vec3(-0.2, 0, 0))));
  return s;
}

// Fits ln |C| against t over [t0, t1] sampled each frame: the decay rate [1/s].
// Least-squares slope of -ln y(t) over samples (t, y).
inline Real log_decay_rate(const std::vector<std::pair<Real, Real>>& samples) {
  Real st = 0, sy = 0, stt = 0, sty = 0;
  const auto n = static_cast<Real>(samples.size());
  for (const auto& [t, value] : samples) {
    const Real y = std::log(value);
    st += t;
    sy += y;
    stt += t * t;
    sty += t * y;
  }
  return -(n * sty - st * sy) / (n * stt - st * st);
}

// |C| at every frame in [t0, t1).
inline std::vector<std::pair<Real, Real>> violation_samples(Simulation& sim, Real t0, Real t1) {
  advance_to(sim, t0);
  std::vector<std::pair<Real, Real>> samples;
  while (sim.state.time < t1 - 1e-12) {
    samples.emplace_back(sim.state.time, violation(sim));
    advance_to(sim, sim.state.time + 1.0 / sim.model.solver.fps);
  }
  return samples;
}

inline Real measured_decay_rate(Simulation& sim, Real t0, Real t1) {
  return log_decay_rate(violation_samples(sim, t0, t1));
}

// A rigid plank (1 x 0.2 x 0.05 m half-sizes, 1 kg) hinged to the world at its centre about y with
// a rotational spring of 50 N m/rad whose rest is 0.3 rad from the start, no gravity, rk4 at
// 1 ms: a torsional oscillator about the axis. The hinge is the scene's only constraint.
inline Scene hinged_plank_scene(Real fps) {
  Scene s;
  s.gravity = Vec3::Zero();
  s.solver.dt = 1e-3;
  s.solver.fps = fps;
  s.solver.integrator = IntegratorKind::rk4;
  BodyDef plank = part("plank", DeformLevel::rigid, Vec3(0, 0, 1), 1.0);
  plank.q_s[1] = 1.0;
  plank.q_s[2] = 0.2;
  plank.q_s[3] = 0.05;
  plank.q_s0 = plank.q_s;
  plank.material.damping = 0;
  s.bodies.push_back(plank);
  ConstraintDef hinge = joint(body_point(0, Vec3::Zero()), world(Vec3(0, 0, 1)));
  hinge.kind = ConstraintKind::hinge;
  hinge.axis = Vec3::UnitY();
  hinge.stiffness = 50;
  hinge.rest_angle = 0.3;
  s.constraints.push_back(hinge);
  return s;
}

// I_yy of a rigid body about its centre, from its lumped node masses (what the dynamics uses).
inline Real inertia_about_y(const BodyModel& b) {
  Real inertia = 0;
  for (int i = 0; i < b.n_nodes(); ++i) {
    const Vec3& p = b.s_fixed[i];
    inertia += b.node_mass[i] * (p.x() * p.x() + p.z() * p.z());
  }
  return inertia;
}

}  // namespace pbm::test::constraints
