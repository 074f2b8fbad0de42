#include "figure/figure_controllers.h"

#include <cmath>

#include "core/error.h"
#include "figure/articulated_body.h"
#include "figure/figure_build.h"

namespace pbm {

namespace {

bool scalar_joint(JointKind kind) {
  return kind == JointKind::revolute || kind == JointKind::prismatic ||
         kind == JointKind::universal;
}

void require(bool ok, const std::string& file, const std::string& path, const char* message) {
  if (!ok) throw Error(file, path, message);
}

}  // namespace

std::vector<JointController> compile_figure_controllers(const FigureDef& def,
                                                        const FigureModel& figure,
                                                        const std::string& file,
                                                        const std::string& path) {
  std::vector<JointController> out;
  out.reserve(def.controllers.size());
  int state = 1;  // entry 0: the actuators' work
  for (std::size_t k = 0; k < def.controllers.size(); ++k) {
    const ControllerDef& d = def.controllers[k];
    const std::string at = path + ".controllers[" + std::to_string(k) + "]";
    JointController c;
    c.def = d;
    c.segment = -1;
    for (int i = 0; i < figure.size(); ++i) {
      if (figure.segments[i].name == d.joint) c.segment = i;
    }
    if (c.segment < 0) {
      throw Error(file, at + ".joint",
                  "'" + d.joint + "' names no segment of figure '" + figure.name + "'");
    }
    const SegmentModel& s = figure.segments[c.segment];
    if (!scalar_joint(s.joint.kind)) {
      throw Error(file, at + ".joint",
                  "segment '" + d.joint +
                      "' hangs on a joint without a single axis; controllers drive revolute, "
                      "prismatic and universal joints");
    }
    const int n = joint_v_size(s.joint.kind);
    if (d.dof < 0 || d.dof >= n) {
      throw Error(file, at + ".dof",
                  "must be in [0, " + std::to_string(n - 1) + "] for this joint's " +
                      std::to_string(n) + " DOF");
    }
    c.q_index = s.q_offset + d.dof;
    c.v_index = s.v_offset + d.dof;
    for (const JointController& earlier : out) {
      if (earlier.v_index == c.v_index) {
        throw Error(file, at + ".dof",
                    "this DOF of '" + d.joint + "' already has a controller (" +
                        std::to_string(&earlier - out.data()) + ")");
      }
    }
    require(!d.keys.empty(), file, at + ".keys", "needs at least one key [time, value]");
    for (std::size_t j = 0; j < d.keys.size(); ++j) {
      const bool ok = std::isfinite(d.keys[j].time) && std::isfinite(d.keys[j].value) &&
                      (j == 0 || d.keys[j].time > d.keys[j - 1].time);
      require(ok, file, at + ".keys[" + std::to_string(j) + "]",
              "must be finite, its time after the previous key's");
    }
    if (d.max_output) {
      require(*d.max_output > 0 && std::isfinite(*d.max_output), file, at + ".max_output",
              "must be > 0 and finite");
    }
    if (d.kind == ControllerKind::mrac) {
      require(d.settling_time > 0 && std::isfinite(d.settling_time), file, at + ".settling_time",
              "must be > 0 and finite");
      require(d.alpha >= 0 && std::isfinite(d.alpha), file, at + ".alpha",
              "must be >= 0 and finite");
      require(d.beta >= 0 && std::isfinite(d.beta), file, at + ".beta", "must be >= 0 and finite");
      c.mrac.settling_time = d.settling_time;
      c.mrac.alpha = d.alpha;
      c.mrac.beta = d.beta;
      if (d.max_output) c.mrac.max_output = *d.max_output;
      c.state_offset = state;
      state += kMracStateSize;
    } else {
      require(d.kp >= 0 && std::isfinite(d.kp), file, at + ".kp", "must be >= 0 and finite");
      require(d.kd >= 0 && std::isfinite(d.kd), file, at + ".kd", "must be >= 0 and finite");
      require(d.kp > 0 || d.kd > 0, file, at + ".kp", "a PD servo needs kp or kd > 0");
    }
    out.push_back(c);
  }
  return out;
}

int controller_state_size(const std::vector<JointController>& controllers) {
  if (controllers.empty()) return 0;
  int n = 1;
  for (const JointController& c : controllers) {
    if (c.state_offset >= 0) n += kMracStateSize;
  }
  return n;
}

void explicit_servo_limit(CompiledFigure& figure) {
  bool any = false;
  for (const JointController& c : figure.controllers) any = any || c.def.kind == ControllerKind::pd;
  if (!any) return;
  const FigureModel& model = figure.model;
  FigureWorkspace ws;
  size_figure_workspace(model, ws);
  const VecX zero = VecX::Zero(model.n_v);
  VecX qdd(model.n_v);
  forward_dynamics(model, figure.q0.data(), zero.data(), zero.data(), {}, Vec3::Zero(), ws,
                   qdd.data());
  for (std::size_t k = 0; k < figure.controllers.size(); ++k) {
    const JointController& c = figure.controllers[k];
    if (c.def.kind != ControllerKind::pd) continue;
    const Real inertia = 1 / ws.D_inv[c.segment](c.def.dof, c.def.dof);
    const Real limit = 2 / (c.def.kd / inertia + std::sqrt(c.def.kp / inertia));
    if (limit < figure.servo_step_limit) {
      figure.servo_step_limit = limit;
      figure.servo_limiting = static_cast<int>(k);
      figure.servo_inertia = inertia;
    }
  }
}

}  // namespace pbm
