// pbm-studio [scene]: the editor. pbm-studio --smoke <scene> --frames N [--drag x0,y0:x1,y1]
// --screenshot out.png [--report out.json]: opens the real window (under Xvfb in CI), steps N
// frames through the real Runner and UI path, performs the drag in window pixels, saves a
// screenshot and the bodies' centres, and exits 0.
#include <QApplication>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTimer>
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "main_window.h"
#include "viewport.h"

namespace {

struct SmokeOptions {
  QString scene, screenshot, report;
  int frames = 0;
  std::optional<QLineF> drag;
  bool overlays = false;  // View > Overlays on
  // --tradeoff T: after the frames, the speed-vs-accuracy panel measures the scene (dt and
  // integrator, T s per run) in the background, applies the front's most accurate point, and
  // the report says what it found and what the scene's solver became.
  double tradeoff_seconds = 0;
  // --keys F0:F1: Page Up held from frame F0 to frame F1, the keyboard lever of the Controllers
  // panel (its first controller unless chosen); the report lists every controller's live keys.
  std::optional<std::pair<int, int>> keys;
  // --jog F0:F1: the first controller's jog lever pressed at frame F0, pushed right kJogPixels
  // a frame and let go at F1, as a user drags it; the report lists the live keys it recorded.
  std::optional<std::pair<int, int>> jog;
};

constexpr double kJogPixels = 4;

int usage(const char* why) {
  std::cerr
      << "error: " << why
      << "\nusage: pbm-studio [scene.json]\n"
         "       pbm-studio --smoke <scene.json> --frames N [--drag x0,y0:x1,y1] "
         "[--overlays] [--tradeoff SECONDS] [--keys F0:F1] [--jog F0:F1] --screenshot out.png "
         "[--report out.json]\n";
  return 2;
}

// "F0:F1" with 0 <= F0 and F0 + min_span <= F1.
std::optional<std::pair<int, int>> frame_range(const std::optional<QString>& text, int min_span) {
  const QStringList ends = text ? text->split(':') : QStringList();
  bool ok0 = false, ok1 = false;
  const int f0 = ends.size() == 2 ? ends[0].toInt(&ok0) : 0;
  const int f1 = ends.size() == 2 ? ends[1].toInt(&ok1) : 0;
  if (!ok0 || !ok1 || f0 < 0 || f1 < f0 + min_span) return std::nullopt;
  return std::make_pair(f0, f1);
}

// Drives the window frame by frame: step, wait for the runner to show it, move the mouse.
class SmokeRun : public QObject {
 public:
  SmokeRun(pbm::MainWindow& window, SmokeOptions options)
      : window_(window), options_(std::move(options)) {
    connect(&timer_, &QTimer::timeout, this, [this] { tick(); });
    timer_.start(1);
  }
  int result() const { return result_; }

 private:
  // A drag in window pixels with Ctrl held: the mouse spring.
  void send(QEvent::Type type, QPointF window_point, Qt::MouseButton button,
            Qt::MouseButtons buttons) {
    const QPointF local = window_.viewport()->mapFrom(&window_, window_point.toPoint());
    send_local(type, local, button, buttons, Qt::ControlModifier);
  }

  void send_local(QEvent::Type type, QPointF local, Qt::MouseButton button,
                  Qt::MouseButtons buttons, Qt::KeyboardModifiers modifiers) {
    pbm::Viewport* viewport = window_.viewport();
    QMouseEvent event(type, local, viewport->mapToGlobal(local), button, buttons, modifiers);
    QApplication::sendEvent(viewport, &event);
  }

  void send_key(QEvent::Type type, int key) {
    QKeyEvent event(type, key, Qt::NoModifier);
    QApplication::sendEvent(window_.viewport(), &event);
  }

