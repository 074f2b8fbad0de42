// BodyModel: one deformable superquadric as the solver sees it, constant while time runs
// (docs/architecture.md: Model / State / Workspace), compiled once from its BodyDef; and the
// springs that pull on body nodes. Its DOF vector holds only what its level pays for; the
// blocks are named in deform/body_layout.h.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/types.h"
#include "deform/body_def.h"
#include "deform/body_layout.h"
#include "deform/membrane_stiffness.h"
#include "deform/stability_limit.h"
#include "deform/superquadric.h"
#include "deform/tessellation.h"

namespace pbm {

// A material point of the global surface where obstacles push (5.11), inside a surface triangle:
// its (u, v), the triangle's nodes and its barycentric weights there (for a cheap first test and
// for velocities), and its share of the contact stiffness before the obstacle's a [N/m].
// Three points per surface triangle by default, not one: with the centroid alone a ball on the
// ground still creeps toward its deepest orientation (8e-3 m/s against 5e-4 m/s after 10 s). The
// centroid is the tessellation's "contact" knob for scenes that can afford that error
// (TessellationDef::contact): a third of the samples to find and push.
inline constexpr int contact_samples_per_triangle(ContactQuadrature rule) {
  return rule == ContactQuadrature::centroid ? 1 : 3;
}

struct ContactSample {
  std::array<int, 3> nodes{};
  Vec3 weights = Vec3::Zero();
  SuperquadricAngles angles;
  std::array<int, 2> grid{};  // its latitude and longitude in BodyModel::sample_grid_u / _v
  Real stiffness = 0;
};

struct BodyModel {
  std::string name;
  DeformLevel level = DeformLevel::local;
  DynamicsOrder order = DynamicsOrder::second;
  ShapeKind shape = ShapeKind::superquadric;
  int n_s = 0;             // global DOFs in the State (0 for rigid bodies)
  int n_shape = 0;         // shape_parameter_count(shape): size of q_s whether dynamic or not
  bool has_local = false;  // q_d present
  // level "auto": q_d present, held at zero while the body is far from contact and unpulled
  // (State::dormant, sim/level_of_detail.h)
  bool auto_level = false;
  VecX q_s_fixed;                // shape of a rigid body (n_shape)
  VecX q_s0;                     // rest values (3.31), before tracks (n_shape)
  VecX k_s;                      // global stiffness diag (3.32) (n_shape)
  Real parameter_inertia = 0;    // eta of the gauge direction, see deform/body_dynamics.h
  VecX parameter_inertia_floor;  // eta_i = k_s,i tau^2 added to M_ss's diagonal (n_s)
  std::vector<Vec3> s_fixed;     // rigid bodies: reference shape at each node (constant)
  Tessellation tessellation;
  std::vector<SuperquadricAngles> node_angles;  // superquadric_angles(u_i, v_i) per node
  // The distinct latitudes and longitudes of the nodes (angles of (u, 0) and (0, v)) and, per
  // node, its pair of indices into them: see SignedPowers.
  std::vector<SuperquadricAngles> grid_u, grid_v;
  std::vector<std::array<int, 2>> node_grid;
  MembraneStiffness stiffness;  // K_dd element matrices, local bodies only
  // Local bodies: samples_per_triangle (1 or 3) per surface triangle, in order.
  int samples_per_triangle = 3;
  std::vector<ContactSample> contact_samples;
  // The material gives the contact stiffness per area (MaterialDef::contact_stiffness): its
  // dashpot is then a damping ratio, not sized on the step (collide/rigid_contact.cpp).
  bool contact_from_material = false;
  Real contact_sample_gap = 0;  // bound on |exact - blended| sample position on the initial shape
  // Per surface triangle: how far its samples lie from its nodes on the initial shape, at most.
  std::vector<Real> contact_triangle_reach;
  std::vector<SuperquadricAngles> sample_grid_u, sample_grid_v;  // distinct sample u and v
  Real w0 = 0, w1 = 0;
  VecX node_mass;         // lumped mass per node [kg] (sec. 6.1, footnote 2)
  Real surface_area = 0;  // of the flat triangles on the initial shape [m^2]
  // The book's contact stiffness per area, sum K_ii / area [N/m^3] (local bodies): what a scene
  // converted to MaterialDef::contact_stiffness gives to keep its contact at this resolution.
  Real book_contact_stiffness = 0;
  Real mass = 0;     // sum of node_mass
  Real damping = 0;  // nu, D = nu M
  Vec3 color{0.8, 0.3, 0.3};
  Real roughness = 0.5;          // renderer
  BodyLayout layout;             // the blocks of its slices (deform/body_layout.h)
  StabilityLimit stability;      // its explicit step's limit (deform/stability_limit.h)
  int q_offset = 0, q_size = 0;  // slice of State::q
  int v_offset = 0, v_size = 0;  // slice of State::v
  int n_nodes() const { return static_cast<int>(node_mass.size()); }
  int n_generalized() const { return BodyLayout::kRigidV + n_s; }  // rigid + global block size k
};

// The body's slices of a whole state vector (State::q and State::v, or a rate vector of the same
// layout).
template <class Vector>
auto body_q(const BodyModel& body, Vector& q) {
  return q.segment(body.q_offset, body.q_size);
}
template <class Vector>
auto body_v(const BodyModel& body, Vector& v) {
  return v.segment(body.v_offset, body.v_size);
}

// A spring from a body node to a target (sec. 6.4); target and stiffness may be driven by tracks.
struct SpringModel {
  std::string name;
  int body = 0;
  int node = 0;
  Vec3 target = Vec3::Zero();
  Real stiffness = 0, damping = 0;
  Real t_begin = 0, t_end = 1e300;
  Real max_force = 1e300;
};

// Compiles one body: tessellation, membrane stiffness, contact samples, masses, the inertia of
// the gauge direction and the shape parameters' floor (sized on the time scale tau,
// solver.shape_inertia_time or solver.dt). Throws pbm::Error(file, path + ...) when the
// definition cannot be compiled; q_offset and v_offset are left 0 for the caller to place.
BodyModel build_body_model(const BodyDef& def, Real inertia_time, const std::string& file,
                           const std::string& path);

}  // namespace pbm
