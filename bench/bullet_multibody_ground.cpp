#include "bullet_multibody_ground.h"

#include <Eigen/Geometry>

// Bullet, with its warnings silenced here only.
#include "bullet_warnings_off.h"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include "bullet_warnings_on.h"

namespace pbm::bench {

// Members in construction order; destroyed in reverse, the world before what it refers to.
struct BulletMultibodyGround {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> world;
  std::unique_ptr<btMultiBody> body;
  std::vector<std::unique_ptr<btCapsuleShapeZ>> shapes;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;
  btStaticPlaneShape plane{btVector3(0, 0, 1), 0};
  std::unique_ptr<btRigidBody> ground;

  ~BulletMultibodyGround() {
    if (!world) return;
    if (ground) world->removeRigidBody(ground.get());
    for (auto& c : colliders) world->removeCollisionObject(c.get());
    if (body) world->removeMultiBody(body.get());
  }
};

namespace {

btVector3 bt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

}  // namespace

void BulletMultibodyGroundDeleter::operator()(BulletMultibodyGround* world) const {
  delete world;
}

BulletMultibodyGroundPtr make_bullet_multibody_ground(const std::vector<MultibodyLink>& links,
                                                      const std::vector<LinkCapsule>& capsules,
                                                      const Vec3& base, const Vec3& gravity,
                                                      Real friction) {
  BulletMultibodyGroundPtr w(new BulletMultibodyGround);
  w->world = std::make_unique<btMultiBodyDynamicsWorld>(&w->dispatcher, &w->broadphase, &w->solver,
                                                        &w->configuration);
  w->world->setGravity(bt(gravity));
  const int n = static_cast<int>(links.size());
  w->body = std::make_unique<btMultiBody>(n, 1.0f, btVector3(1, 1, 1), true, false);
  w->body->setBasePos(bt(base));
  w->body->setWorldToBaseRot(btQuaternion::getIdentity());
  for (int i = 0; i < n; ++i) {
    const MultibodyLink& l = links[static_cast<std::size_t>(i)];
    const Eigen::Quaternion<Real> r(l.rot_parent_to_this);
    const btQuaternion rot(static_cast<btScalar>(r.x()), static_cast<btScalar>(r.y()),
                           static_cast<btScalar>(r.z()), static_cast<btScalar>(r.w()));
    w->body->setupRevolute(i, static_cast<btScalar>(l.mass), bt(l.principal), l.parent, rot,
                           bt(l.axis), bt(l.parent_com_to_pivot), bt(l.pivot_to_com));
  }
  w->body->finalizeMultiDof();
  w->body->setLinearDamping(0);
  w->body->setAngularDamping(0);
  w->body->setHasSelfCollision(false);
  w->body->setCanSleep(false);
  w->world->addMultiBody(w->body.get());
  btAlignedObjectArray<btQuaternion> scratch_q;
  btAlignedObjectArray<btVector3> scratch_m;
  w->body->forwardKinematics(scratch_q, scratch_m);
  for (int i = 0; i < n; ++i) {
    const LinkCapsule& c = capsules[static_cast<std::size_t>(i)];
    w->shapes.push_back(std::make_unique<btCapsuleShapeZ>(
        static_cast<btScalar>(c.radius), static_cast<btScalar>(2 * c.half_length)));
    auto collider = std::make_unique<btMultiBodyLinkCollider>(w->body.get(), i);
    collider->setCollisionShape(w->shapes.back().get());
    collider->setFriction(static_cast<btScalar>(friction));
    w->world->addCollisionObject(collider.get(), btBroadphaseProxy::DefaultFilter,
                                 btBroadphaseProxy::AllFilter);
    w->body->getLink(i).m_collider = collider.get();
    w->colliders.push_back(std::move(collider));
  }
  w->body->updateCollisionObjectWorldTransforms(scratch_q, scratch_m);
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, &w->plane);
  info.m_friction = static_cast<btScalar>(friction);
  w->ground = std::make_unique<btRigidBody>(info);
  w->world->addRigidBody(w->ground.get());
  return w;
}

void step(BulletMultibodyGround& world, Real dt) {
  const auto h = static_cast<btScalar>(dt);
  world.world->stepSimulation(h, 0, h);
}

int contact_points(const BulletMultibodyGround& world) {
  int count = 0;
  const int manifolds = world.dispatcher.getNumManifolds();
  for (int k = 0; k < manifolds; ++k) {
    count += world.dispatcher.getManifoldByIndexInternal(k)->getNumContacts();
  }
  return count;
}

Real link_height(const BulletMultibodyGround& world, int i) {
  return world.body->localPosToWorld(i, btVector3(0, 0, 0)).z();
}

}  // namespace pbm::bench
