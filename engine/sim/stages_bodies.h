// The deformable bodies' part of the step (deform/): their forces, dynamics and kinematic rates,
// the renormalization after the integrator, the mean-axis split where no obstacle stage restores
// it, their measurements and the guard's view of them. Rows of the subsystem table
// (sim/subsystems.cpp).
#pragma once

#include <string>

#include "sim/subsystem.h"

namespace pbm::stages {

bool bodies_present(const Model& model);
void size_bodies(const Model& model, Workspace& ws);
void body_step_start(const SubstepContext& c);  // step_start: the substep's dt
void body_forces(const RateContext& c);         // forces: kinematics, K q_d, loads, A
void body_dynamics(const RateContext& c);       // dynamics: (3.13) / (3.51)
void body_kinematics(const RateContext& c);     // kinematics: q-dot, first-order v
void body_kinematic_rates(const Model& model, const VecX& q, const VecX& v, VecX& q_dot);
void body_renormalize(const SubstepContext& c);     // renormalize: unit quaternions (sec. 6.1)
bool velocity_split_needed(const Model& model);     // no obstacle stage restores the split
void body_velocity_split(const SubstepContext& c);  // velocity_split, a frame's last substep
void measure_bodies(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                    FrameStats& stats);
Real body_energy_allowance(const Model& model, const Inputs& inputs, const State& state, Real t_end,
                           Workspace& ws);
std::string describe_body_failure(const Model& model, const State& state);
void add_body_drawables(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                        draw::Snapshot& snap);

}  // namespace pbm::stages
