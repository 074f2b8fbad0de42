// The subsystem table (docs/architecture.md, "Adding a subsystem"): one row per subsystem, its
// hooks by stage. Table order is the order of measurements, allowances and drawables; the hooks
// run in the order of their stages (sim/step_stage.h), within a stage in table order.
#include "sim/stages_bodies.h"
#include "sim/stages_collisions.h"
#include "sim/stages_constraints.h"
#include "sim/stages_figure_control.h"
#include "sim/stages_figures.h"
#include "sim/stages_liquid.h"
#include "sim/stages_obstacles.h"
#include "sim/subsystem.h"

namespace pbm {
namespace {

using S = StepStage;

constexpr Subsystem kTable[] = {
    {.id = SubsystemId::bodies,
     .present = stages::bodies_present,
     .size_workspace = stages::size_bodies,
     .rates = {{{S::forces, stages::body_forces},
                {S::dynamics, stages::body_dynamics},
                {S::kinematics, stages::body_kinematics}}},
     .kinematic_rates = stages::body_kinematic_rates,
     .substep = {{{S::step_start, stages::body_step_start},
                  {S::renormalize, stages::body_renormalize},
                  {S::velocity_split, stages::body_velocity_split, stages::velocity_split_needed}}},
     .measure = stages::measure_bodies,
     .energy_allowance = stages::body_energy_allowance,
     .describe_failure = stages::describe_body_failure,
     .add_drawables = stages::add_body_drawables},
    {.id = SubsystemId::body_collisions,
     .present = stages::body_collisions_present,
     .size_workspace = stages::size_body_collisions,
     .substep = {{{S::body_collisions, stages::resolve_pairs_of_bodies}}}},
    {.id = SubsystemId::obstacles,
     .present = stages::obstacles_present,
     .rates = {{{S::contact_forces, stages::obstacle_forces}}},
     .substep = {{{S::obstacle_collisions, stages::obstacle_collisions}}},
     .measure = stages::measure_obstacles,
     .energy_allowance = stages::obstacle_energy_allowance,
     .add_drawables = stages::add_obstacle_drawables},
    {.id = SubsystemId::self_collision,
     .present = stages::self_collision_present,
     .size_workspace = stages::size_body_collisions,
     .substep = {{{S::step_start, stages::record_self_collision_start},
                  {S::self_collisions, stages::resolve_bodies_with_themselves}}}},
    {.id = SubsystemId::constraints,
     .present = stages::constraints_present,
     .size_workspace = stages::size_constraints,
     .rates = {{{S::constraints, stages::constraint_rates}}},
     .substep = {{{S::renormalize, stages::record_constraints,
                   stages::constraint_projection_needed},
                  {S::constraint_projection, stages::project_constraints,
                   stages::constraint_projection_needed}}},
     .measure = stages::measure_constraints,
     .energy_allowance = stages::constraint_allowance,
     .add_drawables = stages::add_constraint_drawables},
    {.id = SubsystemId::figures,
     .present = stages::figures_present,
     .size_workspace = stages::size_figures,
     .rates = {{{S::contact_forces, stages::figure_contact_forces},
                {S::controllers, stages::figure_controllers},
                {S::dynamics, stages::figure_dynamics},
                {S::kinematics, stages::figure_kinematics}}},
     .kinematic_rates = stages::figure_kinematic_rates,
     .substep = {{{S::step_start, stages::figure_step_start, stages::figure_step_start_present},
                  {S::renormalize, stages::figure_renormalize},
                  {S::impacts, stages::figure_impacts, stages::figure_impacts_present}}},
     .measure = stages::measure_figures,
     .describe_failure = stages::describe_figure_failure,
     .add_drawables = stages::add_figure_drawables},
    {.id = SubsystemId::segment_bodies,
     .present = stages::segment_bodies_present,
     .size_workspace = stages::size_segment_bodies,
     .substep = {{{S::body_collisions, stages::segment_body_collisions}}}},
    {.id = SubsystemId::liquids,
     .present = stages::liquids_present,
     .size_workspace = stages::size_liquids,
     .substep = {{{S::liquid, stages::advance_liquids}}},
     .measure = stages::measure_liquids,
     .describe_failure = stages::describe_liquid_failure,
     .add_drawables = stages::add_liquid_drawables},
    {.id = SubsystemId::liquid_bodies,
     .present = stages::liquid_bodies_present,
     .size_workspace = stages::size_liquid_bodies,
     .rates = {{{S::contact_forces, stages::liquid_body_forces}}},
     .substep = {{{S::step_start, stages::liquid_probe_start},
                  {S::coupling, stages::liquid_body_work}}}},
};

}  // namespace

std::span<const Subsystem> subsystem_table() {
  return kTable;
}

}  // namespace pbm
