#include "frame_output.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "sim/level_of_detail.h"

namespace pbm {
namespace {

void append_number(std::string& out, double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  out += buf;
}

void append_array(std::string& out, const Eigen::Ref<const VecX>& x) {
  out += '[';
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (i) out += ',';
    append_number(out, x[i]);
  }
  out += ']';
}

// {"name":..., "q":[...], "v":[...]}: a body's or a figure's part of a state line.
void append_part(std::string& out, const std::string& name, const Eigen::Ref<const VecX>& q,
                 const Eigen::Ref<const VecX>& v) {
  out += "{\"name\":" + nlohmann::json(name).dump() + ",\"q\":";
  append_array(out, q);
  out += ",\"v\":";
  append_array(out, v);
  out += '}';
}

}  // namespace

std::string state_json_line(const Model& model, const State& state, long frame) {
  std::string out = "{\"frame\":" + std::to_string(frame) + ",\"time\":";
  append_number(out, state.time);
  out += ",\"bodies\":[";
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    if (b) out += ',';
    append_part(out, body.name, state.q.segment(body.q_offset, body.q_size),
                state.v.segment(body.v_offset, body.v_size));
  }
  out += ']';
  // Figures (ch. 15): their joint coordinates and velocities, left out of scenes without any so
  // that those files stay as they were.
  if (!model.figures.empty()) {
    out += ",\"figures\":[";
    for (std::size_t f = 0; f < model.figures.size(); ++f) {
      const FigureModel& figure = model.figures[f].model;
      if (f) out += ',';
      append_part(out, figure.name, state.q.segment(figure.state_q_offset, figure.n_q),
                  state.v.segment(figure.state_v_offset, figure.n_v));
    }
    out += ']';
  }
  out += "}\n";
  return out;
}

