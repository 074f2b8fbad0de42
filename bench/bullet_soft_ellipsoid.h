// Bullet peer for the deformable benchmark: a pressurised soft ellipsoid ("jello ball") dropped
// on a ground plane, stepped by Bullet's own btSoftRigidDynamicsWorld so our deformable solvers
// can be timed against a widely used reference on the same scene.
//
// Frame: world, z up, gravity (0, 0, -9.81) m/s^2, ground plane z = 0. Units: SI.
// Bullet is built in single precision here, so positions are float internally and returned as
// double.
#pragma once

#include <memory>

namespace pbm::bench {

// Opaque so that Bullet's headers never leak into callers: owns the dynamics world, the static
// ground and the one btSoftBody.
struct BulletSoftEllipsoid;

}  // namespace pbm::bench

// The deleter is defined in the .cpp, where BulletSoftEllipsoid is complete, so a plain
// std::unique_ptr<BulletSoftEllipsoid> can be destroyed by callers that never see Bullet.
namespace std {
template <>
struct default_delete<pbm::bench::BulletSoftEllipsoid> {
  void operator()(pbm::bench::BulletSoftEllipsoid* ellipsoid) const;
};
}  // namespace std

namespace pbm::bench {

// Builds a soft ellipsoid from btSoftBodyHelpers::CreateEllipsoid with about n_nodes surface nodes
// (it hulls n_nodes Hammersley points). Its hull routine drops near-coplanar points, capping it
// near 1150 nodes; when it loses more than 1% of them, n_nodes Hammersley points are hulled
// exactly with btConvexHullComputer instead. Read node_count() for the actual number.
// Radii (rx, ry, rz) in m, centre at `height` above z = 0, total `mass` in kg spread over the
// nodes by surface area. Linear stiffness 0.5, pressure and volume conservation on (a jello ball),
// collision margin 1% of the smallest radius. The ground is a static box whose top face is z = 0.
// Bullet's links are position constraints solved once per step, so finer meshes are softer and
// the pressure inflates them more: after 6 s at rest a 66-node ball holds its rest volume, a
// 16k-node one about 2.5 times it. Compare timings, not shapes, across resolutions.
// Requires n_nodes >= 4, radii > 0, height > rz, mass > 0.
std::unique_ptr<BulletSoftEllipsoid> make_bullet_soft_ellipsoid(int n_nodes, double rx, double ry,
                                                                double rz, double height,
                                                                double mass);

// Number of nodes Bullet actually built.
int node_count(const BulletSoftEllipsoid& ellipsoid);

// One stepSimulation(dt, 0): exactly one internal step of dt seconds, no substepping.
void step(BulletSoftEllipsoid& ellipsoid, double dt);

// Lowest node height in m (z of the lowest node); the ground is z = 0.
double lowest_node_z(const BulletSoftEllipsoid& ellipsoid);

}  // namespace pbm::bench
