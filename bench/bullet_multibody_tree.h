// Side-by-side peer for `pbm bench figures`: the same revolute tree as Bullet's btMultiBody (its
// Featherstone articulated-body method), built from the links both sides read (multibody_link.h).
#pragma once

#include <memory>
#include <vector>

#include "multibody_link.h"

namespace pbm::bench {

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
