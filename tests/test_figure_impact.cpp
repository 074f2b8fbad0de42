// The impact stage of figures (sec. 15.3.1): the contact law (15.2) with e = 0, 0.5, 1 at the
// contact point, momentum conserved when two figures collide, joint impulses with no component
// along the joint axes (15.7), and Coulomb's cone on the impulse beyond the book.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"
#include "figure_momentum.h"
#include "figure_points.h"

namespace pbm {
namespace {

// A chain on a free root: a box torso and `links` revolute/spherical links hanging from it.
FigureModel free_chain(int links) {
  FigureModel figure;
  SegmentModel root;
  root.joint.kind = JointKind::free;
  root.inertia = solid_box_inertia(4.0, Vec3(0.2, 0.15, 0.3));
  figure.segments.push_back(root);
  for (int i = 0; i < links; ++i) {
    SegmentModel s;
    s.parent = i;
    s.joint.kind = i % 2 == 0 ? JointKind::revolute : JointKind::spherical;
    s.joint.axis = Vec3(0.3, 1, 0.2).normalized();
    s.X_tree = translation(Vec3(0.05, 0.0, -0.3));
    SpatialInertia I = solid_box_inertia(1.0 + 0.3 * i, Vec3(0.05, 0.05, 0.2));
    I.c = Vec3(0, 0, -0.2);
    s.inertia = I;
    figure.segments.push_back(s);
  }
  finalize_figure_model(figure);
  return figure;
}

VecX state_q(const FigureModel& figure, const Vec3& position, Real bend) {
  VecX q(figure.n_q);
  figure_neutral_q(figure, q.data());
  q.head<3>() = position;
  q.segment<4>(3) << std::cos(0.2), std::sin(0.2) * Vec3(1, 2, 0.5).normalized();
  for (const SegmentModel& s : figure.segments) {
    if (s.joint.kind == JointKind::revolute) q[s.q_offset] = bend;
    if (s.joint.kind == JointKind::spherical) {
      q.segment<4>(s.q_offset) << std::cos(bend / 2),
          std::sin(bend / 2) * Vec3(1, 0, 1).normalized();
    }
  }
  return q;
}

using test::momentum;
using test::point_velocity;
using test::world_point;

TEST(FigureImpact, ContactPointLeavesWithRestitutionTimesItsApproach) {
  const FigureModel figure = free_chain(3);
  for (ImpactFriction friction : {ImpactFriction::frictionless, ImpactFriction::sticking}) {
    for (Real e : {0.0, 0.5, 1.0}) {
      const VecX q = state_q(figure, Vec3(0, 0, 1), 0.4);
      VecX v = VecX::Zero(figure.n_v);
      v.head<6>() << 0.3, -0.2, 0.1, 0.4, 0.2, -2.0;  // falling, turning
      v.tail(figure.n_v - 6).setConstant(0.5);
      // The last link's tip strikes the floor z = const.
      const int tip = figure.size() - 1;
      const Vec3 point = world_point(figure, q, tip, Vec3(0, 0, -0.4));
      const Vec3 before = point_velocity(figure, q, v, tip, point);
      ASSERT_LT(before.z(), 0);
      ImpactWorkspace ws;
      VecX v_after = v;
      const ImpactFigure f{&figure, q.data(), v_after.data()};
      const ImpactContact contact{.figure_a = 0, .segment_a = tip, .point = point};
      const ImpactResult r =
          resolve_impact({&f, 1}, {&contact, 1}, {.restitution = e, .friction = friction}, ws);
      const Vec3 after = point_velocity(figure, q, v_after, tip, point);
      EXPECT_NEAR(after.z(), -e * before.z(), 1e-9) << "e " << e;
      EXPECT_GT(r.impulses[0].z(), 0);
      if (friction == ImpactFriction::sticking) {
        EXPECT_LT(after.head<2>().norm(), 1e-9);
      }
      if (friction == ImpactFriction::frictionless) {
        EXPECT_LT(r.impulses[0].head<2>().norm(), 1e-12);
      }
    }
  }
}

TEST(FigureImpact, TwoFiguresConserveLinearAndAngularMomentum) {
  const FigureModel a = free_chain(2), b = free_chain(4);
  const VecX qa = state_q(a, Vec3(0, 0, 1), 0.3), qb = state_q(b, Vec3(0.8, 0.3, 1.1), -0.5);
  for (ImpactFriction friction :
       {ImpactFriction::frictionless, ImpactFriction::sticking, ImpactFriction::coulomb}) {
    VecX va = VecX::Zero(a.n_v), vb = VecX::Zero(b.n_v);
    va.head<6>() << 0.1, 0.5, -0.2, 2.0, 0.3, 0.1;
    vb.head<6>() << -0.3, 0.2, 0.4, -1.5, 0.1, 0.2;
    va.tail(a.n_v - 6).setConstant(0.7);
    vb.tail(b.n_v - 6).setConstant(-0.4);
    const Vec6 before = momentum(a, qa, va) + momentum(b, qb, vb);
    // a's last link strikes b's second segment, and a's torso b's torso.
    const Vec3 p1 = world_point(a, qa, a.size() - 1, Vec3(0, 0, -0.4));
    const Vec3 p2 = world_point(a, qa, 0, Vec3(0.2, 0, 0));
    const ImpactContact contacts[] = {{.figure_a = 0,
                                       .segment_a = a.size() - 1,
                                       .figure_b = 1,
                                       .segment_b = 1,
                                       .point = p1,
                                       .normal = Vec3(-1, 0, 0.2).normalized()},
                                      {.figure_a = 0,
                                       .segment_a = 0,
                                       .figure_b = 1,
                                       .segment_b = 0,
                                       .point = p2,
                                       .normal = Vec3(-1, 0.1, 0).normalized()}};
    const ImpactFigure figures[] = {{&a, qa.data(), va.data()}, {&b, qb.data(), vb.data()}};
    ImpactWorkspace ws;
    const ImpactResult r = resolve_impact(
        figures, contacts, {.restitution = 0.5, .friction = friction, .mu = 0.3}, ws);
    const Vec6 after = momentum(a, qa, va) + momentum(b, qb, vb);
    std::printf("%s: momentum change %.2e of %.2e, impulses %.3f %.3f N s%s\n",
                friction == ImpactFriction::frictionless ? "frictionless"
                : friction == ImpactFriction::sticking   ? "sticking"
                                                         : "coulomb",
                (after - before).norm(), before.norm(), r.impulses[0].norm(), r.impulses[1].norm(),
                r.projected ? " (projected)" : "");
    EXPECT_LT((after - before).norm(), 1e-10 * before.norm());
    EXPECT_GT(r.impulses[0].norm() + r.impulses[1].norm(), 0.1);  // they did collide
  }
}

// (15.7): what each joint transmits has no component along its axes. From the segments' momentum
// changes and the contact impulses, inward as RNEA sums forces: the impulse through joint l is
// I_l dv_l - (contact impulse on l) + what l passes to its children.
TEST(FigureImpact, JointImpulsesHaveNoComponentAlongTheJointAxes) {
  const FigureModel figure = free_chain(5);
  const VecX q = state_q(figure, Vec3(0, 0, 1), 0.6);
  VecX v = VecX::Zero(figure.n_v);
  v.head<6>() << 0.2, 0.1, -0.3, 0.5, -0.2, -3.0;
  const VecX v_before = v;
  const int tip = figure.size() - 1;
  const Vec3 point = world_point(figure, q, tip, Vec3(0, 0, -0.4));
  const Vec3 point2 = world_point(figure, q, 2, Vec3(0.05, 0, -0.2));
  const ImpactContact contacts[] = {
      {.segment_a = tip, .point = point},
      {.segment_a = 2, .point = point2, .normal = Vec3(0.2, 0, 1).normalized()}};
  const ImpactFigure f{&figure, q.data(), v.data()};
  ImpactWorkspace ws;
  const ImpactResult r = resolve_impact(
      {&f, 1}, contacts, {.restitution = 0.3, .friction = ImpactFriction::sticking}, ws);
  FigureWorkspace before, after;
  size_figure_workspace(figure, before);
  size_figure_workspace(figure, after);
  figure_kinematics(figure, q.data(), v_before.data(), before);
  figure_kinematics(figure, q.data(), v.data(), after);
  std::vector<SpatialTransform> world;
  segment_world_transforms(figure, after, world);
  std::vector<Vec6> F(figure.size(), Vec6::Zero());
  for (int i = figure.size() - 1; i >= 0; --i) {
    F[i] += after.inertia[i] * (after.v[i] - before.v[i]);
    for (int c = 0; c < 2; ++c) {
      if (contacts[c].segment_a != i) continue;
      // The contact impulse as a spatial force about the world origin, then in segment i.
      const ForceVector p_world{contacts[c].point.cross(r.impulses[c]), r.impulses[c]};
      F[i] -= to_vec6(transform_force(world[i], p_world));
    }
    const int parent = figure.segments[i].parent;
    if (parent >= 0) F[parent] += motion_matrix(after.X_up[i]).transpose() * F[i];
  }
  Real scale = 0, worst = 0;
  for (int i = 0; i < figure.size(); ++i) {
    scale = std::max(scale, F[i].norm());
    worst = std::max(worst, (after.S[i].transpose() * F[i]).norm());
  }
  std::printf("largest joint impulse %.3f N s, largest along a joint axis %.2e\n", scale, worst);
  EXPECT_GT(scale, 0.1);
  EXPECT_LT(worst, 1e-10 * scale);
}

// A box corner sliding fast along the floor: with mu = 0.2 the tangential impulse is on the cone
// and the point keeps sliding; with mu = 5 it sticks.
TEST(FigureImpact, CoulombConeLimitsTheTangentialImpulse) {
  const FigureModel figure = free_chain(0);
  const VecX q = state_q(figure, Vec3(0, 0, 1), 0);
  const Vec3 point = world_point(figure, q, 0, Vec3(0.2, 0.15, -0.3));
  for (Real mu : {0.2, 5.0}) {
    VecX v = VecX::Zero(6);
    v.tail<3>() << 3.0, 0.0, -1.0;  // body-frame v_O: sliding and falling
    const ImpactFigure f{&figure, q.data(), v.data()};
    const ImpactContact contact{.point = point};
    ImpactWorkspace ws;
    const ImpactResult r =
        resolve_impact({&f, 1}, {&contact, 1},
                       {.restitution = 0, .friction = ImpactFriction::coulomb, .mu = mu}, ws);
    const Vec3 p = r.impulses[0];
    const Vec3 after = point_velocity(figure, q, v, 0, point);
    std::printf("mu %.1f: p_t / p_n = %.6f, slip after %.4f m/s%s\n", mu,
                p.head<2>().norm() / p.z(), after.head<2>().norm(),
                r.projected ? " (projected)" : "");
    EXPECT_NEAR(after.z(), 0, 1e-9);
    if (mu < 1) {
      EXPECT_TRUE(r.projected);
      EXPECT_NEAR(p.head<2>().norm(), mu * p.z(), 1e-9 * p.z());
      EXPECT_GT(after.head<2>().norm(), 0.1);
    } else {
      EXPECT_LT(after.head<2>().norm(), 1e-9);
      EXPECT_LE(p.head<2>().norm(), mu * p.z());
    }
  }
}

}  // namespace
}  // namespace pbm
