// The figures' joint controllers, site actuators and impulse events in the step (secs. 15.3,
// 15.4, control/): MRAC and PD servos and the site actuators in the controllers stage, their
// outputs joining the figure's joint forces; stable PD servos inside the dynamics stage, whose
// solve they change (figure/stable_pd.h); impulse events at the start of the substep that holds
// them; the rates of the controllers' state (MRAC's reference model and integrals, the
// actuators' work) and what a frame reports of them. Parts of the figures' row of the subsystem
// table (sim/subsystems.cpp).
#pragma once

#include <optional>
#include <span>

#include "figure/site_actuator.h"
#include "sim/subsystem.h"

namespace pbm::stages {

// Whether any figure has actuators or impulse events (the step_start hook's presence).
bool figure_step_start_present(const Model& model);
void size_figure_controllers(const Model& model, Workspace& ws);
// step_start: the stable PD's and the work rate's step length; the impulse events that fall in
// the substep, applied to the state at its start (figure/figure_impulse.h), their work added to
// the actuators'.
void figure_step_start(const SubstepContext& c);
// controllers: MRAC and PD outputs, MRAC rates, the site actuators' joint forces.
void figure_controllers(const RateContext& c);

// Figure f's site actuators (figure/site_actuator.h) at the rate's (t, q, v): their J^T F added
// to its actuators' forces.
void add_site_actuator_forces(const RateContext& c, std::size_t f);

// Figure f's accelerations (its slice of c.v_dot) under its stable PD servos, with the joint
// forces ws.figures->tau (damping and the explicit controllers) and the external forces on its
// segments; their torque joins the actuators' forces.
// armature: the figure's implicit joint damping (n_v), or null.
void stable_pd_dynamics(const RateContext& c, std::size_t f, std::span<const ForceVector> external,
                        const Real* armature);
bool has_stable_pd(const CompiledFigure& figure);

// The rate of the actuators' work, sum of u q-dot, once every actuator's force is known.
void actuator_work_rate(const RateContext& c, std::size_t f);

// The work done so far and each controller's sample at `state` (ws.drive at state.time), for
// figure f with the inputs of the moment.
void measure_figure_controllers(const CompiledFigure& figure, std::size_t f, const Inputs& inputs,
                                const State& state, FigureFrameStats& out);

// The control panel's target on controller k of figure f, if one is set (sim/inputs.h).
std::optional<LiveKey> control_input(const Inputs& inputs, std::size_t f, std::size_t k);
// A mouse drag's target on site actuator k of figure f, if one is set (sim/inputs.h).
std::optional<HeldSiteTarget> site_target_input(const Inputs& inputs, std::size_t f, std::size_t k);

}  // namespace pbm::stages