  void tick() {
    pbm::Studio& studio = window_.studio();
    if (!studio.runner) return fail("no scene");
    window_.viewport()->refresh();
    const pbm::RunnerStatus& s = studio.status;
    // A frame the runner could not compute leaves it paused short of the request, saying why.
    if (!s.message.empty() && s.frame < requested_ && !s.playing && waited_ > 50) {
      return fail(s.message);
    }
    if (s.frame != requested_ || s.playing) {  // the runner is still on it
      ++waited_;
      return;
    }
    waited_ = 0;
    if (requested_ >= options_.frames || requested_ >= s.last_frame) {
      if (options_.tradeoff_seconds > 0 && !tradeoff_done()) return;
      return finish();
    }
    if (options_.drag) {
      const int begin = options_.frames / 4, end = (3 * options_.frames) / 4;
      const QLineF& d = *options_.drag;
      if (requested_ == begin) {
        send(QEvent::MouseButtonPress, d.p1(), Qt::LeftButton, Qt::LeftButton);
      } else if (requested_ > begin && requested_ < end) {
        const double f = static_cast<double>(requested_ - begin) / (end - begin);
        send(QEvent::MouseMove, d.pointAt(f), Qt::NoButton, Qt::LeftButton);
      } else if (requested_ == end) {
        send(QEvent::MouseMove, d.p2(), Qt::NoButton, Qt::LeftButton);
        send(QEvent::MouseButtonRelease, d.p2(), Qt::LeftButton, Qt::NoButton);
      }
    }
    // The keyboard lever: the panel sees the key at the repaint below and posts the jog before
    // the frame's step, as when a user holds the key.
    if (options_.keys && requested_ == options_.keys->first) {
      send_key(QEvent::KeyPress, Qt::Key_PageUp);
    } else if (options_.keys && requested_ == options_.keys->second) {
      send_key(QEvent::KeyRelease, Qt::Key_PageUp);
    }
    // The jog lever, without Ctrl (Ctrl+click turns an ImGui drag into a text field): pressed
    // where the panel last drew it, then pushed right a few pixels each frame.
    if (options_.jog) {
      const auto [f0, f1] = *options_.jog;
      const std::array<float, 4>& r = studio.first_jog_rect;
      if (requested_ == f0) {
        if (!(r[2] > r[0])) return fail("--jog: no controller's jog lever was drawn");
        jog_start_ = QPointF(0.5 * (r[0] + r[2]), 0.5 * (r[1] + r[3]));
        send_local(QEvent::MouseButtonPress, jog_start_, Qt::LeftButton, Qt::LeftButton,
                   Qt::NoModifier);
      } else if (requested_ > f0 && requested_ <= f1) {
        const int pushed = std::min(requested_, f1 - 1) - f0;
        const QPointF at = jog_start_ + QPointF(kJogPixels * pushed, 0);
        if (requested_ < f1) {
          send_local(QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        } else {
          send_local(QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton, Qt::NoModifier);
        }
      }
    }
    window_.viewport()->repaint();
    studio.runner->post(pbm::StepFrame{});
    ++requested_;
  }

  // The trade panel's sweep, driven as a user would: Measure, wait, Apply. True once the applied
  // scene is the runner's.
  bool tradeoff_done() {
    pbm::Studio& studio = window_.studio();
    pbm::Studio::Tradeoff& t = studio.tradeoff;
    switch (tradeoff_stage_) {
      case 0:
        t.show = true;
        t.dt = t.integrator = true;
        t.tolerance = t.resolution = false;
        t.seconds = static_cast<float>(options_.tradeoff_seconds);
        t.report.reset();
        t.job->start(*studio.status.scene, {"dt", "integrator"}, options_.tradeoff_seconds);
        tradeoff_stage_ = 1;
        return false;
      case 1: {
        // The panel takes the report as soon as it is drawn; so may this.
        if (auto report = t.job->take_report()) t.report = std::move(report);
        if (t.job->progress().running) return false;
        if (!t.report) {
          fail("the trade-off sweep failed: " + t.job->error());
          return false;
        }
        const pbm::TradeoffPoint* best = nullptr;
        for (const pbm::TradeoffPoint& p : t.report->points) {
          if (p.pareto && (!best || p.centre_error < best->centre_error)) best = &p;
        }
        if (!best) {
          fail("the trade-off sweep has no front");
          return false;
        }
        applied_ = best->setting;
        const std::string error = window_.edit(
            "", pbm::scene_with_setting(*studio.status.scene, applied_), "apply trade-off point");
        if (!error.empty()) {
          fail(error);
          return false;
        }
        tradeoff_stage_ = 2;
        return false;
      }
      default:
        return studio.status.scene && studio.status.scene->solver.dt == applied_.dt &&
               studio.status.scene->solver.integrator == applied_.integrator;
    }
  }

  void fail(const std::string& why) {
    std::cerr << "error: smoke run: " << why << "\n";
    result_ = 1;
    timer_.stop();
    QApplication::exit(1);
  }

  void finish() {
    timer_.stop();
    window_.viewport()->repaint();
    const QImage image = window_.grab().toImage();
    if (image.isNull() || !image.save(options_.screenshot)) {
      return fail("cannot write the screenshot " + options_.screenshot.toStdString());
    }
    if (!options_.report.isEmpty()) {
      const pbm::Camera camera = window_.viewport()->view_camera();
      nlohmann::json report = {
          {"frame", window_.studio().status.frame},
          {"time", window_.studio().snapshot ? window_.studio().snapshot->time : 0.0},
          {"camera", {camera.position.x(), camera.position.y(), camera.position.z()}},
          {"bodies", nlohmann::json::array()}};
      if (const auto& snap = window_.studio().snapshot) {
        for (const pbm::draw::Mesh& body : snap->meshes) {
          if (body.pick < 0 || !body.positions) continue;  // the bodies are the pickable meshes
          Eigen::Vector3f c = Eigen::Vector3f::Zero();
          for (const Eigen::Vector3f& p : *body.positions) c += body.rotation * p + body.offset;
          c /= static_cast<float>(std::max<std::size_t>(1, body.positions->size()));
          report["bodies"].push_back({{"name", body.name}, {"center", {c.x(), c.y(), c.z()}}});
        }
        // Figures: each segment's shape centre, and the site actuators the scene now has (a
        // drag on a figure adds one).
        const pbm::Scene& scene = *window_.studio().status.scene;
        report["figures"] = nlohmann::json::array();
        for (const pbm::FigureDef& figure : scene.figures) {
          nlohmann::json live = nlohmann::json::array();
          for (const pbm::ControllerDef& c : figure.controllers) {
            nlohmann::json keys = nlohmann::json::array();
            for (const pbm::LiveKey& k : c.live) keys.push_back({k.time, k.value, k.rate});
            live.push_back(keys);
          }
          report["figures"].push_back({{"name", figure.name},
                                       {"site_actuators", figure.site_actuators.size()},
                                       {"live", live},
                                       {"segments", nlohmann::json::array()}});
        }
        report["fps"] = scene.solver.fps;
        const pbm::SceneEdit* last = window_.studio().history.next_undo();
        report["undo"] = last ? last->label : "";
        for (const pbm::draw::Primitive& p : snap->primitives) {
          if (p.figure < 0 || p.figure >= static_cast<int>(report["figures"].size())) continue;
          report["figures"][p.figure]["segments"].push_back(
              {p.center.x(), p.center.y(), p.center.z()});
        }
      }
      const pbm::Studio::Tradeoff& t = window_.studio().tradeoff;
      if (t.report) {
        int front = 0, ok = 0;
        for (const pbm::TradeoffPoint& p : t.report->points) {
          front += p.pareto;
          ok += p.ok;
        }
        const pbm::Scene& scene = *window_.studio().status.scene;
        report["tradeoff"] = {{"points", t.report->points.size()},
                              {"ok", ok},
                              {"front", front},
                              {"applied", applied_.label()},
                              {"solver_dt", scene.solver.dt},
                              {"shape_inertia_time", scene.solver.shape_inertia_time.value_or(0)}};
      }
      std::ofstream(options_.report.toStdString()) << report.dump(2) << "\n";
    }
    std::cout << "smoke: " << window_.studio().status.frame << " frames, screenshot "
              << options_.screenshot.toStdString() << " (" << image.width() << "x" << image.height()
              << ")\n";
    result_ = 0;
    QApplication::exit(0);
  }

  pbm::MainWindow& window_;
  SmokeOptions options_;
  int tradeoff_stage_ = 0;
  pbm::TradeoffSetting applied_;
  QTimer timer_;
  int requested_ = 0;
  QPointF jog_start_;
  int waited_ = 0;  // ticks since the last step was posted
  int result_ = 1;
};

}  // namespace

int main(int argc, char** argv) {
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);
  QApplication app(argc, argv);
  QApplication::setApplicationName("pbm-studio");
  QApplication::setOrganizationName("pbm");

