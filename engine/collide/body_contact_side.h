// One deformable body as a side of a contact (sec. 5.2.2): the velocity of a point of it, the
// mass it moves with along a direction, an impulse and a positional correction applied to it,
// and the write-back to q and v. Shared by the collisions between bodies (body_collisions.h) and
// those of bodies with figures' segments (sim/segment_body_collisions.h).
// Levels: a local body's side acts on its nodes alone, through q_d and d-dot with the lumped
// nodal masses (the mean-axis split is restored at write-back, resplit_velocities, which moves no
// node). Rigid and global bodies act through their generalized coordinates: an impulse J at
// y = sum w_k x_k maps by sum w_k P_k^T R^T J through the k x k mass block (A^+), as for
// obstacles (5.2.1); their position correction translates c alone (inverse mass 1 / M).
#pragma once

#include <cstdint>
#include <vector>

#include "core/types.h"
#include "deform/body_set.h"

namespace pbm {

// A body's scratch while its contacts are resolved, rebuilt at will (results never depend on it).
struct BodyContactScratch {
  std::vector<Vec3> x0, x;          // node positions at entry / being projected, world [m]
  std::vector<Vec3> x_dot0, x_dot;  // node velocities (local bodies), world [m/s]
  std::vector<Vec3> normal;         // unit area-weighted vertex normals, world
  std::vector<Real> stiffness;      // local bodies: per node, for the push (body_push.h)
  VecX nu, g, delta;                // rigid/global: (R^T c-dot, omega, q_s-dot) and scratch (k)
  Vec3 shift = Vec3::Zero();        // rigid/global: translation of c by the projection [m]
  bool touched = false;
  bool mass_factored = false;
  // The triangles around each node (node k's run is node_triangles[triangle_start[k]] ..
  // node_triangles[triangle_start[k + 1]]), and, per triangle, the node query that last took
  // it as a candidate (a stamp), so a triangle near several of a node's faces is tested once.
  std::vector<int> triangle_start, node_triangles;
  std::vector<std::uint32_t> seen;
  std::uint32_t stamp = 0;
};

// Whether s was sized for body by size_body_scratch.
bool scratch_sized_for(const BodyModel& body, const BodyContactScratch& s);
void size_body_scratch(const BodyModel& body, BodyContactScratch& s);

// Loads s from body b of the set at its state: kinematics, positions, velocities, nu; nothing
// touched, no shift, the mass block not yet factored for it.
void load_body_scratch(const BodySet& set, int b, BodyContactScratch& s);

// One side of a contact: a node (count 1, weight 1) or a triangle's point sum w_k x_k.
struct ContactSide {
  int body = 0;
  const int* nodes = nullptr;
  const Real* weights = nullptr;
  int count = 1;
};

// The bodies and their scratch as the contact response sees them.
struct ContactBodies {
  const BodySet& set;
  std::vector<BodyContactScratch>& scratch;  // one per body of set
  // A rigid or global part held by a constraint (ch. 7) is not translated by the projection
  // (BodyCollisionModel::constrained).
  const std::vector<char>& constrained;
  const BodyModel& body(const ContactSide& side) const { return set.models[side.body]; }
  bool pinned(const ContactSide& side) const {
    return constrained[side.body] != 0 && !set.models[side.body].has_local;
  }
  BodyWorkspace& bw(const ContactSide& side) const { return set.ws[side.body]; }
  BodyContactScratch& of(const ContactSide& side) const { return scratch[side.body]; }
};

// Factors the side's mass block at the set's q once per load (rigid and global bodies).
void ensure_side_mass(const ContactBodies& all, const ContactSide& side);
// World velocity and position of the side's point, from the scratch [m/s], [m].
Vec3 side_velocity(const ContactBodies& all, const ContactSide& side);
Vec3 side_position(const ContactBodies& all, const ContactSide& side);
// Inverse of the mass the side moves with along the unit direction d [1/kg] (needs the mass
// factored: ensure_side_mass).
Real side_inverse_mass(const ContactBodies& all, const ContactSide& side, const Vec3& d);
// Applies the world impulse J [N s] at the side's point to the scratch velocities.
void apply_side_impulse(const ContactBodies& all, const ContactSide& side, const Vec3& J);
// Moves the side by lambda times its positional inverse mass along n (local: the nodes, each by
// its weight over its mass; rigid and global: c, by 1 / M, unless pinned).
void apply_side_displacement(const ContactBodies& all, const ContactSide& side, Real lambda,
                             const Vec3& n);
// The side's inverse mass for the projection [1/kg].
Real side_position_inverse_mass(const ContactBodies& all, const ContactSide& side);

// Back to q and v: local nodes through q_d and d-dot, then the mean-axis split; rigid and global
// bodies through c and nu. Leaves the body's workspace with the new state's kinematics.
void write_back_body(const BodySet& set, int b, BodyContactScratch& s);

}  // namespace pbm
