#include "sim/stages_figure_control.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "figure/figure_impact.h"
#include "figure/figure_impulse.h"
#include "figure/figure_kinematics.h"
#include "figure/inverse_dynamics.h"
#include "figure/stable_pd.h"
#include "sim/stages_figures.h"

namespace pbm::stages {

namespace {

Real limit_of(const JointController& c) {
  return c.def.max_output.value_or(std::numeric_limits<Real>::infinity());
}

}  // namespace

std::optional<LiveKey> control_input(const Inputs& inputs, std::size_t f, std::size_t k) {
  for (const ControlInput& in : inputs.controls) {
    if (in.figure == static_cast<int>(f) && in.controller == static_cast<int>(k)) {
      return LiveKey{in.time, in.value, in.rate};
    }
  }
  return std::nullopt;
}

std::optional<HeldSiteTarget> site_target_input(const Inputs& inputs, std::size_t f,
                                                std::size_t k) {
  for (const SiteTargetInput& in : inputs.site_targets) {
    if (in.figure == static_cast<int>(f) && in.actuator == static_cast<int>(k)) {
      return HeldSiteTarget{in.time, in.target};
    }
  }
  return std::nullopt;
}

bool figure_step_start_present(const Model& model) {
  for (const CompiledFigure& figure : model.figures) {
    if (figure.actuated() || !figure.impulses.empty()) return true;
    // Implicit joint damping needs the substep's length (fw.step).
    for (const SegmentModel& s : figure.model.segments) {
      if (s.damping > 0) return true;
    }
  }
  return false;
}

bool has_stable_pd(const CompiledFigure& figure) {
  for (const JointController& c : figure.controllers) {
    if (c.def.kind == ControllerKind::stable_pd) return true;
  }
  return false;
}

void size_figure_controllers(const Model& model, Workspace& ws) {
  FiguresWorkspace& fw = *ws.figures;
  fw.control.resize(model.figures.size());
  fw.step = model.substep;
  int n_v = 0, segments = 0;
  for (const CompiledFigure& figure : model.figures) {
    if (figure.site_actuators.empty() && figure.impulses.empty()) continue;
    n_v = std::max(n_v, figure.model.n_v);
    segments = std::max(segments, figure.model.size());
  }
  fw.site_forces.assign(static_cast<std::size_t>(segments), ForceVector{});
  size_impulse_scratch(n_v, segments, fw.impulse);
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const CompiledFigure& figure = model.figures[f];
    if (!figure.actuated()) continue;
    const int n = figure.model.n_v;
    FigureControlWorkspace& w = fw.control[f];
    for (VecX* x : {&w.tau, &w.Kp, &w.Kd, &w.q_target, &w.v_target, &w.tau_ext, &w.qdd, &w.tau_pd})
      x->setZero(n);
    if (!has_stable_pd(figure)) continue;
    // The solve's own matrices, sized once so that a step allocates nothing.
    w.pd.H.setZero(n, n);
    w.pd.C.setZero(n);
    w.pd.rhs.setZero(n);
    w.pd.zero.setZero(n);
    w.pd.llt.compute(MatX::Identity(n, n));
  }
}

void figure_step_start(const SubstepContext& c) {
  FiguresWorkspace& fw = *c.ws.figures;
  fw.step = c.dt;
  // The impulse events not yet applied whose time falls before the substep's end, at its start:
  // each once (State::impulses_applied), at most one substep early. A retried frame restarts
  // from its start state, count included, and applies them again.
  const Real t1 = c.state.time + c.dt;
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    const CompiledFigure& figure = c.model.figures[f];
    if (figure.impulses.empty()) continue;
    int& applied = c.state.impulses_applied[f];
    for (; applied < static_cast<int>(figure.impulses.size()); ++applied) {
      const CompiledImpulse& impulse = figure.impulses[applied];
      if (impulse.time >= t1) break;
      const Real work = apply_impulse(figure.model, c.state.q.data() + figure.model.state_q_offset,
                                      c.state.v.data() + figure.model.state_v_offset, impulse,
                                      fw.impulse, fw.each[f]);
      c.state.q[figure.state_control_offset] += work;  // input work for the guard
    }
  }
}

