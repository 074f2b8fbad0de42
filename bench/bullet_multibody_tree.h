// Side-by-side peer for `pbm bench figures`: the same revolute tree as Bullet's btMultiBody (its
// Featherstone articulated-body method), built from a plain description both sides read.
#pragma once

#include <memory>
#include <vector>

#include "core/types.h"

namespace pbm::bench {

// One link as btMultiBody describes it: pivot offsets, its rotation at q = 0 (parent coordinates
// to its own), a revolute axis in its own frame, principal inertia at its centre.
struct MultibodyLink {
  int parent = -1;  // -1: the fixed base
  Real mass = 1;
  Vec3 principal = Vec3::Ones();            // [kg m^2], link axes
  Vec3 parent_com_to_pivot = Vec3::Zero();  // parent frame, from the parent's centre [m]
  Vec3 pivot_to_com = Vec3::Zero();         // own frame [m]
  Mat3 rot_parent_to_this = Mat3::Identity();
  Vec3 axis = Vec3::UnitZ();
};

struct BulletMultibodyTree;
// Releases it (the type is complete only in its file, which keeps Bullet's headers there).
struct BulletMultibodyTreeDeleter {
  void operator()(BulletMultibodyTree* tree) const;
};
using BulletMultibodyTreePtr = std::unique_ptr<BulletMultibodyTree, BulletMultibodyTreeDeleter>;

BulletMultibodyTreePtr make_bullet_multibody_tree(const std::vector<MultibodyLink>& links);

// Sets the joint angles and rates.
void set_state(BulletMultibodyTree& tree, const VecX& q, const VecX& v);
// Its ABA with gravity as link forces, the accelerations left unapplied (dt = 0).
void accelerations(BulletMultibodyTree& tree, const Vec3& gravity);
// One step as btMultiBodyDynamicsWorld takes it without contacts: gravity, ABA with the velocity
// update, then the positions.
void step(BulletMultibodyTree& tree, const Vec3& gravity, Real dt);

}  // namespace pbm::bench
