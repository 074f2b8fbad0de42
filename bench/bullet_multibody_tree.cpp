#include "bullet_multibody_tree.h"

#include <Eigen/Geometry>

// Bullet, with its warnings silenced here only.
#include "bullet_warnings_off.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLink.h>

#include "bullet_warnings_on.h"

namespace pbm::bench {

struct BulletMultibodyTree {
  std::unique_ptr<btMultiBody> body;
  std::vector<btScalar> mass;
  btAlignedObjectArray<btScalar> scratch_r;
  btAlignedObjectArray<btVector3> scratch_v;
  btAlignedObjectArray<btMatrix3x3> scratch_m;
};

namespace {

btVector3 bt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

void add_gravity(BulletMultibodyTree& tree, const Vec3& gravity) {
  tree.body->clearForcesAndTorques();
  for (int i = 0; i < tree.body->getNumLinks(); ++i) {
    tree.body->addLinkForce(i, bt(gravity) * tree.mass[static_cast<std::size_t>(i)]);
  }
}

}  // namespace

void BulletMultibodyTreeDeleter::operator()(BulletMultibodyTree* tree) const {
  delete tree;
}

BulletMultibodyTreePtr make_bullet_multibody_tree(const std::vector<MultibodyLink>& links) {
  BulletMultibodyTreePtr tree(new BulletMultibodyTree);
  const int n = static_cast<int>(links.size());
  tree->body = std::make_unique<btMultiBody>(n, 1.0f, btVector3(1, 1, 1), true, false);
  for (int i = 0; i < n; ++i) {
    const MultibodyLink& l = links[static_cast<std::size_t>(i)];
    const Eigen::Quaternion<Real> r(l.rot_parent_to_this);
    const btQuaternion rot(static_cast<btScalar>(r.x()), static_cast<btScalar>(r.y()),
                           static_cast<btScalar>(r.z()), static_cast<btScalar>(r.w()));
    tree->body->setupRevolute(i, static_cast<btScalar>(l.mass), bt(l.principal), l.parent, rot,
                              bt(l.axis), bt(l.parent_com_to_pivot), bt(l.pivot_to_com));
    tree->mass.push_back(static_cast<btScalar>(l.mass));
  }
  tree->body->finalizeMultiDof();
  tree->body->setLinearDamping(0);
  tree->body->setAngularDamping(0);
  return tree;
}

void set_state(BulletMultibodyTree& tree, const VecX& q, const VecX& v) {
  for (int i = 0; i < tree.body->getNumLinks(); ++i) {
    tree.body->setJointPos(i, static_cast<btScalar>(q[i]));
    tree.body->setJointVel(i, static_cast<btScalar>(v[i]));
  }
}

void accelerations(BulletMultibodyTree& tree, const Vec3& gravity) {
  add_gravity(tree, gravity);
  tree.body->computeAccelerationsArticulatedBodyAlgorithmMultiDof(
      0, tree.scratch_r, tree.scratch_v, tree.scratch_m, false, false, false);
}

void step(BulletMultibodyTree& tree, const Vec3& gravity, Real dt) {
  add_gravity(tree, gravity);
  const auto h = static_cast<btScalar>(dt);
  tree.body->computeAccelerationsArticulatedBodyAlgorithmMultiDof(
      h, tree.scratch_r, tree.scratch_v, tree.scratch_m, false, false, false);
  tree.body->stepPositionsMultiDof(h);
}

}  // namespace pbm::bench