void figure_controllers(const RateContext& c) {
  FiguresWorkspace& fw = *c.ws.figures;
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    const CompiledFigure& figure = c.model.figures[f];
    if (!figure.actuated()) continue;
    FigureControlWorkspace& w = fw.control[f];
    w.tau.setZero();
    const Real* q = c.q.data() + figure.model.state_q_offset;
    const Real* v = c.v.data() + figure.model.state_v_offset;
    const Real* state = c.q.data() + figure.state_control_offset;
    Real* rate = c.q_dot.data() + figure.state_control_offset;
    for (std::size_t k = 0; k < figure.controllers.size(); ++k) {
      const JointController& ctrl = figure.controllers[k];
      if (ctrl.def.kind == ControllerKind::stable_pd) continue;
      const int s = std::max(ctrl.state_offset, 0);
      const ControlledCoordinate x = controlled_coordinate(ctrl, q, v);
      const Real u = explicit_control(ctrl, c.t, x.x, x.x_dot, state + s, rate + s,
                                      control_input(c.inputs, f, k))
                         .output;
      add_controller_output(ctrl, x, u, w.tau.data());
    }
    if (!figure.site_actuators.empty()) add_site_actuator_forces(c, f);
  }
}

void add_site_actuator_forces(const RateContext& c, std::size_t f) {
  FiguresWorkspace& fw = *c.ws.figures;
  const CompiledFigure& figure = c.model.figures[f];
  const FigureModel& model = figure.model;
  FigureWorkspace& each = fw.each[f];
  // With contacts, figure_contact_forces, the rate stage before this one (sim/subsystems.cpp),
  // has left this rate's kinematics and world transforms in fw.each and fw.worlds; without, they
  // are computed here, once.
  const bool known = figure_contacts_present(c.model);
  if (!known) {
    figure_kinematics(model, c.q.data() + model.state_q_offset, c.v.data() + model.state_v_offset,
                      each);
    segment_world_transforms(model, each, fw.world);
  }
  const std::vector<SpatialTransform>& world = known ? fw.worlds[f] : fw.world;
  const std::span<ForceVector> forces(fw.site_forces.data(),
                                      static_cast<std::size_t>(model.size()));
  for (ForceVector& force : forces) force = ForceVector{};
  for (std::size_t k = 0; k < figure.site_actuators.size(); ++k) {
    const CompiledSiteActuator& a = figure.site_actuators[k];
    const int i = a.site.segment;
    const SitePull pull = site_pull(a, c.t, world[i], each.v[i], site_target_input(c.inputs, f, k));
    forces[i] += site_pull_force(a, world[i], pull);
  }
  add_external_joint_forces(model, forces, each, fw.control[f].tau.data());
}

void stable_pd_dynamics(const RateContext& c, std::size_t f, std::span<const ForceVector> external,
                        const Real* armature) {
  FiguresWorkspace& fw = *c.ws.figures;
  const CompiledFigure& figure = c.model.figures[f];
  const FigureModel& model = figure.model;
  FigureControlWorkspace& w = fw.control[f];
  fw.q.head(model.n_q) = c.q.segment(model.state_q_offset, model.n_q);
  fw.v.head(model.n_v) = c.v.segment(model.state_v_offset, model.n_v);
  w.Kp.setZero();
  w.Kd.setZero();
  w.q_target.setZero();
  w.v_target.setZero();
  for (std::size_t k = 0; k < figure.controllers.size(); ++k) {
    const JointController& ctrl = figure.controllers[k];
    if (ctrl.def.kind != ControllerKind::stable_pd) continue;
    const DesiredMotion d = controller_desired(ctrl, c.t, control_input(c.inputs, f, k));
    w.Kp[ctrl.v_index] = ctrl.def.kp;
    w.Kd[ctrl.v_index] = ctrl.def.kd;
    w.q_target[ctrl.v_index] = d.q;
    w.v_target[ctrl.v_index] = d.q_dot;
  }
  w.tau_ext = fw.tau.head(model.n_v);
  // A servo whose torque would pass its limit gives the limit instead, as a known force, and the
  // solve is repeated without its gains, until no other servo passes its own (at most once per
  // servo).
  for (;;) {
    stable_pd_accelerations(model, fw.q, fw.v, w.tau_ext, external, c.ws.drive.gravity, w.Kp, w.Kd,
                            w.q_target, w.v_target, fw.step, fw.each[f], w.pd, w.qdd, w.tau_pd,
                            armature);
    bool cut = false;
    for (const JointController& ctrl : figure.controllers) {
      const int i = ctrl.v_index;
      if (ctrl.def.kind != ControllerKind::stable_pd || (w.Kp[i] == 0 && w.Kd[i] == 0)) continue;
      const Real limit = limit_of(ctrl);
      if (!(std::abs(w.tau_pd[i]) > limit)) continue;
      // The output on its coordinate (a ball's r_k: the torque J_r^-T e_k per unit).
      const ControlledCoordinate x = controlled_coordinate(ctrl, fw.q.data(), fw.v.data());
      add_controller_output(ctrl, x, std::clamp(w.tau_pd[i], -limit, limit), w.tau_ext.data());
      add_controller_output(ctrl, x, std::clamp(w.tau_pd[i], -limit, limit), w.tau.data());
      w.Kp[i] = w.Kd[i] = 0;
      cut = true;
    }
    if (!cut) break;
  }
  for (const JointController& ctrl : figure.controllers) {
    const int i = ctrl.v_index;
    if (ctrl.def.kind != ControllerKind::stable_pd || (w.Kp[i] == 0 && w.Kd[i] == 0)) continue;
    add_controller_output(ctrl, controlled_coordinate(ctrl, fw.q.data(), fw.v.data()), w.tau_pd[i],
                          w.tau.data());
  }
  c.v_dot.segment(model.state_v_offset, model.n_v) = w.qdd;
}

