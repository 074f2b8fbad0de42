#include "sim/stages_figures.h"

#include <algorithm>
#include <cstdio>

#include "collide/obstacle.h"
#include "core/quaternion.h"
#include "figure/articulated_body.h"
#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"
#include "figure/joint_springs.h"
#include "figure/segment_probes.h"
#include "sim/stages_figure_control.h"

namespace pbm::stages {

namespace {

// A figure's slices of the World's q, v and their rates.
const Real* q_of(const FigureModel& f, const VecX& q) {
  return q.data() + f.state_q_offset;
}
const Real* v_of(const FigureModel& f, const VecX& v) {
  return v.data() + f.state_v_offset;
}

draw::PrimitiveShape primitive_of(SegmentShapeKind kind) {
  switch (kind) {
    case SegmentShapeKind::box:
      return draw::PrimitiveShape::box;
    case SegmentShapeKind::sphere:
      return draw::PrimitiveShape::sphere;
    case SegmentShapeKind::cylinder:
      return draw::PrimitiveShape::cylinder;
    case SegmentShapeKind::capsule:
      return draw::PrimitiveShape::capsule;
  }
  return draw::PrimitiveShape::box;
}

// The joint forces of the passive figure: its joints' damping, tau = -d q-dot per DOF.
void joint_damping(const FigureModel& figure, const Real* v, Real* tau) {
  for (const SegmentModel& s : figure.segments) {
    const int n = joint_v_size(s.joint.kind);
    for (int k = 0; k < n; ++k) tau[s.v_offset + k] = -s.damping * v[s.v_offset + k];
  }
}

// Under euler (and implicit, whose figures step alike) the joint damping is taken at the step's
// end, -d (v + dt qddot): backward Euler on the damper, stable at any d, where the explicit
// damper needs dt < 2 I / d (a crane's cable joint, the extremes' 1e6 N m s/rad). Its dt d part
// is an armature of the articulated-body method; -d v stays among the joint forces. The
// Runge-Kutta integrators keep it explicit, within the figure's step limit
// (figure/figure_controllers.h). Returns the armature (n_v), or null when it has none.
const Real* implicit_damping(const Model& model, const FigureModel& figure, FiguresWorkspace& fw) {
  const IntegratorKind kind = model.solver.integrator;
  if (kind != IntegratorKind::euler && kind != IntegratorKind::implicit) return nullptr;
  bool any = false;
  for (const SegmentModel& s : figure.segments) {
    const int n = joint_v_size(s.joint.kind);
    for (int k = 0; k < n; ++k) fw.armature[s.v_offset + k] = fw.step * s.damping;
    any = any || (s.damping > 0 && n > 0);
  }
  return any ? fw.armature.data() : nullptr;
}

// One contact point of a segment with an obstacle, in world coordinates.
struct ContactPoint {
  Vec3 point;     // the probe's deepest point [m]
  Vec3 normal;    // the obstacle's outward normal
  Real depth;     // how far inside [m], > 0
  Vec3 velocity;  // of the segment's material at `point` relative to the obstacle's [m/s]
};

// Calls visit(segment, point) for every probe of every segment of the figure inside an obstacle
// (after figure_kinematics and segment_world_transforms of (q, v) in w and world).
template <typename Visit>
void for_each_contact(const FigureModel& figure, const FigureDef& def, const FigureWorkspace& w,
                      const std::vector<SpatialTransform>& world, Obstacles obstacles,
                      Visit&& visit) {
  SegmentProbes probes;
  for (int i = 0; i < figure.size(); ++i) {
    const int n = segment_probes(def.segments[i].shape, probes);
    const SpatialTransform& X = world[i];  // world -> segment
    const MotionVector v = motion_from_vec6(w.v[i]);
    for (int k = 0; k < n; ++k) {
      const Vec3 centre = X.r + X.E.transpose() * probes[k].center;
      for (const ObstacleModel& obstacle : obstacles) {
        Vec3 normal;
        const Real depth = probes[k].radius - signed_distance(obstacle, centre, normal);
        if (!(depth > 0)) continue;
        const Vec3 point = centre - probes[k].radius * normal;
        const Vec3 local = X.E * (point - X.r);
        const Vec3 material = X.E.transpose() * (v.linear + v.angular.cross(local));
        visit(i, ContactPoint{point, normal, depth, material - obstacle.velocity_at(point)},
              obstacle);
      }
    }
  }
}

// The contact stage's force at a contact point (sec. 15.3): a mild spring-damper of stiffness k and
// damping d along the normal that only pushes, and Coulomb friction mu f_n against the sliding,
// viscous (the same damper) below the cone so that a resting contact does not chatter.
Vec3 contact_force(Real k, Real d, const ContactPoint& c, Real mu) {
  const Real v_n = c.velocity.dot(c.normal);
  const Real f_n = std::max(Real(0), k * c.depth - d * v_n);
  const Vec3 v_t = c.velocity - v_n * c.normal;
  const Real speed = v_t.norm();
  Vec3 f_t = -d * v_t;
  if (d * speed > mu * f_n) f_t = speed > 0 ? Vec3(-mu * f_n / speed * v_t) : Vec3::Zero();
  return f_n * c.normal + f_t;
}

// Adds a world force at a world point to a segment's force in its own frame.
void add_point_force(const SpatialTransform& X, const Vec3& force, const Vec3& point,
                     ForceVector& total) {
  const Vec3 f = X.E * force;
  const Vec3 local = X.E * (point - X.r);
  total += ForceVector{local.cross(f), f};
}

// The velocity of segment a's material relative to segment b's at the contact's point.
Vec3 relative_velocity(const FiguresWorkspace& fw, const SegmentContact& k) {
  return segment_point_velocity(fw.worlds[k.figure_a][k.segment_a],
                                fw.each[k.figure_a].v[k.segment_a], k.point) -
         segment_point_velocity(fw.worlds[k.figure_b][k.segment_b],
                                fw.each[k.figure_b].v[k.segment_b], k.point);
}

// The contact stage between segments: equal and opposite spring-damper forces at each point
// (after all_figure_kinematics of the rate's q and v).
void add_segment_contact_forces(const Model& model, FiguresWorkspace& fw) {
  collect_segment_contacts(model, fw.worlds, fw.collision, fw.segment_contacts);
  for (const SegmentContact& k : fw.segment_contacts) {
    const PairContactSettings s =
        pair_contact_settings(model.scene.figures[k.figure_a], model.scene.figures[k.figure_b]);
    const Vec3 u = relative_velocity(fw, k);
    if (u.dot(k.normal) < -s.impact_speed) continue;  // the impact stage's, as with obstacles
    const Vec3 f =
        contact_force(s.stiffness, s.damping, {k.point, k.normal, k.depth, u}, s.friction);
    add_point_force(fw.worlds[k.figure_a][k.segment_a], f, k.point,
                    fw.contact_forces[k.figure_a][k.segment_a]);
    add_point_force(fw.worlds[k.figure_b][k.segment_b], -f, k.point,
                    fw.contact_forces[k.figure_b][k.segment_b]);
  }
}

// The impact stage between segments, (15.1)-(15.8): figure pair by figure pair, the points
// approaching faster than impact_speed have their impact together (a pair within one figure is a
// figure with two of its own segments in each contact).
void segment_impacts(const SubstepContext& c) {
  const Model& model = c.model;
  FiguresWorkspace& fw = *c.ws.figures;
  all_figure_kinematics(model, c.state.q.data(), c.state.v.data(), fw);
  collect_segment_contacts(model, fw.worlds, fw.collision, fw.segment_contacts);
  const std::vector<SegmentContact>& contacts = fw.segment_contacts;
  for (std::size_t begin = 0, end = 0; begin < contacts.size(); begin = end) {
    const int fa = contacts[begin].figure_a, fb = contacts[begin].figure_b;
    end = begin;
    while (end < contacts.size() && contacts[end].figure_a == fa && contacts[end].figure_b == fb)
      ++end;
    const PairContactSettings s =
        pair_contact_settings(model.scene.figures[fa], model.scene.figures[fb]);
    fw.impacts.clear();
    for (std::size_t k = begin; k < end; ++k) {
      if (relative_velocity(fw, contacts[k]).dot(contacts[k].normal) >= -s.impact_speed) continue;
      fw.impacts.push_back({.figure_a = 0,
                            .segment_a = contacts[k].segment_a,
                            .figure_b = fa == fb ? 0 : 1,
                            .segment_b = contacts[k].segment_b,
                            .point = contacts[k].point,
                            .normal = contacts[k].normal});
    }
    if (fw.impacts.empty()) continue;
    const int pair[2] = {fa, fb};
    const int n = fa == fb ? 1 : 2;
    ImpactFigure figures[2];
    for (int i = 0; i < n; ++i) {
      const FigureModel& figure = model.figures[pair[i]].model;
      figures[i] = {&figure, c.state.q.data() + figure.state_q_offset,
                    c.state.v.data() + figure.state_v_offset};
    }
    resolve_impact(
        {figures, static_cast<std::size_t>(n)}, fw.impacts,
        {.restitution = s.restitution, .friction = ImpactFriction::coulomb, .mu = s.friction},
        fw.impact);
    // The velocities changed: the next pairs' contacts see them.
    for (int i = 0; i < n; ++i) {
      const FigureModel& figure = model.figures[pair[i]].model;
      pbm::figure_kinematics(figure, c.state.q.data() + figure.state_q_offset,
                             c.state.v.data() + figure.state_v_offset, fw.each[pair[i]]);
    }
  }
}

// The editor's overlays (drawn on demand): each joint's axes where it sits, a dot at each
// ball-and-socket or welded joint, and the segments' sites.
void add_joint_overlays(const FigureModel& figure, const FigureDef& def,
                        const std::vector<SpatialTransform>& world, draw::Snapshot& snap) {
  constexpr float kAxisLength = 0.12f;  // [m] each way from the joint
  const draw::Vec3f axis_color{0.95f, 0.8f, 0.2f}, site_color{0.9f, 0.3f, 0.8f};
  draw::Lines axes{.layer = draw::Layer::overlay};
  draw::Points dots{.size = 6, .layer = draw::Layer::overlay};
  for (int i = 0; i < figure.size(); ++i) {
    const SegmentModel& s = figure.segments[i];
    const SpatialTransform joint = s.parent >= 0 ? s.X_tree * world[s.parent] : s.X_tree;
    const Vec3 at = joint.r;
    const auto axis = [&](const Vec3& a) {
      const Vec3 d = joint.E.transpose() * a * kAxisLength;
      axes.points.push_back((at - d).cast<float>());
      axes.points.push_back((at + d).cast<float>());
      axes.colors.push_back(axis_color);
    };
    switch (s.joint.kind) {
      case JointKind::revolute:
      case JointKind::prismatic:
        axis(s.joint.axis);
        break;
      case JointKind::universal:
        axis(s.joint.axis);
        axis(joint.E * world[i].E.transpose() * s.joint.axis2);  // on the child, in joint axes
        break;
      case JointKind::spherical:
      case JointKind::fixed:
        dots.positions.push_back(at.cast<float>());
        dots.colors.push_back(axis_color);
        break;
      case JointKind::free:
        break;
    }
    for (const SiteDef& site : def.segments[i].sites) {
      dots.positions.push_back((world[i].r + world[i].E.transpose() * site.position).cast<float>());
      dots.colors.push_back(site_color);
    }
  }
  if (!axes.points.empty()) snap.lines.push_back(std::move(axes));
  if (!dots.positions.empty()) snap.points.push_back(std::move(dots));
}

// The site actuators' strings, from each site to where its path is at t (the marionette's
// strings), and for a quarter second after each impulse event a red stroke ending at the site
// it struck, along the impulse.
void add_event_drawables(const CompiledFigure& figure, std::size_t f, const Inputs& inputs, Real t,
                         const std::vector<SpatialTransform>& world, draw::Snapshot& snap) {
  if (!figure.site_actuators.empty()) {
    draw::Lines strings{.end_points = true, .end_point_size = 4, .layer = draw::Layer::scene};
    for (std::size_t k = 0; k < figure.site_actuators.size(); ++k) {
      const CompiledSiteActuator& a = figure.site_actuators[k];
      const SitePull pull =
          site_pull(a, t, world[a.site.segment], Vec6::Zero(), site_target_input(inputs, f, k));
      if (!pull.active) continue;  // a mouse drag that ended, a string not yet taken up
      strings.points.push_back(pull.position.cast<float>());
      strings.points.push_back(pull.target.cast<float>());
      strings.colors.push_back({0.85f, 0.85f, 0.8f});
    }
    if (!strings.points.empty()) snap.lines.push_back(std::move(strings));
  }
  constexpr Real kShown = 0.25;  // [s]
  constexpr Real kLength = 0.4;  // [m]
  draw::Lines strokes{.layer = draw::Layer::overlay};
  for (const CompiledImpulse& impulse : figure.impulses) {
    if (t < impulse.time || t > impulse.time + kShown) continue;
    const SpatialTransform& X = world[impulse.site.segment];
    const Vec3 at = X.r + X.E.transpose() * impulse.site.position;
    Vec3 along = impulse.frame == ImpulseFrame::world
                     ? impulse.linear
                     : Vec3(X.E.transpose() * impulse.site.rotation * impulse.linear);
    if (!(along.norm() > 0)) continue;  // a couple alone has no line of action
    along.normalize();
    strokes.points.push_back((at - kLength * along).cast<float>());
    strokes.points.push_back(at.cast<float>());
    strokes.colors.push_back({0.95f, 0.15f, 0.1f});
  }
  if (!strokes.points.empty()) snap.lines.push_back(std::move(strokes));
}

}  // namespace

bool figures_present(const Model& model) {
  return !model.figures.empty();
}

void all_figure_kinematics(const Model& model, const Real* q, const Real* v, FiguresWorkspace& fw) {
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    pbm::figure_kinematics(figure, q + figure.state_q_offset,
                           v ? v + figure.state_v_offset : nullptr, fw.each[f]);
    segment_world_transforms(figure, fw.each[f], fw.worlds[f]);
  }
}

