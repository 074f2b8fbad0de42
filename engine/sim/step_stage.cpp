#include "sim/step_stage.h"

namespace pbm {

const char* stage_name(StepStage stage) {
  switch (stage) {
    case StepStage::drive:
      return "drive";
    case StepStage::step_start:
      return "step_start";
    case StepStage::forces:
      return "forces";
    case StepStage::contact_forces:
      return "contact_forces";
    case StepStage::controllers:
      return "controllers";
    case StepStage::dynamics:
      return "dynamics";
    case StepStage::constraints:
      return "constraints";
    case StepStage::kinematics:
      return "kinematics";
    case StepStage::integrate:
      return "integrate";
    case StepStage::renormalize:
      return "renormalize";
    case StepStage::impacts:
      return "impacts";
    case StepStage::body_collisions:
      return "body_collisions";
    case StepStage::obstacle_collisions:
      return "obstacle_collisions";
    case StepStage::velocity_split:
      return "velocity_split";
    case StepStage::self_collisions:
      return "self_collisions";
    case StepStage::constraint_projection:
      return "constraint_projection";
    case StepStage::liquid:
      return "liquid";
    case StepStage::coupling:
      return "coupling";
    case StepStage::measure:
      return "measure";
    case StepStage::count:
      break;
  }
  return "?";
}

const char* subsystem_name(SubsystemId id) {
  switch (id) {
    case SubsystemId::bodies:
      return "bodies";
    case SubsystemId::obstacles:
      return "obstacles";
    case SubsystemId::body_collisions:
      return "body_collisions";
    case SubsystemId::self_collision:
      return "self_collision";
    case SubsystemId::constraints:
      return "constraints";
    case SubsystemId::figures:
      return "figures";
    case SubsystemId::segment_bodies:
      return "segment_bodies";
    case SubsystemId::liquids:
      return "liquids";
    case SubsystemId::liquid_bodies:
      return "liquid_bodies";
    case SubsystemId::count:
      break;
  }
  return "?";
}

}  // namespace pbm
