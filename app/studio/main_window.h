// The studio's window: menus (File, Edit, View, Simulation, Help), the viewport, files (atomic
// save, autosave, crash recovery, recent files, drag and drop, mesh import) and the edit history.
#pragma once

#include <QMainWindow>
#include <QStringList>
#include <QTimer>

#include "studio.h"

class QAction;
class QMenu;

namespace pbm {

class Viewport;

class MainWindow : public QMainWindow, public StudioActions {
  Q_OBJECT
 public:
  // smoke: no dialogs (scripted runs under Xvfb); errors go to stderr instead.
  explicit MainWindow(bool smoke = false);
  ~MainWindow() override;

  // Opens a scene file; false (and a message) when it does not load.
  bool open_scene(const QString& path);
  void new_scene();
  Viewport* viewport() const { return viewport_; }
  Studio& studio() { return studio_; }
  // Offers the autosave of a session that did not end cleanly (not in smoke mode).
  void offer_recovery();
  // What View > Overlays does (smoke runs).
  void trigger_overlays();

  std::string edit(const std::string& pointer, const nlohmann::json& value,
                   const std::string& label) override;
  void undo() override;
  void redo() override;

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  bool maybe_save();  // asks about unsaved changes; false = cancel
  bool save();
  bool save_as();
  void revert();
  void export_frames();
  void import_mesh(const QString& path);
  void autosave();
  void start(const Scene& scene, const QString& path);
  void update_title_and_actions();
  void remember_recent(const QString& path);
  void rebuild_recent_menu();
  void report(const QString& message);

  Studio studio_;
  Viewport* viewport_ = nullptr;
  bool smoke_ = false;
  bool previous_session_crashed_ = false;
  QTimer tick_, autosave_timer_;
  QMenu* recent_menu_ = nullptr;
  QAction *undo_ = nullptr, *redo_ = nullptr, *scene_camera_ = nullptr, *overlays_ = nullptr;
};

// Where autosaves and the crash marker live (the user's state folder).
QString studio_state_folder();

}  // namespace pbm