bool figure_external_forces_present(const Model& model) {
  return figure_contacts_present(model) || !model.liquids.empty();
}

void size_figures(const Model& model, Workspace& ws) {
  FiguresWorkspace& fw = ws.figures.emplace();
  fw.each.resize(model.figures.size());
  int n_v = 0, n_segments = 0;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    size_figure_workspace(figure, fw.each[f]);
    n_v = std::max(n_v, figure.n_v);
    n_segments = std::max(n_segments, figure.size());
  }
  fw.tau.setZero(n_v);
  fw.world.reserve(static_cast<std::size_t>(n_segments));
  fw.contact_forces.resize(model.figures.size());
  int n_q = 0;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    fw.contact_forces[f].assign(static_cast<std::size_t>(model.figures[f].model.size()),
                                ForceVector{});
    n_q = std::max(n_q, model.figures[f].model.n_q);
  }
  fw.q.setZero(n_q);
  fw.v.setZero(n_v);
  fw.worlds.resize(model.figures.size());
  // Impacts of up to 16 contacts between two figures allocate nothing.
  reserve_impact_workspace(model.segment_collisions ? 2 : 1, n_segments, n_v, 16, fw.impact);
  if (model.segment_collisions) {
    // Room for every segment touching a few others, so that contacts that come and go do not
    // allocate during the step (they grow these only in a pile-up beyond it).
    std::size_t segments = 0;
    for (const CompiledFigure& f : model.figures) segments += f.model.segments.size();
    fw.collision.solids.reserve(segments);
    fw.collision.boxes.reserve(segments);
    fw.collision.order.reserve(segments);
    fw.collision.first.reserve(model.figures.size() + 1);
    fw.collision.pairs.reserve(8 * segments);
    fw.segment_contacts.reserve(8 * segments);
    fw.impacts.reserve(8 * segments);
  }
  size_figure_controllers(model, ws);
  fw.armature.setZero(n_v);
}

