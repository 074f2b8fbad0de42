#include "figure/figure_controllers.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/error.h"
#include "figure/figure_build.h"
#include "figure/joint_space_inertia.h"

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
    c.ball = s.joint.kind == JointKind::spherical;
    if (!scalar_joint(s.joint.kind) && !c.ball) {
      throw Error(file, at + ".joint",
                  "segment '" + d.joint +
                      "' hangs on a fixed or free joint; controllers drive revolute, prismatic, "
                      "universal and spherical joints");
    }
    const int n = joint_v_size(s.joint.kind);
    if (d.dof < 0 || d.dof >= n) {
      throw Error(file, at + ".dof",
                  "must be in [0, " + std::to_string(n - 1) + "] for this joint's " +
                      std::to_string(n) + " DOF");
    }
    // A ball: component dof of the rotation vector of the quaternion at q_offset.
    c.q_index = s.q_offset + (c.ball ? 0 : d.dof);
    c.v_index = s.v_offset + d.dof;
    for (const JointController& earlier : out) {
      if (earlier.v_index == c.v_index) {
        throw Error(file, at + ".dof",
                    "this DOF of '" + d.joint + "' already has a controller (" +
                        std::to_string(&earlier - out.data()) + ")");
      }
    }
    for (std::size_t j = 0; j < d.live.size(); ++j) {
      const LiveKey& key = d.live[j];
      const bool ok = std::isfinite(key.time) && std::isfinite(key.value) &&
                      std::isfinite(key.rate) && key.time >= 0 &&
                      (j == 0 || key.time > d.live[j - 1].time);
      require(ok, file, at + ".live[" + std::to_string(j) + "]",
              "needs finite [time, value] or [time, value, rate] with times >= 0 increasing "
              "strictly");
    }
    require_keyframes(d.keys, file, at + ".keys");
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
      c.mrac.adaptive_bias = d.adaptive_bias;
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

namespace {

// The fastest rate lambda_max(H^-1 G) of the gains G = diag(g) on the figure of joint-space
// inertia H (its Cholesky factor given), and the DOF that moves most in that mode (the largest
// entry of the symmetric form's eigenvector, G^1/2 x). 0 without gains.
Real fastest_mode(const Eigen::LLT<MatX>& H, const VecX& g, int& dof) {
  dof = -1;
  if (!(g.maxCoeff() > 0)) return 0;
  // G^1/2 H^-1 G^1/2 is symmetric and has the eigenvalues of H^-1 G.
  const VecX root = g.cwiseSqrt();
  const MatX A = root.asDiagonal() * H.solve(MatX(root.asDiagonal()));
  const Eigen::SelfAdjointEigenSolver<MatX> eigen(0.5 * (A + A.transpose()));
  const Eigen::Index last = A.rows() - 1;
  Eigen::Index at = 0;
  eigen.eigenvectors().col(last).cwiseAbs().maxCoeff(&at);
  dof = static_cast<int>(at);
  return eigen.eigenvalues()[last];
}

JointStepLimit step_limit(const CompiledFigure& figure, const Eigen::LLT<MatX>& H,
                          const VecX& stiffness, const VecX& damping,
                          const std::vector<int>& servo) {
  JointStepLimit limit;
  int dof_k = -1, dof_d = -1;
  const Real lambda_k = fastest_mode(H, stiffness, dof_k);
  const Real lambda_d = fastest_mode(H, damping, dof_d);
  if (lambda_k == 0 && lambda_d == 0) return limit;
  // The damped oscillator's explicit bound, 2 / (d / I + sqrt(k / I)), with each rate the
  // figure's fastest: exact for one DOF, conservative when the two modes differ.
  limit.step = 2 / (lambda_d + std::sqrt(lambda_k));
  const bool by_damping = lambda_d >= std::sqrt(lambda_k);
  const int dof = by_damping ? dof_d : dof_k;
  const FigureModel& model = figure.model;
  for (int i = 0; i < model.size(); ++i) {
    const int first = model.segments[i].v_offset;
    if (dof >= first && dof < first + joint_v_size(model.segments[i].joint.kind)) {
      limit.segment = i;
      limit.dof = dof - first;
    }
  }
  limit.controller = servo[static_cast<std::size_t>(dof)];
  limit.stiffness = stiffness[dof];
  limit.damping = damping[dof];
  limit.inertia = by_damping ? damping[dof] / lambda_d : stiffness[dof] / lambda_k;
  return limit;
}

}  // namespace

void explicit_joint_force_limit(CompiledFigure& figure) {
  const FigureModel& model = figure.model;
  // Each DOF's explicit stiffness and damping: its joint's spring and damping, and the gains of
  // the explicit PD servos on it (a stable PD's are implicit: figure/stable_pd.h).
  VecX stiffness = VecX::Zero(model.n_v), joint_damping = VecX::Zero(model.n_v);
  VecX servo_damping = VecX::Zero(model.n_v);
  std::vector<int> servo(static_cast<std::size_t>(model.n_v), -1);
  for (const SegmentModel& s : model.segments) {
    for (int k = 0; k < joint_v_size(s.joint.kind); ++k) {
      stiffness[s.v_offset + k] += s.stiffness;
      joint_damping[s.v_offset + k] += s.damping;
    }
  }
  for (std::size_t k = 0; k < figure.controllers.size(); ++k) {
    const JointController& c = figure.controllers[k];
    if (c.def.kind != ControllerKind::pd) continue;
    stiffness[c.v_index] += c.def.kp;
    servo_damping[c.v_index] += c.def.kd;
    servo[static_cast<std::size_t>(c.v_index)] = static_cast<int>(k);
  }
  if (model.n_v == 0 || (!(stiffness.maxCoeff() > 0) && !(joint_damping.maxCoeff() > 0) &&
                         !(servo_damping.maxCoeff() > 0))) {
    return;
  }
  // The modes of the whole figure at its initial pose: H^-1 K and H^-1 D, with H the joint-space
  // inertia (coupled joints move together, so no joint's own inertia bounds them alone).
  FigureWorkspace ws;
  size_figure_workspace(model, ws);
  MatX H;
  joint_space_inertia(model, figure.q0.data(), ws, H);
  const Eigen::LLT<MatX> factor(H);
  figure.step_limit_explicit_damping =
      step_limit(figure, factor, stiffness, joint_damping + servo_damping, servo);
  figure.step_limit_implicit_damping = step_limit(figure, factor, stiffness, servo_damping, servo);
}

}  // namespace pbm