std::string frame_stats_json(const World& world, const FrameStats& s, long frame) {
  const Model& model = *world.model;
  nlohmann::json j;
  j["frame"] = frame;
  j["time"] = s.time;
  j["wall_seconds"] = s.wall_seconds;
  j["substeps"] = s.substeps;
  j["retries"] = s.retries;
  j["rejected_steps"] = s.rejected;
  j["evaluations"] = s.evaluations;
  j["kinetic_energy"] = s.kinetic;
  j["elastic_energy"] = s.elastic;
  j["potential_energy"] = s.potential;
  j["energy_surplus"] = s.energy_surplus;
  j["energy_surplus_limit"] = s.energy_limit;
  j["min_obstacle_distance"] =
      model.obstacles.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.min_distance);
  j["contact_nodes"] = s.contacts;
  if (!model.constraints.empty()) j["constraint_violation"] = s.constraint_violation;
  if (auto_levels_present(model)) {
    j["dormant_bodies"] = s.levels.dormant_bodies;
    j["level_switches"] = s.levels.switches;
    j["level_energy_jump"] = s.levels.energy_jump;
    j["level_position_jump"] = s.levels.position_jump;
  }
  if (!s.notes.empty()) j["notes"] = s.notes;
  // Every stage and every subsystem on its own clock (sim/step_stage.h): a stage no subsystem of
  // the scene runs in reports 0, a subsystem the scene lacks is left out.
  nlohmann::json stages;
  for (int k = 0; k < kStageCount; ++k) {
    stages[stage_name(static_cast<StepStage>(k))] = s.stage_seconds[k];
  }
  j["stage_seconds"] = stages;
  nlohmann::json subsystems;
  for (const Subsystem* subsystem : world.subsystems) {
    subsystems[subsystem_name(subsystem->id)] =
        s.subsystem_seconds[static_cast<int>(subsystem->id)];
  }
  j["subsystem_seconds"] = subsystems;
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const BodyFrameStats& bs = s.bodies[b];
    bodies.push_back({{"name", model.bodies[b].name},
                      {"q_s", std::vector<double>(bs.q_s.data(), bs.q_s.data() + bs.q_s.size())},
                      {"position", {bs.position.x(), bs.position.y(), bs.position.z()}},
                      {"kinetic_energy", bs.kinetic},
                      {"elastic_energy", bs.elastic}});
  }
  j["bodies"] = bodies;
  if (!model.figures.empty()) {
    nlohmann::json figures = nlohmann::json::array();
    for (std::size_t f = 0; f < s.figures.size(); ++f) {
      const FigureFrameStats& fs = s.figures[f];
      const CompiledFigure& compiled = model.figures[f];
      nlohmann::json figure = {{"name", compiled.model.name},      {"kinetic_energy", fs.kinetic},
                               {"potential_energy", fs.potential}, {"elastic_energy", fs.elastic},
                               {"contacts", fs.contacts},          {"contact_depth", fs.depth}};
      // The controllers' plot of figs. 15.7, 15.8: desired, reference model and actual position
      // per controlled DOF, with the actuator's output.
      if (compiled.n_control > 0) figure["actuator_work"] = fs.work;
      if (!compiled.controllers.empty()) {
        nlohmann::json controllers = nlohmann::json::array();
        for (std::size_t k = 0; k < compiled.controllers.size(); ++k) {
          const JointController& c = compiled.controllers[k];
          const ControlSample& sample = fs.controllers[k];
          controllers.push_back({{"joint", c.def.joint},
                                 {"dof", c.def.dof},
                                 {"desired", sample.desired},
                                 {"reference", sample.reference},
                                 {"actual", sample.actual},
                                 {"output", sample.output},
                                 {"saturated", sample.saturated}});
        }
        figure["controllers"] = std::move(controllers);
      }
      // The strings of site trajectories: where each pulls, where its site is, and how hard.
      if (!compiled.site_actuators.empty()) {
        const auto xyz = [](const Vec3& x) { return nlohmann::json{x.x(), x.y(), x.z()}; };
        nlohmann::json actuators = nlohmann::json::array();
        for (std::size_t k = 0; k < compiled.site_actuators.size(); ++k) {
          const SiteActuatorDef& d = compiled.site_actuators[k].def;
          const SitePull& pull = fs.site_actuators[k];
          actuators.push_back({{"segment", d.segment},
                               {"site", d.site},
                               {"target", xyz(pull.target)},
                               {"position", xyz(pull.position)},
                               {"force", xyz(pull.force)},
                               {"saturated", pull.saturated}});
        }
        figure["site_actuators"] = std::move(actuators);
      }
      figures.push_back(std::move(figure));
    }
    j["figures"] = figures;
  }
  // Segments with bodies (sim/segment_body_collisions.h), the frame's last substep.
  const bool segment_bodies =
      std::any_of(world.subsystems.begin(), world.subsystems.end(),
                  [](const Subsystem* k) { return k->id == SubsystemId::segment_bodies; });
  if (segment_bodies) {
    const SegmentBodyStats& sb = s.segment_bodies;
    j["segment_bodies"] = {{"contacts", sb.contacts},
                           {"penetrating", sb.penetrating},
                           {"max_penetration", sb.max_penetration},
                           {"normal_impulse", sb.normal_impulse},
                           {"pressing", sb.pressing},
                           {"push_impulse", sb.push_impulse}};
  }
  // Each liquid (sim/stages_liquid.h): what it holds and what its own substeps cost.
  if (!model.liquids.empty()) {
    nlohmann::json liquids = nlohmann::json::array();
    for (std::size_t l = 0; l < s.liquids.size(); ++l) {
      const LiquidFrameStats& ls = s.liquids[l];
      const LiquidStepStats& st = ls.step;
      liquids.push_back({{"name", model.liquids[l].def.name},
                         {"volume", ls.volume},
                         {"markers", ls.markers},
                         {"kinetic_energy", ls.kinetic},
                         {"max_speed", ls.max_speed},
                         {"substeps", st.substeps},
                         {"dt_min", st.dt_min},
                         {"dt_max", st.dt_max},
                         {"cfl", st.cfl},
                         {"pressure_iterations", st.iterations},
                         {"max_pressure_iterations", st.max_iterations},
                         {"unconverged_solves", st.unconverged},
                         {"cfl_retries", st.cfl_retries},
                         {"divergence", st.divergence},
                         {"markers_removed", st.removed},
                         {"markers_dropped", st.dropped},
                         {"solid_cells", st.solid_cells},
                         {"markers_pushed", st.pushed},
                         {"spray", ls.spray},
                         {"foam", ls.foam},
                         {"spray_emitted", st.spray_emitted},
                         {"foam_landed", st.foam_landed},
                         {"chain_joins", st.chain_joins},
                         {"chain_loops_dropped", st.chain_loops_dropped},
                         {"solve_seconds", st.solve_seconds}});
      if (!model.bodies.empty()) {
        const Vec3& f = ls.body_force;
        liquids.back()["body_force"] = {f.x(), f.y(), f.z()};
        liquids.back()["wetted_area"] = ls.wetted_area;
      }
    }
    j["liquids"] = std::move(liquids);
  }
  return j.dump();
}

}  // namespace pbm