bool figure_contacts_present(const Model& model) {
  return !model.obstacles.empty() || model.segment_collisions;
}

void figure_contact_forces(const RateContext& c) {
  if (!figure_contacts_present(c.model)) return;
  FiguresWorkspace& fw = *c.ws.figures;
  all_figure_kinematics(c.model, c.q.data(), c.v.data(), fw);
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    const FigureModel& figure = c.model.figures[f].model;
    const FigureDef& def = c.model.scene.figures[f];
    const std::vector<SpatialTransform>& world = fw.worlds[f];
    std::vector<ForceVector>& forces = fw.contact_forces[f];
    std::fill(forces.begin(), forces.end(), ForceVector{});
    for_each_contact(figure, def, fw.each[f], world, c.ws.drive.obstacles,
                     [&](int i, const ContactPoint& contact, const ObstacleModel& obstacle) {
                       // A point arriving faster than impact_speed is the impact stage's, at the
                       // step's end: the springs act only after the impact (sec. 15.3), else
                       // their damper would take the arrival's speed before the e-law sees it.
                       if (contact.velocity.dot(contact.normal) < -def.impact_speed) return;
                       add_point_force(world[i],
                                       contact_force(def.contact_stiffness, def.contact_damping,
                                                     contact, obstacle.friction),
                                       contact.point, forces[i]);
                     });
  }
  if (c.model.segment_collisions) add_segment_contact_forces(c.model, fw);
}

