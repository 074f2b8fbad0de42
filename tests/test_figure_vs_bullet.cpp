// Agreement with an independent implementation: a 5-link chain of revolute and spherical joints
// hanging from a fixed base under gravity, our articulated-body method (sec. 15.2) against
// Bullet's btMultiBody (its own Featherstone ABA, double precision). The accelerations at random
// states agree to 1e-10, and the chain integrated for 2 s by the same RK4 with each side's
// accelerations keeps its joint angles within 1e-6 rad.
//
// Built from the figure sources alone against Bullet's float64 libraries (tests/CMakeLists.txt):
// the engine links the single-precision Bullet, whose symbols would clash.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "figure/articulated_body.h"
#include "figure/figure_model.h"
#include "figure_rk4.h"
#include "multibody_link.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyLink.h>
#pragma GCC diagnostic pop

static_assert(sizeof(btScalar) == sizeof(double), "the peer must be Bullet's double precision");

namespace pbm {
namespace {

const Vec3 kGravity(0, 0, -9.81);
constexpr int kLinks = 5;

btVector3 bt(const Vec3& v) {
  return btVector3(v.x(), v.y(), v.z());
}

using bench::MultibodyLink;

std::vector<MultibodyLink> random_chain(std::mt19937& rng) {
  std::uniform_real_distribution<Real> u(-1, 1), positive(0.5, 2.0);
  std::normal_distribution<Real> normal;
  std::vector<MultibodyLink> links(kLinks);
  for (int i = 0; i < kLinks; ++i) {
    MultibodyLink& l = links[i];
    l.parent = i - 1;
    l.spherical = i % 2 == 1;
    l.mass = positive(rng);
    l.principal = 0.05 * Vec3(positive(rng), positive(rng), positive(rng)) + Vec3::Constant(0.05);
    l.parent_com_to_pivot = Vec3(0.1 * u(rng), 0.1 * u(rng), -0.2 + 0.1 * u(rng));
    l.pivot_to_com = Vec3(0.1 * u(rng), 0.1 * u(rng), -0.25 + 0.1 * u(rng));
    l.rot_parent_to_this =
        Eigen::Quaternion<Real>(normal(rng), normal(rng), normal(rng), normal(rng))
            .normalized()
            .toRotationMatrix();
    l.axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
  }
  return links;
}

struct BulletChain {
  std::unique_ptr<btMultiBody> body;
  std::vector<Real> mass;
  btAlignedObjectArray<btScalar> scratch_r;
  btAlignedObjectArray<btVector3> scratch_v;
  btAlignedObjectArray<btMatrix3x3> scratch_m;
};

BulletChain bullet_chain(const std::vector<MultibodyLink>& links) {
  BulletChain chain;
  chain.body = std::make_unique<btMultiBody>(kLinks, 1.0, btVector3(1, 1, 1), true, false);
  for (int i = 0; i < kLinks; ++i) {
    const MultibodyLink& l = links[i];
    const Eigen::Quaternion<Real> r(l.rot_parent_to_this);
    const btQuaternion rot(r.x(), r.y(), r.z(), r.w());
    if (l.spherical) {
      chain.body->setupSpherical(i, l.mass, bt(l.principal), i - 1, rot, bt(l.parent_com_to_pivot),
                                 bt(l.pivot_to_com));
    } else {
      chain.body->setupRevolute(i, l.mass, bt(l.principal), i - 1, rot, bt(l.axis),
                                bt(l.parent_com_to_pivot), bt(l.pivot_to_com));
    }
    chain.mass.push_back(l.mass);
  }
  chain.body->finalizeMultiDof();
  // Physics only: no artificial damping, and no clamp on the velocity change read below.
  chain.body->setLinearDamping(0);
  chain.body->setAngularDamping(0);
  chain.body->setMaxCoordinateVelocity(1e30);
  return chain;
}

// Bullet's qddot at our (q, v): its velocity change over a step of 1 s (its ABA adds qddot dt to
// the velocities), velocities restored after.
VecX bullet_accelerations(BulletChain& chain, const FigureModel& figure, const VecX& q,
                          const VecX& v) {
  btMultiBody& body = *chain.body;
  for (int i = 0; i < kLinks; ++i) {
    const SegmentModel& s = figure.segments[i];
    if (s.joint.kind == JointKind::spherical) {
      const Real* w = q.data() + s.q_offset;  // ours (w, x, y, z), Bullet's (x, y, z, w)
      const double position[4] = {w[1], w[2], w[3], w[0]};
      body.setJointPosMultiDof(i, position);
      body.setJointVelMultiDof(i, v.data() + s.v_offset);
    } else {
      body.setJointPos(i, q[s.q_offset]);
      body.setJointVel(i, v[s.v_offset]);
    }
  }
  body.clearForcesAndTorques();
  for (int i = 0; i < kLinks; ++i) body.addLinkForce(i, bt(chain.mass[i] * kGravity));
  body.computeAccelerationsArticulatedBodyAlgorithmMultiDof(1.0, chain.scratch_r, chain.scratch_v,
                                                            chain.scratch_m, false, false, false);
  VecX qdd(figure.n_v);
  for (int i = 0; i < kLinks; ++i) {
    const SegmentModel& s = figure.segments[i];
    const int dof = joint_v_size(s.joint.kind);
    const btScalar* after = body.getJointVelMultiDof(i);
    for (int k = 0; k < dof; ++k) qdd[s.v_offset + k] = after[k] - v[s.v_offset + k];
  }
  return qdd;
}

VecX our_accelerations(const FigureModel& figure, FigureWorkspace& ws, const VecX& q,
                       const VecX& v) {
  const VecX tau = VecX::Zero(figure.n_v);
  VecX qdd(figure.n_v);
  forward_dynamics(figure, q.data(), v.data(), tau.data(), {}, kGravity, ws, qdd.data());
  return qdd;
}

TEST(FigureVsBullet, AccelerationsAgreeAtRandomStates) {
  std::mt19937 rng(5);
  Real worst = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const std::vector<MultibodyLink> links = random_chain(rng);
    const FigureModel figure = bench::figure_of_links(links);
    FigureWorkspace ws;
    size_figure_workspace(figure, ws);
    BulletChain chain = bullet_chain(links);
    std::uniform_real_distribution<Real> u(-1.5, 1.5);
    VecX q(figure.n_q), v(figure.n_v);
    for (int k = 0; k < figure.n_q; ++k) q[k] = u(rng);
    for (int k = 0; k < figure.n_v; ++k) v[k] = u(rng);
    figure_normalize(figure, q.data());
    const VecX ours = our_accelerations(figure, ws, q, v);
    const VecX theirs = bullet_accelerations(chain, figure, q, v);
    worst = std::max(worst, (ours - theirs).norm() / theirs.norm());
  }
  std::printf("worst relative difference of qddot, ours vs btMultiBody: %.2e\n", worst);
  EXPECT_LT(worst, 1e-10);
}

// The angle between two joint positions: |q_a - q_b| for a revolute joint, the rotation angle
// between the two quaternions for a spherical one.
Real joint_angle_difference(const SegmentModel& s, const VecX& a, const VecX& b) {
  if (s.joint.kind == JointKind::revolute) return std::abs(a[s.q_offset] - b[s.q_offset]);
  const Real dot = std::abs(a.segment<4>(s.q_offset).dot(b.segment<4>(s.q_offset)));
  return 2 * std::acos(std::min<Real>(1, dot));
}

TEST(FigureVsBullet, ChainSwingsTheSameFor2Seconds) {
  std::mt19937 rng(9);
  const std::vector<MultibodyLink> links = random_chain(rng);
  const FigureModel figure = bench::figure_of_links(links);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  BulletChain chain = bullet_chain(links);
  VecX q0(figure.n_q);
  figure_neutral_q(figure, q0.data());
  for (const SegmentModel& s : figure.segments) {  // released from a bent pose
    if (s.joint.kind == JointKind::revolute) q0[s.q_offset] = 0.8;
    if (s.joint.kind == JointKind::spherical) {
      q0.segment<4>(s.q_offset) << std::cos(0.3), std::sin(0.3) * Vec3(1, -1, 0.5).normalized();
    }
  }
  const VecX v0 = VecX::Zero(figure.n_v);
  // The same RK4 (1 ms) on each side's accelerations.
  const auto integrate = [&](auto&& accelerations) {
    VecX q = q0, v = v0;
    const Real h = 1e-3;
    const auto rates = [&](const VecX& qs, const VecX& vs, VecX& q_dot, VecX& v_dot) {
      q_dot.resize(figure.n_q);
      figure_q_dot(figure, qs.data(), vs.data(), q_dot.data());
      v_dot = accelerations(qs, vs);
    };
    for (int step = 0; step < 2000; ++step) test::figure_rk4_step(figure, q, v, h, rates);
    return q;
  };
  const VecX ours =
      integrate([&](const VecX& q, const VecX& v) { return our_accelerations(figure, ws, q, v); });
  const VecX theirs = integrate(
      [&](const VecX& q, const VecX& v) { return bullet_accelerations(chain, figure, q, v); });
  Real worst = 0, travel = 0;
  for (const SegmentModel& s : figure.segments) {
    worst = std::max(worst, joint_angle_difference(s, ours, theirs));
    travel = std::max(travel, joint_angle_difference(s, ours, q0));
  }
  std::printf("after 2 s: joints moved up to %.3f rad; worst difference ours vs Bullet %.2e rad\n",
              travel, worst);
  EXPECT_GT(travel, 0.1);  // the chain did swing
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace pbm
