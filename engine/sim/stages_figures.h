// Articulated figures' part of the step (figure/, ch. 15): each figure's accelerations by the
// articulated-body method with its joint damping among the rates (sec. 15.2), q-dot from v, unit
// quaternions after the step, contacts with obstacles in the book's two stages (impact, then
// mild spring-dampers: sec. 15.3), the energies the stability guard watches, and the segments'
// shapes to draw. Rows of the subsystem table (sim/subsystems.cpp).
#pragma once

#include "sim/subsystem.h"

namespace pbm::stages {

bool figures_present(const Model& model);
void size_figures(const Model& model, Workspace& ws);
// Every figure's kinematics at (q, v) (v may be null) and its segments' world transforms, into
// fw.each and fw.worlds.
void all_figure_kinematics(const Model& model, const Real* q, const Real* v, FiguresWorkspace& fw);
// Whether forces act on segments beyond gravity, the joints and the actuators: the contact stage's
// (obstacles, other segments) and the liquids' (sim/stages_liquid.h), in fw.contact_forces, with
// that rate's kinematics in fw.each and fw.worlds.
bool figure_external_forces_present(const Model& model);
// Contacts with obstacles (sec. 15.3): the contact stage's spring-dampers among the rates, the
// impact stage after the step.
bool figure_contacts_present(const Model& model);
void figure_contact_forces(const RateContext& c);  // contact_forces
// The impact stage runs where contacts can happen or a joint has limits.
bool figure_impacts_present(const Model& model);
void figure_impacts(const SubstepContext& c);  // impacts: (15.1)-(15.8), joint limits
// Segments with deformable bodies (sim/segment_body_collisions.h), after the step at the
// body_collisions stage: present where a figure with body_collisions meets a scene with bodies.
bool segment_bodies_present(const Model& model);
void size_segment_bodies(const Model& model, Workspace& ws);
void segment_body_collisions(const SubstepContext& c);
void figure_dynamics(const RateContext& c);    // dynamics: sec. 15.2, the articulated-body method
void figure_kinematics(const RateContext& c);  // kinematics: q-dot from v
void figure_kinematic_rates(const Model& model, const VecX& q, const VecX& v, VecX& q_dot);
void figure_renormalize(const SubstepContext& c);  // renormalize: unit quaternions (sec. 6.1)
void measure_figures(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                     FrameStats& stats);
std::string describe_figure_failure(const Model& model, const State& state);
void add_figure_drawables(const Model& model, const Inputs& inputs, const State& state,
                          Workspace& ws, draw::Snapshot& snap);

}  // namespace pbm::stages