bool figure_impacts_present(const Model& model) {
  if (figure_contacts_present(model)) return true;
  for (const CompiledFigure& f : model.figures) {
    if (!f.limits.empty()) return true;
  }
  return false;
}

void figure_impacts(const SubstepContext& c) {
  // The obstacles where the step ends, as the bodies' collision stage places them.
  place_obstacles(c.model, c.inputs, c.state.time, c.ws.drive.obstacles);
  FiguresWorkspace& fw = *c.ws.figures;
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    const FigureModel& figure = c.model.figures[f].model;
    const FigureDef& def = c.model.scene.figures[f];
    FigureWorkspace& w = fw.each[f];
    // The joints arriving at their limits (figure/joint_limits.h), before the contacts see the
    // velocities.
    resolve_limit_impacts(figure, c.model.figures[f].limits,
                          c.state.q.data() + figure.state_q_offset,
                          c.state.v.data() + figure.state_v_offset, def.impact_speed, fw.impact);
    if (c.ws.drive.obstacles.empty()) continue;
    fw.q.head(figure.n_q) = c.state.q.segment(figure.state_q_offset, figure.n_q);
    fw.v.head(figure.n_v) = c.state.v.segment(figure.state_v_offset, figure.n_v);
    pbm::figure_kinematics(figure, fw.q.data(), fw.v.data(), w);
    segment_world_transforms(figure, w, fw.world);
    // Obstacle by obstacle (each has its own friction): the contact points approaching it
    // faster than impact_speed have their impact together, (15.1)-(15.8).
    for (const ObstacleModel& obstacle : c.ws.drive.obstacles) {
      fw.impacts.clear();
      for_each_contact(
          figure, def, w, fw.world, Obstacles(&obstacle, 1),
          [&](int i, const ContactPoint& contact, const ObstacleModel&) {
            if (contact.velocity.dot(contact.normal) < -def.impact_speed) {
              fw.impacts.push_back({.figure_a = 0,
                                    .segment_a = i,
                                    .point = contact.point,
                                    .normal = contact.normal,
                                    .surface_velocity = obstacle.velocity_at(contact.point)});
            }
          });
      if (fw.impacts.empty()) continue;
      const ImpactFigure one{&figure, fw.q.data(), fw.v.data()};
      resolve_impact({&one, 1}, fw.impacts,
                     {.restitution = def.restitution,
                      .friction = ImpactFriction::coulomb,
                      .mu = obstacle.friction},
                     fw.impact);
      c.state.v.segment(figure.state_v_offset, figure.n_v) = fw.v.head(figure.n_v);
      // The velocities changed: the next obstacle's contacts see them.
      pbm::figure_kinematics(figure, fw.q.data(), fw.v.data(), w);
    }
  }
  if (c.model.segment_collisions) segment_impacts(c);
}