  const QStringList args = QApplication::arguments();
  std::optional<SmokeOptions> smoke;
  QString scene;
  for (int i = 1; i < args.size(); ++i) {
    const QString& a = args[i];
    auto value = [&](const char* what) -> std::optional<QString> {
      if (i + 1 >= args.size()) return std::nullopt;
      (void)what;
      return args[++i];
    };
    if (a == "--smoke") {
      smoke.emplace();
      auto v = value("scene");
      if (!v) return usage("--smoke needs a scene file");
      smoke->scene = *v;
    } else if (a == "--frames" && smoke) {
      auto v = value("frames");
      bool ok = false;
      smoke->frames = v ? v->toInt(&ok) : 0;
      if (!ok || smoke->frames < 1) return usage("--frames needs a positive integer");
    } else if (a == "--drag" && smoke) {
      auto v = value("drag");
      const QStringList ends = v ? v->split(':') : QStringList();
      const QStringList p0 = ends.size() == 2 ? ends[0].split(',') : QStringList();
      const QStringList p1 = ends.size() == 2 ? ends[1].split(',') : QStringList();
      if (p0.size() != 2 || p1.size() != 2) return usage("--drag needs x0,y0:x1,y1");
      smoke->drag = QLineF(p0[0].toDouble(), p0[1].toDouble(), p1[0].toDouble(), p1[1].toDouble());
    } else if (a == "--tradeoff" && smoke) {
      auto v = value("tradeoff");
      bool ok = false;
      smoke->tradeoff_seconds = v ? v->toDouble(&ok) : 0;
      if (!ok || !(smoke->tradeoff_seconds > 0)) return usage("--tradeoff needs seconds > 0");
    } else if (a == "--keys" && smoke) {
      smoke->keys = frame_range(value("keys"), 1);
      if (!smoke->keys) return usage("--keys needs frames F0:F1, F0 < F1");
    } else if (a == "--jog" && smoke) {
      smoke->jog = frame_range(value("jog"), 2);
      if (!smoke->jog) return usage("--jog needs frames F0:F1, F0 + 1 < F1");
    } else if (a == "--overlays" && smoke) {
      smoke->overlays = true;
    } else if (a == "--screenshot" && smoke) {
      auto v = value("screenshot");
      if (!v) return usage("--screenshot needs a file");
      smoke->screenshot = *v;
    } else if (a == "--report" && smoke) {
      auto v = value("report");
      if (!v) return usage("--report needs a file");
      smoke->report = *v;
    } else if (!a.startsWith("--") && scene.isEmpty()) {
      scene = a;
    } else {
      return usage(("unknown argument " + a.toStdString()).c_str());
    }
  }
  if (smoke && (smoke->frames < 1 || smoke->screenshot.isEmpty())) {
    return usage("--smoke needs --frames and --screenshot");
  }

  pbm::MainWindow window(smoke.has_value());
  window.resize(1280, 800);
  window.show();
  if (smoke) {
    if (!window.open_scene(smoke->scene)) return 2;
    if (smoke->overlays) window.trigger_overlays();
    SmokeRun run(window, *smoke);
    QApplication::exec();
    return run.result();
  }
  if (!scene.isEmpty()) {
    if (!window.open_scene(scene)) window.new_scene();
  } else {
    window.new_scene();
    window.offer_recovery();
  }
  return QApplication::exec();
}
