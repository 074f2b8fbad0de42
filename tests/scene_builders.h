// Small scenes built in code for the physics tests.
#pragma once

#include "deform/reference_shape.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace pbm::test {

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
  b.material.nodal_mass = 0;
  b.material.mass = 10;
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