bool segment_bodies_present(const Model& model) {
  if (model.bodies.empty()) return false;
  for (const FigureDef& def : model.scene.figures) {
    if (def.body_collisions) return true;
  }
  return false;
}

void size_segment_bodies(const Model& model, Workspace& ws) {
  size_segment_body_workspace(model, ws.figures->bodies);
}

void segment_body_collisions(const SubstepContext& c) {
  FiguresWorkspace& fw = *c.ws.figures;
  all_figure_kinematics(c.model, c.state.q.data(), c.state.v.data(), fw);
  const BodySet set{c.model.bodies, c.ws.bodies, c.state.q, c.state.v, c.state.time};
  c.ws.segment_body_stats =
      resolve_segment_body_collisions(c.model, set, fw.each, fw.worlds, c.dt, fw.bodies);
  c.ws.contacts += c.ws.segment_body_stats.contacts;  // the end of 5.2.2's step reduction
}

void figure_dynamics(const RateContext& c) {
  FiguresWorkspace& fw = *c.ws.figures;
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    const FigureModel& figure = c.model.figures[f].model;
    const CompiledFigure& compiled = c.model.figures[f];
    const Real* v = v_of(figure, c.v);
    joint_damping(figure, v, fw.tau.data());
    add_joint_spring_forces(figure, q_of(figure, c.q), fw.tau.data());
    add_joint_limit_forces(compiled.limits, q_of(figure, c.q), v,
                           c.model.scene.figures[f].impact_speed, fw.tau.data());
    // The explicit controllers' forces (the controllers stage ran before).
    if (compiled.actuated()) fw.tau.head(figure.n_v) += fw.control[f].tau;
    // Gravity as the base's acceleration, at its value of the moment (tracks may drive it); the
    // contact stage's forces when obstacles or liquids are present (figure_contact_forces and
    // liquid_body_forces ran before).
    const bool external_present = figure_external_forces_present(c.model);
    const std::span<const ForceVector> external =
        external_present ? std::span<const ForceVector>(fw.contact_forces[f])
                         : std::span<const ForceVector>();
    const Real* armature = implicit_damping(c.model, figure, fw);
    if (has_stable_pd(compiled)) {
      stable_pd_dynamics(c, f, external, armature);
    } else if (external_present || !compiled.site_actuators.empty()) {
      // The contact stage (or, without it, the site actuators' forces), a stage before this one
      // (sim/subsystems.cpp), left this rate's kinematics in fw.each[f].
      forward_dynamics_after_kinematics(figure, fw.tau.data(), external, c.ws.drive.gravity,
                                        fw.each[f], c.v_dot.data() + figure.state_v_offset,
                                        armature);
    } else {
      forward_dynamics(figure, q_of(figure, c.q), v, fw.tau.data(), external, c.ws.drive.gravity,
                       fw.each[f], c.v_dot.data() + figure.state_v_offset, armature);
    }
    actuator_work_rate(c, f);
  }
}

