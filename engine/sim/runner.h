// The engine thread and its timeline (docs/architecture.md, "Runner" and "Timeline").
//
// RunnerCore is the whole behaviour, single-threaded and deterministic: it owns the Scene (the
// editable source, saved by the studio), the Model compiled from it, the State, the Workspace and
// the Timeline cache of every computed frame. Runner puts a RunnerCore on its own std::thread:
// the UI posts Commands to a queue and reads only the latest Snapshot (a triple buffer) and a
// RunnerStatus. Every command the thread applies, and every frame it steps, is written to a
// journal, so `replay(journal)` on a fresh RunnerCore reproduces the final State bit for bit.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "scene/scene.h"
#include "sim/model.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"
#include "sim/state.h"
#include "sim/timeline.h"
#include "sim/world.h"

namespace pbm {

struct Play {};  // refused at last_frame()
struct Pause {};
struct StepFrame {};  // one frame forward, then paused
// To a frame in [0, last_frame()]: cached states are restored exactly, others re-simulated from
// the nearest cached frame before them. A mouse spring being dragged is released first (as by
// SpringEnd), so that a drag never reaches back before the time it was made.
struct Seek {
  int frame = 0;
};
struct ResetToStart {  // seek to frame 0 and pause
};
// Replace the value at an RFC 6901 pointer of the scene's JSON (scene_to_json) with `value_json`,
// e.g. {"/bodies/0/material/w1", "12"}; "" replaces the whole scene. The result is validated by
// parse_scene and compiled by build_model; a refused edit changes nothing and its message (file
// and JSON path of the field) is returned by apply() and shown in RunnerStatus::message.
// Frames after the current one are dropped. If the edit changes the initial state (positions,
// velocities, the layout of State) every frame but 0 is dropped and the current frame is
// re-simulated from frame 0. Refused while a mouse spring is dragged.
struct EditScene {
  std::string pointer;
  std::string value_json;
};
// The mouse spring of sec. 6.4: one mechanism, a scene spring whose target tracks the drag
// writes, recorded into the scene as it is applied so that playback (and a saved file) reproduce
// it. Begin adds a SpringDef from `node` of `body` to `target`, with a stiffness ramped in over
// kSpringRampSeconds, a damping and a force limit sized on the body's mass, its damping and the
// time step (mouse_spring_parameters), and three `springs[i].target[k]` tracks with step
// interpolation, and compiles the scene. Move records a key at the current time (or replaces the
// key there) into the scene and sets the same values as Inputs of the step (sim/inputs.h), which
// act exactly as those keys: a move compiles nothing. End sets t_end to the current time and
// compiles the scene with every key recorded. Each drops the cached frames after the current
// one. A Begin while another spring is dragged ends that one first.
struct SpringBegin {
  int body = 0;
  int node = 0;
  Vec3 target = Vec3::Zero();
};
// The mouse spring on a figure: the same mechanism with a site actuator (figure/site_actuator.h)
// for the spring. Begin adds a site at `point` (world, on the segment as it is now) to `segment`
// of `figure` (its index in the compiled figure) and a site actuator pulling it toward `target`,
// with step-interpolated x, y, z keys, t_begin now, its stiffness ramped in over
// kSpringRampSeconds, and gains sized on the figure's mass and the substep
// (figure_spring_parameters); Move and End act on it as on a body's spring.
struct FigureSpringBegin {
  int figure = 0;
  int segment = 0;
  Vec3 point = Vec3::Zero();
  Vec3 target = Vec3::Zero();
};
struct SpringMove {
  Vec3 target = Vec3::Zero();
};
struct SpringEnd {};

// A target set on a figure's joint controller from the control panel (fig. 15.11's crane panel):
// recorded at the current time as a key of the controller's `live` track (control/controller_def.h,
// LiveKey), replacing later keys and the key at that time, and set as an Input of the step
// (sim/inputs.h) that acts exactly as that key: nothing is compiled, frames after the current one
// are dropped. Commands that re-simulate or recompile (Seek, ResetToStart, EditScene, a spring's
// Begin) compile the recorded keys first.
struct ControlSet {
  int figure = 0;
  int controller = 0;
  Real value = 0;  // the target from now on [rad or m]
  Real rate = 0;   // and its speed: nonzero, a jog (a lever held, the crane's crawlers)
  // A lever moved: the target continues from where the controller's desired position is now
  // (value is ignored), so a jog neither jumps nor stops the motion it takes over.
  bool from_desired = false;
};

using Command = std::variant<Play, Pause, StepFrame, Seek, ResetToStart, EditScene, SpringBegin,
                             FigureSpringBegin, SpringMove, SpringEnd, ControlSet>;

inline constexpr Real kSpringRampSeconds = 0.2;

// Stiffness [N/m], damping [N s/m] and force limit [N] of a mouse spring on `body`: the whole body
// follows the target within about 1 / (2 pi 1.5 Hz), through its own damping nu too, capped so
// that the explicit substep stays stable on the one node it acts on; the force is at most three
// body weights, or what moves a heavily damped body at 3 m/s.
struct MouseSpringParameters {
  Real stiffness = 0, damping = 0, max_force = 0;
};
MouseSpringParameters mouse_spring_parameters(const Model& model, int body);
// The same for a figure grabbed at a segment: the whole figure's mass follows the hand, the
// stiffness capped so that the grabbed segment alone stays an explicitly stable oscillator at the
// substep.
MouseSpringParameters figure_spring_parameters(const Model& model, int figure, int segment);

class RunnerCore {
 public:
  // Throws pbm::Error when the scene does not compile.
  explicit RunnerCore(const Scene& scene, std::size_t cache_bytes = std::size_t{512} << 20);
  // The simulation's world holds its model's address.
  RunnerCore(const RunnerCore&) = delete;
  RunnerCore& operator=(const RunnerCore&) = delete;

