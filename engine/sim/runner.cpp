#include "sim/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>

#include <nlohmann/json.hpp>

#include "core/bits.h"
#include "core/error.h"
#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"
#include "scene/scene_json.h"
#include "scene/track_targets.h"
#include "sim/stages_figure_control.h"

namespace pbm {
namespace {

using Json = nlohmann::ordered_json;  // keeps the scene's keys in their documented order
using Clock = std::chrono::steady_clock;

// "/bodies/0/material/w1" -> "bodies[0].material.w1": the path form pbm::Error uses
// (docs/architecture.md, "Errors and exit codes").
std::string path_of_pointer(const std::string& pointer) {
  std::string path;
  std::size_t begin = 1;
  while (begin <= pointer.size() && !pointer.empty()) {
    std::size_t end = pointer.find('/', begin);
    if (end == std::string::npos) end = pointer.size();
    std::string token = pointer.substr(begin, end - begin);
    for (std::size_t i = 0; (i = token.find('~', i)) != std::string::npos; ++i) {
      if (i + 1 < token.size()) token.replace(i, 2, token[i + 1] == '1' ? "/" : "~");
    }
    const bool index = !token.empty() && std::all_of(token.begin(), token.end(),
                                                     [](char c) { return c >= '0' && c <= '9'; });
    path += index ? "[" + token + "]" : (path.empty() ? "" : ".") + token;
    begin = end + 1;
  }
  return path;
}

std::string target_track_name(int spring, int k) {
  return format_track_target(TrackTarget::spring_target, spring, k);
}

// Index of the track driving `target` in scene.tracks (the Model's tracks have the same order),
// or -1.
int find_track(const Scene& scene, const std::string& target) {
  for (std::size_t k = 0; k < scene.tracks.size(); ++k) {
    if (scene.tracks[k].target == target) return static_cast<int>(k);
  }
  return -1;
}

// Records a user's input as a key at time t: keys later than t belong to frames that are dropped
// with it, and a key already at t (a second input in the same frame) takes the new value.
void record_key(std::vector<Keyframe>& keys, Real t, Real value) {
  std::erase_if(keys, [t](const Keyframe& key) { return key.time > t; });
  if (!keys.empty() && keys.back().time == t) {
    keys.back().value = value;
  } else {
    keys.push_back({t, value});
  }
}

}  // namespace

MouseSpringParameters mouse_spring_parameters(const Model& model, int body) {
  const BodyModel& b = model.bodies[body];
  const Real m_body = b.mass;
  const Real m_node = b.node_mass.minCoeff();
  const Real nu = b.damping;      // D = nu M (sec. 6.1) [1/s]
  const Real dt = model.substep;  // the longest substep the step takes
  const Real g = model.gravity.norm() > 0 ? model.gravity.norm() : 9.81;
  MouseSpringParameters p;
  // The body on the spring, m x'' + nu m x' + k x = k x_target, should follow a hand within
  // about 1 / omega, omega = 2 pi 1.5 Hz: quick, yet slow enough that the body's own deformation
  // shows. Lightly damped (the jello: nu = 1.4 / s) that is k = m omega^2; where its own damping
  // dominates (nu > omega: a body moving as through honey) the response time is nu m / k, so
  // k = m nu omega. But the spring pulls one node: alone on it that node oscillates at
  // sqrt(k / m_node), and the explicit substep is stable only for omega_node dt < 2; a quarter
  // of the bound (omega_node dt = 0.5) leaves room for the membrane's own stiffness there.
  const Real omega = 2 * std::numbers::pi * 1.5;
  p.stiffness = std::min(m_body * omega * std::max(omega, nu), 0.25 * m_node / (dt * dt));
  // 0.7 of critical damping for the body on the spring settles it in about one period without
  // overshooting much; the damper too acts on one node, where explicit damping is stable for
  // c dt / m_node < 2, and 0.5 keeps it well inside.
  p.damping = std::min(2 * 0.7 * std::sqrt(p.stiffness * m_body), 0.5 * m_node / dt);
  // Three body weights lift and swing the body briskly; a heavily damped body needs nu m v to
  // move at all, here at a brisk hand's 3 m/s. No more: a target dragged far away (the cursor
  // off the screen) must not fling the body or tear the node out of the membrane.
  constexpr Real kHandSpeed = 3.0;  // [m/s]
  p.max_force = m_body * std::max(3 * g, nu * kHandSpeed);
  return p;
}

MouseSpringParameters figure_spring_parameters(const Model& model, int figure, int segment) {
  const FigureModel& f = model.figures[figure].model;
  Real m_figure = 0;
  for (const SegmentModel& s : f.segments) m_figure += s.inertia.m;
  const Real m_segment = f.segments[segment].inertia.m;
  const Real dt = model.substep;
  const Real g = model.gravity.norm() > 0 ? model.gravity.norm() : 9.81;
  MouseSpringParameters p;
  // As for a body (mouse_spring_parameters): the whole figure follows the hand within about
  // 1 / (2 pi 1.5 Hz), 0.7 of critical damping. The spring acts at one point of one segment,
  // whose own mass there must stay an explicitly stable oscillator (omega dt = 0.5; a point off
  // the segment's centre moves with as little as a quarter of its mass, omega dt = 1 < 2).
  const Real omega = 2 * std::numbers::pi * 1.5;
  p.stiffness = std::min(m_figure * omega * omega, 0.25 * m_segment / (dt * dt));
  p.damping = std::min(2 * 0.7 * std::sqrt(p.stiffness * m_figure), 0.5 * m_segment / dt);
  // Three weights of the figure lift it briskly; a cursor off the screen must not fling it.
  p.max_force = 3 * m_figure * g;
  return p;
}

// ---- RunnerCore -------------------------------------------------------------------------------

RunnerCore::RunnerCore(const Scene& scene, std::size_t cache_bytes)
    : scene_(std::make_shared<const Scene>(scene)),
      sim_(std::make_unique<Simulation>(*scene_)),
      timeline_(cache_bytes) {
  last_stats_ = sim_->stats;
  timeline_.store(0, sim_->state, last_stats_);
}

int RunnerCore::last_frame() const {
  return static_cast<int>(std::lround(model().solver.duration * model().solver.fps));
}

Snapshot RunnerCore::snapshot() {
  return make_snapshot(*sim_);
}

std::string RunnerCore::apply(const Command& command) {
  message_.clear();
  std::string refusal = std::visit([this](const auto& c) { return handle(c); }, command);
  if (!refusal.empty()) message_ = refusal;
  return refusal;
}

bool RunnerCore::tick() {
  if (!playing_) return false;
  if (frame_ >= last_frame()) {
    playing_ = false;
    return false;
  }
  if (!step_forward()) return false;
  if (frame_ >= last_frame()) playing_ = false;
  return true;
}

std::string RunnerCore::handle(const Play&) {
  if (frame_ >= last_frame()) return "already at the last frame: seek back to play again";
  playing_ = true;
  return {};
}

std::string RunnerCore::handle(const Pause&) {
  playing_ = false;
  return {};
}

std::string RunnerCore::handle(const StepFrame&) {
  playing_ = false;
  if (frame_ >= last_frame()) return "already at the last frame";
  step_forward();
  return {};
}

std::string RunnerCore::handle(const Seek& seek) {
  if (seek.frame < 0 || seek.frame > last_frame()) {
    return "cannot seek to frame " + std::to_string(seek.frame) + ": frames are 0 to " +
           std::to_string(last_frame());
  }
  release_spring();
  flush_controls();
  go_to(seek.frame);
  return {};
}

std::string RunnerCore::handle(const ResetToStart&) {
  release_spring();
  flush_controls();
  playing_ = false;
  go_to(0);
  return {};
}

std::string RunnerCore::handle(const EditScene& edit) {
  // Through the file format, so that an edit is validated exactly like a loaded file and names
  // the field it broke in the same words (docs/architecture.md, "Errors and exit codes").
  if (active_spring_ >= 0 || active_figure_ >= 0) {
    return "finish dragging the mouse spring before editing the scene";
  }
  Scene edited;
  try {
    Json json = Json::parse(scene_to_json(*scene_));
    Json value = Json::parse(edit.value_json);
    if (edit.pointer.empty()) {
      json = std::move(value);
    } else {
      json[Json::json_pointer(edit.pointer)] = std::move(value);
    }
    edited = parse_scene(json.dump(), scene_->file);
  } catch (const Json::exception& e) {
    return Error(scene_->file, path_of_pointer(edit.pointer),
                 std::string("cannot apply the edit: ") + e.what())
        .what();
  } catch (const Error& e) {
    return e.what();
  }
  return rebuild(std::move(edited));
}

std::string RunnerCore::handle(const SpringBegin& begin) {
  const int n_bodies = static_cast<int>(model().bodies.size());
  if (begin.body < 0 || begin.body >= n_bodies) {
    return "mouse spring: no body " + std::to_string(begin.body) + " (the scene has " +
           std::to_string(n_bodies) + ")";
  }
  const int n_nodes = model().bodies[begin.body].n_nodes();
  if (begin.node < 0 || begin.node >= n_nodes) {
    return "mouse spring: body '" + model().bodies[begin.body].name + "' has no node " +
           std::to_string(begin.node) + " (it has " + std::to_string(n_nodes) + ")";
  }
  if (!begin.target.allFinite()) return "mouse spring: the target is not finite";
  release_spring();
  Scene scene = *scene_;
  const int drags = static_cast<int>(
      std::count_if(scene.springs.begin(), scene.springs.end(),
                    [](const SpringDef& s) { return s.name.rfind("drag ", 0) == 0; }));
  const int index = static_cast<int>(scene.springs.size());
  const MouseSpringParameters p = mouse_spring_parameters(model(), begin.body);
  const Real t = state().time;
  // Recorded as an ordinary spring of the scene (sec. 6.4), so that playing the timeline again,
  // or the saved file, reproduces the drag: it acts from now on, never on a frame already
  // computed, which therefore stay valid.
  SpringDef spring;
  spring.name = "drag " + std::to_string(drags + 1);
  spring.body = begin.body;
  spring.node = begin.node;
  spring.target = begin.target;
  spring.stiffness = p.stiffness;
  spring.damping = p.damping;
  spring.max_force = p.max_force;
  spring.t_begin = t;
  spring.t_end = 1e300;
  scene.springs.push_back(spring);
  // The cursor jumps between mouse events: the target is held from one event to the next
  // (step), never interpolated toward a position the hand had not reached yet.
  for (int k = 0; k < 3; ++k) {
    scene.tracks.push_back({.target = target_track_name(index, k),
                            .interpolation = Interpolation::step,
                            .keys = {{t, begin.target[k]}}});
  }
  // Grabbing a body that is at rest must not jolt it: the pull grows over kSpringRampSeconds.
  scene.tracks.push_back({.target = format_track_target(TrackTarget::spring_stiffness, index, 0),
                          .interpolation = Interpolation::linear,
                          .keys = {{t, 0.0}, {t + kSpringRampSeconds, p.stiffness}}});
  std::string refusal = rebuild(std::move(scene));
  if (refusal.empty()) active_spring_ = index;
  return refusal;
}

std::string RunnerCore::handle(const FigureSpringBegin& begin) {
  const int n_figures = static_cast<int>(model().figures.size());
  if (begin.figure < 0 || begin.figure >= n_figures) {
    return "mouse spring: no figure " + std::to_string(begin.figure) + " (the scene has " +
           std::to_string(n_figures) + ")";
  }
  const FigureModel& grabbed_figure = model().figures[begin.figure].model;
  if (begin.segment < 0 || begin.segment >= grabbed_figure.size()) {
    return "mouse spring: figure '" + grabbed_figure.name + "' has no segment " +
           std::to_string(begin.segment) + " (it has " + std::to_string(grabbed_figure.size()) +
           ")";
  }
  if (!begin.point.allFinite() || !begin.target.allFinite()) {
    return "mouse spring: the grabbed point or the target is not finite";
  }
  // Releasing a drag under way compiles the scene: the Model is a new one after it.
  release_spring();
  const FigureModel& figure = model().figures[begin.figure].model;
  Scene scene = *scene_;
  FigureDef& def = scene.figures[static_cast<std::size_t>(begin.figure)];
  const std::string& grabbed = figure.segments[static_cast<std::size_t>(begin.segment)].name;
  SegmentDef& segment = *std::find_if(def.segments.begin(), def.segments.end(),
                                      [&](const SegmentDef& s) { return s.name == grabbed; });
  // A site at the grabbed point, named apart from the segment's own sites.
  int drags = 0;
  for (const SegmentDef& s : def.segments) {
    drags += static_cast<int>(std::count_if(s.sites.begin(), s.sites.end(), [](const SiteDef& d) {
      return d.name.rfind("drag ", 0) == 0;
    }));
  }
  const std::string name = "drag " + std::to_string(drags + 1);
  // The grabbed point in the segment's frame, from where the segment is now.
  FigureWorkspace kinematics;
  size_figure_workspace(figure, kinematics);
  figure_kinematics(figure, state().q.data() + figure.state_q_offset, nullptr, kinematics);
  std::vector<SpatialTransform> world;
  segment_world_transforms(figure, kinematics, world);
  const SpatialTransform& X = world[static_cast<std::size_t>(begin.segment)];
  segment.sites.push_back({.name = name, .position = X.E * (begin.point - X.r)});
  const MouseSpringParameters p = figure_spring_parameters(model(), begin.figure, begin.segment);
  const Real t = state().time;
  // Recorded as a site actuator of the scene, acting from now on: the frames already computed
  // stay valid, and playback and the saved file repeat the drag.
  SiteActuatorDef drag;
  drag.segment = segment.name;
  drag.site = name;
  drag.interpolation = Interpolation::step;  // held between mouse events, as a body's drag
  drag.x = {{t, begin.target.x()}};
  drag.y = {{t, begin.target.y()}};
  drag.z = {{t, begin.target.z()}};
  drag.stiffness = p.stiffness;
  drag.damping = p.damping;
  drag.max_force = p.max_force;
  drag.t_begin = t;
  drag.ramp = kSpringRampSeconds;
  const int index = static_cast<int>(def.site_actuators.size());
  def.site_actuators.push_back(std::move(drag));
  std::string refusal = rebuild(std::move(scene));
  if (refusal.empty()) {
    active_figure_ = begin.figure;
    active_actuator_ = index;
  }
  return refusal;
}

std::string RunnerCore::handle(const ControlSet& set) {
  const int n_figures = static_cast<int>(scene_->figures.size());
  if (set.figure < 0 || set.figure >= n_figures) {
    return "control: no figure " + std::to_string(set.figure) + " (the scene has " +
           std::to_string(n_figures) + ")";
  }
  const FigureDef& def = scene_->figures[static_cast<std::size_t>(set.figure)];
  const int n_model = static_cast<int>(model().figures[set.figure].controllers.size());
  if (set.controller < 0 || set.controller >= n_model) {
    return "control: figure '" + def.name + "' has no controller " +
           std::to_string(set.controller) + " (it has " + std::to_string(n_model) + ")";
  }
  if (set.controller >= static_cast<int>(def.controllers.size())) {
    return "control: controller " + std::to_string(set.controller) + " of figure '" + def.name +
           "' follows its motion capture clip; map the joint out of the clip to drive it live";
  }
  const Real t = state().time;
  const auto f = static_cast<std::size_t>(set.figure);
  const auto k = static_cast<std::size_t>(set.controller);
  const Real value = set.from_desired
                         ? controller_desired(model().figures[f].controllers[k], t,
                                              stages::control_input(sim_->inputs, f, k))
                               .q
                         : set.value;
  if (!std::isfinite(value)) return "control: the target is not finite";
  if (!std::isfinite(set.rate)) return "control: the target's rate is not finite";
  Scene scene = *scene_;
  std::vector<LiveKey>& live = scene.figures[f].controllers[k].live;
  std::erase_if(live, [t](const LiveKey& key) { return key.time > t; });
  if (!live.empty() && live.back().time == t) live.pop_back();
  live.push_back({t, value, set.rate});
  // The same key as an input of the step, acting exactly as the recorded key will once the scene
  // is compiled (sim/inputs.h): setting a target while playing compiles nothing.
  std::vector<ControlInput>& inputs = sim_->inputs.controls;
  std::erase_if(inputs, [&](const ControlInput& in) {
    return in.figure == set.figure && in.controller == set.controller;
  });
  inputs.push_back({set.figure, set.controller, t, value, set.rate});
  scene_ = std::make_shared<const Scene>(std::move(scene));
  ++revision_;
  timeline_.drop_after(frame_);
  sim_->ws.last_measured.valid = false;
  return {};
}

std::string RunnerCore::flush_controls() {
  if (sim_->inputs.controls.empty()) return {};
  // The recorded keys act exactly as the inputs did, so every cached frame stays valid: only the
  // Model changes, the State carries over as it is.
  std::unique_ptr<Simulation> sim;
  try {
    sim = std::make_unique<Simulation>(*scene_);
  } catch (const Error& e) {
    return e.what();
  }
  sim->state = sim_->state;
  sim->inputs.tracks = sim_->inputs.tracks;
  sim->inputs.site_targets = sim_->inputs.site_targets;
  sim_ = std::move(sim);
  return {};
}

std::string RunnerCore::handle(const SpringMove& move) {
  if (active_figure_ >= 0) return move_figure_spring(move.target);
  if (active_spring_ < 0) return "mouse spring: no spring is being dragged";
  if (!move.target.allFinite()) return "mouse spring: the target is not finite";
  Scene scene = *scene_;
  const Real t = state().time;
  std::array<int, 3> tracks{};
  for (int k = 0; k < 3; ++k) {
    tracks[k] = find_track(scene, target_track_name(active_spring_, k));
    if (tracks[k] < 0) {
      return "mouse spring: the scene no longer has " + target_track_name(active_spring_, k);
    }
    TrackDef& track = scene.tracks[static_cast<std::size_t>(tracks[k])];
    record_key(track.keys, t, move.target[k]);
  }
  // The same keys as inputs of the step: from t on they hold the target exactly as the recorded
  // keys will once the drag ends and the scene is compiled (sim/inputs.h). The Model is not
  // rebuilt.
  std::vector<TrackInput>& inputs = sim_->inputs.tracks;
  for (int k = 0; k < 3; ++k) {
    std::erase_if(inputs, [&](const TrackInput& in) { return in.track == tracks[k]; });
    inputs.push_back({tracks[k], t, move.target[k]});
  }
  scene_ = std::make_shared<const Scene>(std::move(scene));
  ++revision_;
  timeline_.drop_after(frame_);
  // The frame start's measurement read the drive without these inputs (the guard's allowance
  // uses the spring targets there).
  sim_->ws.last_measured.valid = false;
  return {};
}

std::string RunnerCore::move_figure_spring(const Vec3& target) {
  if (!target.allFinite()) return "mouse spring: the target is not finite";
  Scene scene = *scene_;
  const Real t = state().time;
  SiteActuatorDef& drag = scene.figures[static_cast<std::size_t>(active_figure_)]
                              .site_actuators[static_cast<std::size_t>(active_actuator_)];
  for (int k = 0; k < 3; ++k) {
    std::vector<Keyframe>& keys = k == 0 ? drag.x : k == 1 ? drag.y : drag.z;
    record_key(keys, t, target[k]);
  }
  // As a body's drag: the same target as an input of the step, exactly as the recorded keys.
  std::vector<SiteTargetInput>& inputs = sim_->inputs.site_targets;
  std::erase_if(inputs, [&](const SiteTargetInput& in) {
    return in.figure == active_figure_ && in.actuator == active_actuator_;
  });
  inputs.push_back({active_figure_, active_actuator_, t, target});
  scene_ = std::make_shared<const Scene>(std::move(scene));
  ++revision_;
  timeline_.drop_after(frame_);
  sim_->ws.last_measured.valid = false;
  return {};
}

std::string RunnerCore::handle(const SpringEnd&) {
  if (active_spring_ < 0 && active_figure_ < 0) return "mouse spring: no spring is being dragged";
  release_spring();
  return {};
}

void RunnerCore::release_spring() {
  if (active_figure_ >= 0) {
    const int f = active_figure_, a = active_actuator_;
    active_figure_ = active_actuator_ = -1;
    Scene scene = *scene_;
    SiteActuatorDef& drag =
        scene.figures[static_cast<std::size_t>(f)].site_actuators[static_cast<std::size_t>(a)];
    drag.t_end = std::max(state().time, drag.t_begin);
    rebuild(std::move(scene));
    return;
  }
  const int s = active_spring_;
  active_spring_ = -1;
  if (s < 0 || s >= static_cast<int>(scene_->springs.size())) return;
  Scene scene = *scene_;
  SpringDef& spring = scene.springs[static_cast<std::size_t>(s)];
  spring.t_end = std::max(state().time, spring.t_begin);
  // Only the spring's end changed, and it lies at or after every cached frame the edit keeps:
  // this scene compiles whenever the current one does.
  rebuild(std::move(scene));
}

std::string RunnerCore::rebuild(Scene edited) {
  auto scene = std::make_shared<const Scene>(std::move(edited));
  std::unique_ptr<Simulation> sim;
  try {
    sim = std::make_unique<Simulation>(*scene);
  } catch (const Error& e) {
    return e.what();
  }
  // Frames up to the current one stay valid when the edit changes neither where the run starts
  // nor when frames fall (docs/architecture.md: an edit at frame f invalidates the frames after
  // f). The new workspace gives the same results as the old one would (determinism by
  // construction): nothing but the State carries over.
  const State& old_start = *timeline_.find(0);
  const bool same_start = sim->model.solver.fps == model().solver.fps &&
                          same_bits(sim->state.q, old_start.q) &&
                          same_bits(sim->state.v, old_start.v);
  const int target = std::min(
      frame_, static_cast<int>(std::lround(sim->model.solver.duration * sim->model.solver.fps)));
  if (same_start) sim->state = sim_->state;
  sim_ = std::move(sim);
  scene_ = std::move(scene);
  ++revision_;
  if (same_start) {
    timeline_.drop_after(target);
    go_to(target);
  } else {
    timeline_.clear();
    frame_ = 0;
    last_stats_ = sim_->stats;
    timeline_.store(0, sim_->state, last_stats_);
    go_to(target);
  }
  return {};
}

bool RunnerCore::advance() {
  FrameResult result = advance_frame(*sim_);
  if (!result.ok) {
    // The stability guard gave up (docs/architecture.md, "Stability guard"): the state is still
    // that of frame_, never a NaN frame.
    message_ = "frame " + std::to_string(frame_ + 1) + ": " + result.message;
    playing_ = false;
    return false;
  }
  ++frame_;
  last_stats_ = sim_->stats;
  timeline_.store(frame_, sim_->state, last_stats_);
  return true;
}

bool RunnerCore::step_forward() {
  if (timeline_.find(frame_ + 1)) {
    restore(frame_ + 1);
    return true;
  }
  return advance();
}

void RunnerCore::restore(int frame) {
  sim_->state = *timeline_.find(frame);
  last_stats_ = *timeline_.stats(frame);
  frame_ = frame;
}

void RunnerCore::go_to(int frame) {
  if (frame == frame_) return;
  if (timeline_.find(frame)) {
    restore(frame);
    return;
  }
  // From the nearest cached frame before it, or from the current state if that is nearer (it is
  // exactly frame_'s state even when the cache has evicted frame_).
  const int start = timeline_.nearest_at_or_before(frame);
  if (!(frame_ < frame && frame_ > start)) restore(start);
  while (frame_ < frame && advance()) {
  }
}

void replay(RunnerCore& core, const std::vector<JournalEntry>& journal) {
  for (const JournalEntry& entry : journal) {
    if (const Command* command = std::get_if<Command>(&entry)) {
      core.apply(*command);
    } else {
      core.tick();
    }
  }
}

// ---- Runner -----------------------------------------------------------------------------------

Runner::Runner(const Scene& scene, RunnerOptions options)
    : core_(scene, options.cache_bytes), options_(options) {
  publish_snapshot();
  status_ = make_status();
  thread_ = std::thread([this] { run(); });
}

Runner::~Runner() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Runner::post(Command command) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(command));
  }
  wake_.notify_one();
}

