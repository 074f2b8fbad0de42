// Side-by-side peer for `pbm bench figures`' step with contacts: the links of multibody_link.h as
// a btMultiBody in a btMultiBodyDynamicsWorld, each link a capsule collider, over a static ground
// plane; one step is the world's (collision detection, its multibody constraint solver for the
// contacts, ABA, positions).
#pragma once

#include <memory>
#include <vector>

#include "multibody_link.h"

namespace pbm::bench {

// A link's capsule along its own z axis, centred at its centre of mass.
struct LinkCapsule {
  Real radius = 0.04;      // [m]
  Real half_length = 0.1;  // of the straight part [m]
};

struct BulletMultibodyGround;
struct BulletMultibodyGroundDeleter {
  void operator()(BulletMultibodyGround* world) const;
};
using BulletMultibodyGroundPtr =
    std::unique_ptr<BulletMultibodyGround, BulletMultibodyGroundDeleter>;

// The links' fixed base at `base` (world), the ground z = 0 with friction `friction` (the links'
// too), no self collisions, gravity g.
BulletMultibodyGroundPtr make_bullet_multibody_ground(const std::vector<MultibodyLink>& links,
                                                      const std::vector<LinkCapsule>& capsules,
                                                      const Vec3& base, const Vec3& gravity,
                                                      Real friction);

// One step of its world of dt.
void step(BulletMultibodyGround& world, Real dt);
// Contact points between the links and the ground after the last step.
int contact_points(const BulletMultibodyGround& world);
// The height of link i's centre of mass [m].
Real link_height(const BulletMultibodyGround& world, int i);

}  // namespace pbm::bench
