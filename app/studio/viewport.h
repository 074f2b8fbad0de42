// The studio's 3D view: the shared renderer (ui/renderer.h) through Qt's context, Dear ImGui's
// panels over it with Qt's input bridged into ImGui's IO, camera navigation (orbit, pan, zoom,
// frame selection), selection by click and the mouse spring of sec. 6.4 (Ctrl + left drag, or
// right drag).
#pragma once

#include <QElapsedTimer>
#include <QOpenGLWidget>
#include <memory>
#include <optional>

#include "gl_functions.h"
#include "studio.h"

struct ImGuiContext;

namespace pbm {

class Renderer;
class ImGuiRenderer;

class Viewport : public QOpenGLWidget {
  Q_OBJECT
 public:
  Viewport(Studio& studio, StudioActions& actions, QWidget* parent = nullptr);
  ~Viewport() override;
  void frame_selection();
  // Pulls the runner's latest snapshot and status into the Studio (UI thread, every tick).
  void refresh();
  // What the viewport draws from: the latest snapshot's camera (the scene's, its tracks at that
  // frame's time) while View > View from scene camera is on and the scene has one, else the
  // user's.
  Camera view_camera() const;

 protected:
  void initializeGL() override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void keyReleaseEvent(QKeyEvent* event) override;

 private:
  bool imgui_wants_mouse() const;
  void set_mouse(QMouseEvent* event, bool down);

  Studio& studio_;
  StudioActions& actions_;
  gl::Functions gl_;
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<ImGuiRenderer> imgui_renderer_;
  ImGuiContext* imgui_ = nullptr;
  QElapsedTimer clock_;
  enum class Drag { none, orbit, pan, spring } drag_ = Drag::none;
  QPointF last_;
  Eigen::Vector3f spring_point_ = Eigen::Vector3f::Zero();
  nlohmann::json drag_scene_before_;  // for the drag's undo entry
};

}  // namespace pbm