void Runner::wait_idle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return queue_.empty() && !busy_ && !status_.playing; });
}

void Runner::set_speed(double speed) {
  {
    std::lock_guard lock(mutex_);
    options_.speed = speed > 0 ? speed : 1.0;
  }
  wake_.notify_one();
}

std::shared_ptr<const Snapshot> Runner::snapshot() {
  std::lock_guard lock(reader_mutex_);
  snapshots_.take();
  return snapshots_.front();
}

RunnerStatus Runner::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

std::vector<JournalEntry> Runner::journal() const {
  std::lock_guard lock(mutex_);
  return journal_;
}

void Runner::publish_snapshot() {
  snapshots_.back() = std::make_shared<const Snapshot>(core_.snapshot());
  snapshots_.publish();
}

RunnerStatus Runner::make_status() const {
  RunnerStatus s;
  s.frame = core_.frame();
  s.last_frame = core_.last_frame();
  s.playing = core_.playing();
  s.message = core_.message();
  s.cached = core_.timeline().ranges();
  s.stats = core_.last_stats();
  s.scene = core_.shared_scene();
  s.scene_revision = core_.scene_revision();
  return s;
}

// The engine thread. core_ belongs to it alone (readers get copies: status, snapshots), so it is
// used without the lock; the lock guards the queue, the journal, the status and the flags.
// While playing, frames and commands interleave: a frame that is due goes first (real time), or
// frames and commands alternate (as fast as possible), so that neither a stream of mouse moves
// stalls play nor a long play delays an edit by more than a frame.
void Runner::run() {
  // Snapshots cost a kinematics pass and a copy of every node: at most one per display refresh
  // while busy, and always one before going idle, so the last one shows the final state.
  constexpr auto kSnapshotInterval = std::chrono::microseconds(8000);
  Clock::time_point last_snapshot = Clock::now();
  bool snapshot_stale = false;
  bool paced = false;  // play's real-time clock is running
  Clock::time_point next_frame;
  bool ticked_last = false;
  // Frames stepped during the last second: (wall time, simulated seconds stepped so far).
  std::deque<std::pair<Clock::time_point, double>> rate;
  double simulated = 0;

  std::unique_lock lock(mutex_);
  while (!stop_) {
    const bool has_command = !queue_.empty();
    const bool playing = core_.playing();
    if (!has_command && !playing) {
      paced = false;
      rate.clear();
      if (snapshot_stale) {
        lock.unlock();
        publish_snapshot();
        lock.lock();
        snapshot_stale = false;
        last_snapshot = Clock::now();
        continue;
      }
      status_.real_time_factor = 0;
      busy_ = false;
      idle_.notify_all();
      wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      continue;
    }
    bool tick = false;
    if (playing && options_.real_time) {
      const auto now = Clock::now();
      if (!paced) {
        paced = true;
        next_frame = now;
      }
      if (now >= next_frame) {
        tick = true;
        const double fps = core_.model().solver.fps * options_.speed;
        const auto period =
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / fps));
        // A frame that took longer than its period is not made up for with a burst of frames.
        next_frame = std::max(next_frame + period, now);
      } else if (!has_command) {
        wake_.wait_until(lock, next_frame);
        continue;
      }
    } else if (playing) {
      tick = !has_command || !ticked_last;
    }
    JournalEntry entry = Tick{};
    if (!tick) {
      entry = std::move(queue_.front());
      queue_.pop_front();
    }
    ticked_last = tick;
    busy_ = true;
    lock.unlock();
    bool stepped = false;
    if (const Command* command = std::get_if<Command>(&entry)) {
      core_.apply(*command);
    } else {
      stepped = core_.tick();
    }
    snapshot_stale = true;
    const auto now = Clock::now();
    if (now - last_snapshot >= kSnapshotInterval) {
      publish_snapshot();
      snapshot_stale = false;
      last_snapshot = now;
    }
    RunnerStatus status = make_status();
    if (stepped) {
      simulated += 1.0 / core_.model().solver.fps;
      rate.emplace_back(now, simulated);
      while (rate.size() > 2 && now - rate[1].first >= std::chrono::seconds(1)) rate.pop_front();
    }
    if (rate.size() >= 2) {
      const double wall =
          std::chrono::duration<double>(rate.back().first - rate.front().first).count();
      if (wall > 0) status.real_time_factor = (rate.back().second - rate.front().second) / wall;
    }
    lock.lock();
    if (options_.keep_journal) journal_.push_back(std::move(entry));
    status_ = std::move(status);
  }
  busy_ = false;
  idle_.notify_all();
}

}  // namespace pbm
