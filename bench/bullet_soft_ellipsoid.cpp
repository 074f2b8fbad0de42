#include "bullet_soft_ellipsoid.h"

#include <algorithm>
#include <cassert>
#include <limits>

// Bullet, with its warnings silenced here only.
#include "bullet_warnings_off.h"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <LinearMath/btConvexHullComputer.h>

#include "bullet_warnings_on.h"

namespace pbm::bench {

struct BulletSoftEllipsoid {
  // Bullet wants these alive for the world's whole life; declared in construction order so they
  // are destroyed in reverse, after the destructor has taken the bodies out of the world.
  std::unique_ptr<btSoftBodyRigidBodyCollisionConfiguration> collision_configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> constraint_solver;
  std::unique_ptr<btSoftRigidDynamicsWorld> world;
  std::unique_ptr<btBoxShape> ground_shape;
  std::unique_ptr<btRigidBody> ground;
  std::unique_ptr<btSoftBody> soft_body;

  BulletSoftEllipsoid() = default;
  BulletSoftEllipsoid(const BulletSoftEllipsoid&) = delete;
  BulletSoftEllipsoid& operator=(const BulletSoftEllipsoid&) = delete;
  ~BulletSoftEllipsoid() {
    if (world) {
      if (soft_body) world->removeSoftBody(soft_body.get());
      if (ground) world->removeRigidBody(ground.get());
    }
  }
};

namespace {

constexpr btScalar kGravity = 9.81f;         // m/s^2, along -z
constexpr btScalar kLinearStiffness = 0.5f;  // Bullet's m_kLST in [0, 1]
// Bullet's pressure is kPR / V per unit area. To carry the ball's weight m g on a contact patch
// of radius r/2 (area pi r^2 / 4) at rest volume (4/3) pi r^3 it needs kPR = (16/3) m g r. More
// inflates dense meshes, whose single-iteration links are softer, well past their rest volume.
constexpr btScalar kPressureOverWeightRadius = 16.0f / 3.0f;
constexpr btScalar kVolumeConservation = 20.0f;  // Bullet's kVC, pulls back to the rest volume
constexpr btScalar kDynamicFriction = 0.5f;
constexpr btScalar kDamping = 0.001f;
// Margin as a fraction of the smallest radius: small, so contact is near the true surface.
constexpr btScalar kMarginOverRadius = 0.01f;
// Half-size of the ground box, m: far wider than any ball we drop.
constexpr btScalar kGroundHalfSize = 100.0f;
// CreateEllipsoid may lose this fraction of its points before we hull them exactly ourselves.
constexpr double kMaxLostNodeFraction = 0.01;

// n Hammersley points on the ellipsoid, the sampling CreateEllipsoid uses: the van der Corput
// radical inverse of i gives the height w in [-1, 1] (uniform in w is uniform in area on a
// sphere, Archimedes), and i gives the longitude.
btAlignedObjectArray<btVector3> sample_hammersley_ellipsoid(int n, const btVector3& centre,
                                                            const btVector3& radii) {
  btAlignedObjectArray<btVector3> x;
  x.resize(n);
  for (int i = 0; i < n; ++i) {
    btScalar radical_inverse = 0;
    btScalar p = 0.5f;
    for (int j = i; j != 0; j >>= 1, p *= 0.5f) {
      if ((j & 1) != 0) radical_inverse += p;
    }
    const btScalar w = 2 * radical_inverse - 1;
    const btScalar longitude = (SIMD_PI + 2 * static_cast<btScalar>(i) * SIMD_PI) / n;
    const btScalar s = btSqrt(btMax(btScalar(0), 1 - w * w));
    x[i] = centre + radii * btVector3(s * btCos(longitude), s * btSin(longitude), w);
  }
  return x;
}

// Soft body on the exact convex hull of x (btConvexHullComputer keeps every extreme point),
// built the way CreateFromConvexHull builds its body: a link per hull edge, a face per triangle.
btSoftBody* create_soft_body_on_exact_hull(btSoftBodyWorldInfo& world_info,
                                           const btAlignedObjectArray<btVector3>& x) {
  btConvexHullComputer hull;
  hull.compute(&x[0].x(), sizeof(btVector3), x.size(), 0, 0);
  auto* body = new btSoftBody(&world_info, hull.vertices.size(), &hull.vertices[0], nullptr);
  for (int e = 0; e < hull.edges.size(); ++e) {
    const btConvexHullComputer::Edge& edge = hull.edges[e];
    // Each hull edge is stored twice, once per direction; link it once.
    if (edge.getSourceVertex() < edge.getTargetVertex()) {
      body->appendLink(edge.getSourceVertex(), edge.getTargetVertex());
    }
  }
  for (int f = 0; f < hull.faces.size(); ++f) {
    // Faces are planar polygons (counter-clockwise seen from outside); fan-triangulate them.
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const int apex = first->getSourceVertex();
    for (const btConvexHullComputer::Edge* edge = first->getNextEdgeOfFace();
         edge->getTargetVertex() != apex; edge = edge->getNextEdgeOfFace()) {
      if (edge->getSourceVertex() != first->getTargetVertex()) {
        body->appendLink(apex, edge->getSourceVertex());  // the fan's interior diagonals
      }
      body->appendFace(apex, edge->getSourceVertex(), edge->getTargetVertex());
    }
  }
  body->randomizeConstraints();
  return body;
}

}  // namespace

std::unique_ptr<BulletSoftEllipsoid> make_bullet_soft_ellipsoid(int n_nodes, double rx, double ry,
                                                                double rz, double height,
                                                                double mass) {
  assert(n_nodes >= 4 && rx > 0 && ry > 0 && rz > 0 && mass > 0);
  auto e = std::unique_ptr<BulletSoftEllipsoid>(new BulletSoftEllipsoid);
  e->collision_configuration = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
  e->dispatcher = std::make_unique<btCollisionDispatcher>(e->collision_configuration.get());
  e->broadphase = std::make_unique<btDbvtBroadphase>();
  e->constraint_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
  e->world = std::make_unique<btSoftRigidDynamicsWorld>(e->dispatcher.get(), e->broadphase.get(),
                                                        e->constraint_solver.get(),
                                                        e->collision_configuration.get());
  const btVector3 gravity(0, 0, -kGravity);
  e->world->setGravity(gravity);

  btSoftBodyWorldInfo& world_info = e->world->getWorldInfo();
  world_info.m_gravity = gravity;
  world_info.air_density = 1.2f;
  world_info.water_density = 0;
  world_info.m_sparsesdf.Initialize();

  // A box whose top face is z = 0, not a btStaticPlaneShape: Bullet collides soft bodies with
  // concave shapes (the plane is one) through triangles extruded by a fixed 0.06 m, so the ball
  // would rest 6 cm above the plane; against a convex box it rests at its own small margin.
  e->ground_shape =
      std::make_unique<btBoxShape>(btVector3(kGroundHalfSize, kGroundHalfSize, kGroundHalfSize));
  btRigidBody::btRigidBodyConstructionInfo ground_info(0, nullptr, e->ground_shape.get());
  ground_info.m_startWorldTransform.setOrigin(btVector3(0, 0, -kGroundHalfSize));
  ground_info.m_friction = 1;
  e->ground = std::make_unique<btRigidBody>(ground_info);
  e->world->addRigidBody(e->ground.get());

  // CreateEllipsoid hulls res + 3 Hammersley points.
  const btVector3 radii(static_cast<btScalar>(rx), static_cast<btScalar>(ry),
                        static_cast<btScalar>(rz));
  const btVector3 centre(0, 0, static_cast<btScalar>(height));
  e->soft_body.reset(
      btSoftBodyHelpers::CreateEllipsoid(world_info, centre, radii, std::max(n_nodes - 3, 1)));
  // Its HullLibrary skips points closer to the hull than 0.1% of the bounding box, which on a
  // dense sampling of a sphere caps the body near 1150 nodes whatever n_nodes asks for.
  if (e->soft_body->m_nodes.size() < (1 - kMaxLostNodeFraction) * n_nodes) {
    e->soft_body.reset(create_soft_body_on_exact_hull(
        world_info, sample_hammersley_ellipsoid(n_nodes, centre, radii)));
  }
  btSoftBody& body = *e->soft_body;
  body.m_materials[0]->m_kLST = kLinearStiffness;
  const btScalar r_mean = (radii.x() + radii.y() + radii.z()) / 3;
  body.m_cfg.kPR = kPressureOverWeightRadius * static_cast<btScalar>(mass) * kGravity * r_mean;
  body.m_cfg.kVC = kVolumeConservation;
  body.m_cfg.kDF = kDynamicFriction;
  body.m_cfg.kDP = kDamping;
  // Mass by face area, so refinement does not change how the load is spread.
  body.setTotalMass(static_cast<btScalar>(mass), true);
  // The rest pose stores the rest volume that kVC restores.
  body.setPose(true, false);
  const btScalar r_min = std::min({radii.x(), radii.y(), radii.z()});
  body.getCollisionShape()->setMargin(kMarginOverRadius * r_min);
  e->world->addSoftBody(&body);
  return e;
}

int node_count(const BulletSoftEllipsoid& ellipsoid) {
  return ellipsoid.soft_body->m_nodes.size();
}

void step(BulletSoftEllipsoid& ellipsoid, double dt) {
  const auto h = static_cast<btScalar>(dt);
  // maxSubSteps = 0 makes Bullet take exactly one internal step of h.
  ellipsoid.world->stepSimulation(h, 0, h);
  // Bullet's demos free stale signed-distance cells every step; otherwise the cache fills up
  // and is thrown away whole, a spike in an arbitrary step.
  ellipsoid.world->getWorldInfo().m_sparsesdf.GarbageCollect();
}

double lowest_node_z(const BulletSoftEllipsoid& ellipsoid) {
  const btSoftBody& body = *ellipsoid.soft_body;
  btScalar z_min = std::numeric_limits<btScalar>::max();
  for (int i = 0; i < body.m_nodes.size(); ++i) z_min = std::min(z_min, body.m_nodes[i].m_x.z());
  return z_min;
}

}  // namespace pbm::bench

namespace std {
void default_delete<pbm::bench::BulletSoftEllipsoid>::operator()(
    pbm::bench::BulletSoftEllipsoid* ellipsoid) const {
  delete ellipsoid;
}
}  // namespace std