void actuator_work_rate(const RateContext& c, std::size_t f) {
  const CompiledFigure& figure = c.model.figures[f];
  if (!figure.actuated()) return;
  const FigureModel& model = figure.model;
  const FiguresWorkspace& fw = *c.ws.figures;
  const auto v = c.v.segment(model.state_v_offset, model.n_v);
  // The power u . q-dot. Euler's step (6.1) moves q with the new velocity, so the work of the
  // forces it holds over the step is u . v_new dt, v_new = v + dt v-dot: counted at v, a stiff
  // servo's first step would do no work while the figure gains its energy. The Runge-Kutta
  // integrators take the power at each stage as it is.
  const IntegratorKind kind = c.model.solver.integrator;
  if (kind == IntegratorKind::euler || kind == IntegratorKind::implicit) {
    c.q_dot[figure.state_control_offset] =
        fw.control[f].tau.dot(v + fw.step * c.v_dot.segment(model.state_v_offset, model.n_v));
  } else {
    c.q_dot[figure.state_control_offset] = fw.control[f].tau.dot(v);
  }
}

void measure_figure_controllers(const CompiledFigure& figure, std::size_t f, const Inputs& inputs,
                                const State& state, FigureFrameStats& out) {
  out.controllers.resize(figure.controllers.size());
  const Real* control = state.q.data() + figure.state_control_offset;
  out.work = figure.n_control > 0 ? control[0] : 0;
  const Real* q = state.q.data() + figure.model.state_q_offset;
  const Real* v = state.v.data() + figure.model.state_v_offset;
  for (std::size_t k = 0; k < figure.controllers.size(); ++k) {
    const JointController& c = figure.controllers[k];
    const ControlledCoordinate x = controlled_coordinate(c, q, v);
    const Real qi = x.x, vi = x.x_dot;
    const std::optional<LiveKey> held = control_input(inputs, f, k);
    if (c.def.kind != ControllerKind::stable_pd) {
      Real rate[kMracStateSize];
      out.controllers[k] = explicit_control(c, state.time, qi, vi,
                                            control + std::max(c.state_offset, 0), rate, held);
      continue;
    }
    // The servo's spring-damper at the state; the step applies it at the step's end (within the
    // same limit), which differs from this by O(dt).
    const DesiredMotion d = controller_desired(c, state.time, held);
    const Real u = c.def.kp * (d.q - qi) + c.def.kd * (d.q_dot - vi);
    const Real limit = limit_of(c);
    out.controllers[k] = {.desired = d.q,
                          .reference = d.q,
                          .actual = qi,
                          .output = std::clamp(u, -limit, limit),
                          .saturated = std::abs(u) > limit};
  }
}

}  // namespace pbm::stages