  // Applies a command; returns "" or why it was refused (nothing changed then). A frame that
  // fails to compute is not a refusal: the run pauses before it and message() says why.
  std::string apply(const Command& command);
  // While playing, steps one frame and returns true; pauses at last_frame() or on a failed
  // frame (message() says why) and returns false.
  bool tick();

  int frame() const { return frame_; }
  int last_frame() const;  // round(duration * fps)
  bool playing() const { return playing_; }
  const std::string& message() const { return message_; }
  const Scene& scene() const { return *scene_; }
  std::shared_ptr<const Scene> shared_scene() const { return scene_; }
  std::uint64_t scene_revision() const { return revision_; }
  const Model& model() const { return sim_->model; }
  const State& state() const { return sim_->state; }
  const Inputs& inputs() const { return sim_->inputs; }
  const Timeline& timeline() const { return timeline_; }
  const FrameStats& last_stats() const { return last_stats_; }
  Snapshot snapshot();

 private:
  std::string handle(const Play&);
  std::string handle(const Pause&);
  std::string handle(const StepFrame&);
  std::string handle(const Seek&);
  std::string handle(const ResetToStart&);
  std::string handle(const EditScene&);
  std::string handle(const SpringBegin&);
  std::string handle(const FigureSpringBegin&);
  std::string handle(const ControlSet&);
  std::string handle(const SpringMove&);
  std::string handle(const SpringEnd&);
  // Compiles `scene` and makes it current; returns why not (then nothing changed).
  std::string rebuild(Scene scene);
  void release_spring();  // SpringEnd of the dragged spring, if any
  // Compiles the keys ControlSet recorded (their inputs then live in the Model); "" or why not.
  std::string flush_controls();
  std::string move_figure_spring(const Vec3& target);  // SpringMove of a figure's drag
  bool advance();       // computes frame_ + 1 and caches it; false on failure
  bool step_forward();  // frame_ + 1 from the cache, else computed
  void restore(int frame);
  void go_to(int frame);

  std::shared_ptr<const Scene> scene_;
  std::uint64_t revision_ = 0;
  std::unique_ptr<Simulation> sim_;  // model, world, workspace, state and the drag's inputs
  Timeline timeline_;
  FrameStats last_stats_;
  int frame_ = 0;
  bool playing_ = false;
  int active_spring_ = -1;  // index in scene().springs of the spring being dragged
  // Or the figure's site actuator being dragged (figure index, actuator index), else -1.
  int active_figure_ = -1, active_actuator_ = -1;
  std::string message_;
};

// What the runner thread did, in order: a command applied or a frame stepped by play.
struct Tick {};
using JournalEntry = std::variant<Command, Tick>;
// Applies a journal to `core` in order (commands with apply, ticks with tick).
void replay(RunnerCore& core, const std::vector<JournalEntry>& journal);

struct RunnerStatus {
  int frame = 0, last_frame = 0;
  bool playing = false;
  std::string message;
  std::vector<std::pair<int, int>> cached;  // inclusive frame ranges
  FrameStats stats;                         // of the current frame
  double real_time_factor = 0;              // simulated / wall seconds over the last second
  std::shared_ptr<const Scene> scene;
  std::uint64_t scene_revision = 0;
};

struct RunnerOptions {
  bool real_time = true;  // pace play to the scene's fps times speed; false = as fast as it can
  double speed = 1.0;     // playback speed when real_time
  bool keep_journal = false;
  std::size_t cache_bytes = std::size_t{512} << 20;
};

// Three slots: the writer fills its own and swaps it with the middle one; the reader swaps the
// middle one into its own when it is newer. Neither ever waits for the other's copy.
template <class T>
class TripleBuffer {
 public:
  T& back() { return slots_[back_]; }
  void publish() { back_ = middle_.exchange(back_ | kFresh) & kIndex; }
  // True when a newer value was taken; front() is the latest published value.
  bool take() {
    if (!(middle_.load() & kFresh)) return false;
    front_ = middle_.exchange(front_) & kIndex;
    return true;
  }
  const T& front() const { return slots_[front_]; }

 private:
  static constexpr int kFresh = 4, kIndex = 3;
  T slots_[3];
  int back_ = 0, front_ = 1;
  std::atomic<int> middle_{2};
};

class Runner {
 public:
  // Throws pbm::Error when the scene does not compile; the thread starts paused at frame 0.
  explicit Runner(const Scene& scene, RunnerOptions options = {});
  ~Runner();
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;

  void post(Command command);
  // Blocks until every posted command is applied, play has stopped (Pause, the last frame or a
  // failed frame) and the snapshot of the result is published.
  void wait_idle();
  void set_speed(double speed);

  // UI side: the newest snapshot (nullptr before the first one) and status.
  std::shared_ptr<const Snapshot> snapshot();
  RunnerStatus status() const;
  std::vector<JournalEntry> journal() const;
  // The core's state, for tests: call only after wait_idle() with play stopped.
  const RunnerCore& core_when_idle() const { return core_; }

 private:
  void run();
  void publish_snapshot();
  RunnerStatus make_status() const;  // engine thread only

  RunnerCore core_;
  RunnerOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<Command> queue_;
  bool stop_ = false, busy_ = false;
  std::vector<JournalEntry> journal_;
  RunnerStatus status_;
  TripleBuffer<std::shared_ptr<const Snapshot>> snapshots_;
  std::mutex reader_mutex_;  // one reader at a time takes from the triple buffer
  std::thread thread_;
};

}  // namespace pbm