void figure_kinematics(const RateContext& c) {
  figure_kinematic_rates(c.model, c.q, c.v, c.q_dot);
}

void figure_kinematic_rates(const Model& model, const VecX& q, const VecX& v, VecX& q_dot) {
  for (const CompiledFigure& compiled : model.figures) {
    const FigureModel& figure = compiled.model;
    figure_q_dot(figure, q_of(figure, q), v_of(figure, v), q_dot.data() + figure.state_q_offset);
  }
}

void figure_renormalize(const SubstepContext& c) {
  for (const CompiledFigure& compiled : c.model.figures) {
    figure_normalize(compiled.model, c.state.q.data() + compiled.model.state_q_offset);
  }
}

void measure_figures(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                     FrameStats& stats) {
  FiguresWorkspace& fw = *ws.figures;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    FigureWorkspace& w = fw.each[f];
    pbm::figure_kinematics(figure, q_of(figure, state.q), v_of(figure, state.v), w);
    segment_world_transforms(figure, w, fw.world);
    FigureFrameStats& out = stats.figures[f];
    out.kinetic = out.potential = 0;
    for (int i = 0; i < figure.size(); ++i) {
      const SpatialInertia& I = figure.segments[i].inertia;
      const MotionVector vi = motion_from_vec6(w.v[i]);
      out.kinetic += 0.5 * dot(vi, I * vi);
      // The centre of mass in the world: x = r + E^T c for the world -> segment transform.
      const Vec3 centre = fw.world[i].r + fw.world[i].E.transpose() * I.c;
      out.potential -= I.m * ws.drive.gravity.dot(centre);
    }
    // The joint springs' energy, then the contact springs' below.
    out.elastic = joint_spring_energy(figure, q_of(figure, state.q)) +
                  joint_limit_energy(model.figures[f].limits, q_of(figure, state.q));
    out.contacts = 0;
    out.depth = 0;
    measure_figure_controllers(model.figures[f], f, inputs, state, out);
    out.site_actuators.resize(model.figures[f].site_actuators.size());
    for (std::size_t k = 0; k < out.site_actuators.size(); ++k) {
      const CompiledSiteActuator& a = model.figures[f].site_actuators[k];
      out.site_actuators[k] = site_pull(a, state.time, fw.world[a.site.segment],
                                        w.v[a.site.segment], site_target_input(inputs, f, k));
    }
    if (!figure_contacts_present(model)) continue;
    const FigureDef& def = model.scene.figures[f];
    for_each_contact(figure, def, w, fw.world, ws.drive.obstacles,
                     [&](int, const ContactPoint& contact, const ObstacleModel&) {
                       out.elastic += 0.5 * def.contact_stiffness * contact.depth * contact.depth;
                       out.depth = std::max(out.depth, contact.depth);
                       ++out.contacts;
                     });
  }
  if (!model.segment_collisions) return;
  // The springs between segments: their energy is the first figure's, their points both's.
  all_figure_kinematics(model, state.q.data(), nullptr, fw);
  collect_segment_contacts(model, fw.worlds, fw.collision, fw.segment_contacts);
  for (const SegmentContact& k : fw.segment_contacts) {
    const PairContactSettings s =
        pair_contact_settings(model.scene.figures[k.figure_a], model.scene.figures[k.figure_b]);
    stats.figures[k.figure_a].elastic += 0.5 * s.stiffness * k.depth * k.depth;
    for (const int f : {k.figure_a, k.figure_b}) {
      stats.figures[f].depth = std::max(stats.figures[f].depth, k.depth);
    }
    ++stats.figures[k.figure_a].contacts;
    if (k.figure_b != k.figure_a) ++stats.figures[k.figure_b].contacts;
  }
}

