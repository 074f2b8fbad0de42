// The studio's shared state (UI thread only): the document's runner, its history, selection,
// camera and what the panels show. MainWindow owns it; the viewport and the panels use it.
#pragma once

#include <array>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "camera.h"
#include "scene_document.h"
#include "sim/runner.h"
#include "tradeoff_job.h"

namespace pbm {

// What the outliner or a click in the viewport selects: an item of one of the scene's lists
// ("bodies", "obstacles", ...: the list keys of scene/scene_format.h), the solver ("solver") or
// the scene's own fields ("scene"); "" is nothing.
struct Selection {
  std::string list;
  int index = -1;  // the item of `list`
};

// One point of the Stats panel's plots (per computed frame shown).
struct StatsSample {
  int frame = 0;
  float kinetic = 0, elastic = 0, min_distance = 0;
  float step_ms[static_cast<int>(StepStage::count)] = {};
  // Every figure's controllers in scene order: desired, reference model, actual (figs. 15.7,
  // 15.8).
  std::vector<std::array<float, 3>> control;
};

// What the UI asks of the window around it (files, history): the panels call these.
class StudioActions {
 public:
  virtual ~StudioActions() = default;
  // Validates and posts an edit; records it for undo. Returns "" or the validator's message.
  virtual std::string edit(const std::string& pointer, const nlohmann::json& value,
                           const std::string& label) = 0;
  virtual void undo() = 0;
  virtual void redo() = 0;
};

struct Studio {
  std::unique_ptr<Runner> runner;
  RunnerStatus status;                             // refreshed every UI frame
  std::shared_ptr<const draw::Snapshot> snapshot;  // latest taken
  EditHistory history;
  std::string path;  // scene file ("" for a new scene)
  std::uint64_t saved_revision = 0;
  Selection selection;
  std::string last_edited_pointer;  // the field under edit, for keyframes
  Camera camera;
  bool use_scene_camera = true;
  bool camera_initialized = false;
  bool overlays = false;         // springs, constraints, the wireframe (View menu)
  bool show_controllers = true;  // the controllers' plot, when the scene has controllers
  // The control panel's target being dragged (figure, controller; -1: none), its value and the
  // scene before the drag (one undo step for the whole drag).
  int control_figure = -1, control_index = -1;
  double control_value = 0;
  nlohmann::json control_scene_before;
  // The jog lever being held (figure, controller; -1: none) and its speed [/s]; it springs back
  // to 0 when released. Its undo step shares control_scene_before (one widget at a time).
  int jog_figure = -1, jog_index = -1;
  double jog_rate = 0;
  // The first controller's jog lever as last drawn (x0, y0, x1, y1 in viewport pixels; empty
  // before it is), where pbm-studio --smoke --jog takes hold of it.
  std::array<float, 4> first_jog_rect{};
  // The keyboard lever: Page Up / Page Down held jog one controller (figure, controller) at
  // +-lever_speed; lever_direction is the keys' state last frame (-1, 0, 1), and the hold is one
  // undo step (lever_scene_before).
  int lever_figure = 0, lever_index = 0;
  double lever_speed = 0.2;
  int lever_direction = 0;
  nlohmann::json lever_scene_before;
  int samples = 2;  // viewport MSAA: llvmpipe pays per sample
  double speed = 1.0;
  std::deque<StatsSample> plot;  // the last seconds
  int last_plotted_frame = -1;
  std::string message;  // last error shown in the status line
  // The speed-versus-accuracy panel: its sweep in the background and the last report.
  struct Tradeoff {
    bool show = false;
    std::unique_ptr<TradeoffJob> job = std::make_unique<TradeoffJob>();
    std::optional<TradeoffReport> report;
    std::uint64_t revision = 0;  // scene revision the report measured
    float seconds = 2;
    bool dt = true, integrator = true, tolerance = false, resolution = true, contact = false;
    // The figures' physics knobs (sim/tradeoff.h): each setting gets a reference of its own.
    bool stiffness = false, restitution = false, gains = false, settling = false;
    int selected = -1;  // point under the last click
  } tradeoff;
  bool dirty() const { return status.scene_revision != saved_revision; }
};

}  // namespace pbm
