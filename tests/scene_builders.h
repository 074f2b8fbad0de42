// Small scenes built in code for the physics tests.
#pragma once

#include "deform/reference_shape.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace pbm::test {

// `mass` kg the same on every node, as the book lumps it, whatever the tessellation: what these
// tests were measured with before a total mass was spread by area (deform/body_def.h).
inline void set_uniform_mass(BodyDef& b, Real mass) {
  b.material.mass = 0;
  b.material.density = 0;
  b.material.nodal_mass = mass / (2 + b.tessellation.rings * b.tessellation.segments);
}

inline BodyDef ball(DeformLevel level, int resolution = 8) {
  BodyDef b;
  b.name = "ball";
  b.level = level;
  b.shape = ShapeKind::superquadric;
  b.q_s = default_shape_parameters(b.shape);
  b.q_s0 = b.q_s;
  b.k_s = VecX::Constant(b.q_s.size(), 2000.0);
  b.tessellation.kind = TessellationKind::triangles;
  b.tessellation.rings = resolution;
  b.tessellation.segments = resolution;
  b.material.w0 = 20;
  b.material.w1 = 15;
  // 10 kg, the same on every node (the book's lumping): the mass the tests built on this ball
  // were measured with. A total mass would be spread by area (deform/body_def.h).
  set_uniform_mass(b, 10.0);
  b.material.damping = 0;
  return b;
}

inline Scene free_space(BodyDef body) {
  Scene s;
  s.name = "test";
  s.gravity = Vec3::Zero();
  s.bodies.push_back(std::move(body));
  return s;
}

// The engine's one setup path (sim/simulation.h): model, world, workspace, state, inputs.
using pbm::Simulation;

}  // namespace pbm::test
