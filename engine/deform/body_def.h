// What a scene file says of deformable bodies and the loads on them (scenes/README.md, sections
// "bodies", "force_fields", "springs"): plain definitions with defaults, validated by the scene
// reader (scene/) and compiled into a BodyModel (deform/body_model.h). Data only.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "deform/shape_parameters.h"

namespace pbm {

// What a body pays for (docs/architecture.md): its DOF vector holds only these coordinates.
// q_c,q_theta | + q_s | + q_s, q_d | automatic: the state of `local`, its displacements switched
// on near contact or a drag and off (held at zero, run as `global`) elsewhere
// (sim/level_of_detail.h)
enum class DeformLevel { rigid, global, local, automatic };
// Tessellation of (u,v): quads + pole triangles (fig. 4.1) or all triangles (fig. 4.2).
enum class TessellationKind { quads, triangles };
// Where obstacles push on each surface triangle (5.11): three points (Strang-Fix's degree-2
// rule) or its centroid alone, a third of the contact's cost (deform/body_model.h).
enum class ContactQuadrature { three_point, centroid };
// Second-order Lagrangian model (3.13) for animation, first-order model (3.51) for shaping.
enum class DynamicsOrder { second, first };
enum class ForceFieldKind { acceleration, force_per_node };

struct TessellationDef {
  TessellationKind kind = TessellationKind::triangles;
  int rings = 16;     // interior latitude rings between the poles (>= 2)
  int segments = 16;  // nodes around each ring (>= 3); nodes = 2 + rings * segments
  ContactQuadrature contact = ContactQuadrature::three_point;
};

struct MaterialDef {
  Real w0 = 20.0;  // membrane magnitude stiffness w00 (3.34), >= 0
  Real w1 = 15.0;  // membrane variation stiffness w10 = w01 (3.34), >= 0
  // Exactly one of nodal_mass, mass, density is > 0. nodal_mass is the book's (sec. 6.1): the
  // body's mass grows with its node count. mass and density do not depend on the mesh: each node
  // carries the mass of its share of the initial surface (a third of its triangles' areas).
  Real nodal_mass = 0;  // lumped mass per node [kg]
  Real mass = 0;        // total mass [kg], spread over the nodes by area
  Real density = 0;     // areal density [kg/m^2] of the initial surface, spread by area
  // Contact stiffness per unit area [N/m^3], multiplied by the obstacle's elasticity: refining
  // the mesh keeps the pressure of a dent. 0: the book's (5.10)-(5.11), the nodes' K_ii per area,
  // which grows with the node count.
  Real contact_stiffness = 0;
  Real damping = 1.4;         // nu in D = nu M (sec. 6.1) [1/s], >= 0
  Vec3 color{0.8, 0.3, 0.3};  // base colour for the renderer, components in [0, 1]
  Real roughness = 0.5;       // renderer: 0 = mirror-like highlight, 1 = matte
};

struct BodyDef {
  std::string name;
  DeformLevel level = DeformLevel::local;
  DynamicsOrder order = DynamicsOrder::second;
  ShapeKind shape = ShapeKind::superquadric;
  VecX q_s;   // initial global parameters (size shape_parameter_count(shape)), (2.8)/(2.11)/(2.27)
  VecX q_s0;  // rest values of q_s (3.31); defaults to q_s
  VecX k_s;   // stiffness per global parameter (3.32), >= 0; defaults to 0
  Vec3 position = Vec3::Zero();          // q_c [m]
  Vec4 orientation{1, 0, 0, 0};          // q_theta quaternion (w, x, y, z), normalized on load
  Vec3 velocity = Vec3::Zero();          // c-dot [m/s], world frame
  Vec3 angular_velocity = Vec3::Zero();  // omega [rad/s], world frame
  TessellationDef tessellation;
  MaterialDef material;
};

struct ForceFieldDef {
  ForceFieldKind kind = ForceFieldKind::acceleration;
  Vec3 value = Vec3::Zero();  // acceleration [m/s^2] or force on each node [N]
  std::vector<int> bodies;    // indices into the scene's bodies; empty = every body
};

// A spring from a surface point of a body to a target point (sec. 6.4's mouse spring).
// The point is a node index, or material coordinates (u, v) resolved to the nearest node.
struct SpringDef {
  std::string name;
  int body = 0;
  int node = -1;                       // >= 0: node index
  std::optional<Vec2> material_point;  // (u, v) in radians when node < 0
  Vec3 target = Vec3::Zero();          // [m], world frame
  Real stiffness = 100.0;              // [N/m], >= 0
  Real damping = 1.0;                  // [N s/m], >= 0
  Real t_begin = 0.0;                  // active interval [s]
  Real t_end = 1e300;
  Real max_force = 1e300;  // [N], > 0: the force's magnitude is clamped to it
};

}  // namespace pbm