namespace {

// What to change when a figure under MRAC fails: the adaptation's error signal is weighted as
// the reference model's dynamics, 16 / t_s^2 and 4 / t_s (15.15), so its gains (15.16), (15.17)
// stiffen as 1 / t_s^2 and a short t_s needs a far shorter step (a 1 kg, 1 m link under t_s =
// 0.01 s runs at 1e-7 s, not at 1e-6 s). Empty without MRAC.
std::string mrac_hint(const CompiledFigure& figure) {
  const JointController* fastest = nullptr;
  for (const JointController& c : figure.controllers) {
    if (c.def.kind != ControllerKind::mrac) continue;
    if (!fastest || c.mrac.settling_time < fastest->mrac.settling_time) fastest = &c;
  }
  if (!fastest) return {};
  char text[96];
  std::snprintf(text, sizeof text, "%g s", fastest->mrac.settling_time);
  return "; its MRAC adapts with gains that stiffen as 1 / t_s^2 (15.15)-(15.17), t_s down to " +
         std::string(text) + " on '" + fastest->def.joint +
         "': a longer settling_time or smaller alpha and beta let it run at this step";
}

}  // namespace

std::string describe_figure_failure(const Model& model, const State& state) {
  for (const CompiledFigure& compiled : model.figures) {
    const FigureModel& figure = compiled.model;
    for (const SegmentModel& s : figure.segments) {
      const auto q =
          state.q.segment(figure.state_q_offset + s.q_offset, joint_q_size(s.joint.kind));
      const auto v =
          state.v.segment(figure.state_v_offset + s.v_offset, joint_v_size(s.joint.kind));
      if (q.allFinite() && v.allFinite()) continue;
      return "figure '" + figure.name + "', segment '" + s.name + "': its joint's " +
             (q.allFinite() ? "velocity" : "position") + " became NaN or infinite" +
             mrac_hint(compiled);
    }
    if (!state.q.segment(compiled.state_control_offset, compiled.n_control).allFinite()) {
      return "figure '" + figure.name + "': its controllers' state (MRAC's model and integrals, " +
             "the actuators' work) became NaN or infinite" + mrac_hint(compiled);
    }
  }
  return {};
}

void add_figure_drawables(const Model& model, const Inputs& inputs, const State& state,
                          Workspace& ws, draw::Snapshot& snap) {
  FiguresWorkspace& fw = *ws.figures;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureModel& figure = model.figures[f].model;
    const FigureDef& def = model.scene.figures[f];
    pbm::figure_kinematics(figure, q_of(figure, state.q), nullptr, fw.each[f]);
    segment_world_transforms(figure, fw.each[f], fw.world);
    for (int i = 0; i < figure.size(); ++i) {
      const SegmentShapeDef& shape = def.segments[i].shape;
      const Mat3 to_world = fw.world[i].E.transpose();
      draw::Primitive& p = snap.primitives.emplace_back();
      p.shape = primitive_of(shape.kind);
      p.center = (fw.world[i].r + to_world * shape.center).cast<float>();
      p.rotation = (to_world * rotation_from_quaternion(shape.orientation)).cast<float>();
      p.half_size = shape.size.cast<float>();
      p.material.color = def.segments[i].color.cast<float>();
      p.material.roughness = 0.6f;
      p.figure = static_cast<int>(f);
      p.segment = i;
      // The shape's bounding sphere frames an automatic camera.
      const float reach = static_cast<float>(shape.size.norm());
      snap.focus.add(p.center - draw::Vec3f::Constant(reach));
      snap.focus.add(p.center + draw::Vec3f::Constant(reach));
    }
    add_joint_overlays(figure, def, fw.world, snap);
    add_event_drawables(model.figures[f], f, inputs, state.time, fw.world, snap);
  }
}

}  // namespace pbm::stages
