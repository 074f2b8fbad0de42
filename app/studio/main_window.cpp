#include "main_window.h"

#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProcess>
#include <QSettings>
#include <QStandardPaths>
#include <QStatusBar>
#include <iostream>

#include "core/error.h"
#include "scene/scene_json.h"
#include "viewport.h"

namespace pbm {

using json = nlohmann::json;

namespace {

constexpr int kAutosaveMilliseconds = 2 * 60 * 1000;
const QStringList kMeshSuffixes{"obj", "gltf", "glb", "fbx", "ply", "stl", "dae", "3ds"};

QString autosave_path() {
  return studio_state_folder() + "/autosave.json";
}
// Present while a studio runs; left behind by a crash.
QString running_marker() {
  return studio_state_folder() + "/running";
}

Scene default_scene() {
  const json j = {{"name", "untitled"},
                  {"camera", {{"position", {0, -9, 3.5}}, {"target", {0, 0, 1}}, {"fov", 40}}},
                  {"solver", {{"dt", 0.002}, {"fps", 30}, {"duration", 10}}},
                  {"bodies", {body_preset("sphere", "ball", Vec3(0, 0, 2.5))}},
                  {"obstacles",
                   {{{"name", "ground"},
                     {"kind", "plane"},
                     {"point", {0, 0, 0}},
                     {"normal", {0, 0, 1}},
                     {"size", {12, 12}}}}}};
  return parse_scene(j.dump(), "untitled.json");
}

}  // namespace

QString studio_state_folder() {
  QString folder = QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation);
  if (folder.isEmpty()) folder = QDir::homePath() + "/.local/state/pbm-studio";
  QDir().mkpath(folder);
  return folder;
}

MainWindow::MainWindow(bool smoke) : smoke_(smoke) {
  setAcceptDrops(true);
  viewport_ = new Viewport(studio_, *this, this);
  setCentralWidget(viewport_);

  QMenu* file = menuBar()->addMenu("&File");
  file->addAction("&New", QKeySequence::New, this, [this] {
    if (maybe_save()) new_scene();
  });
  file->addAction("&Open...", QKeySequence::Open, this, [this] {
    if (!maybe_save()) return;
    const QString path =
        QFileDialog::getOpenFileName(this, "Open scene", QString(), "Scenes (*.json)");
    if (!path.isEmpty()) open_scene(path);
  });
  recent_menu_ = file->addMenu("Open &Recent");
  rebuild_recent_menu();
  file->addAction("&Save", QKeySequence::Save, this, [this] { save(); });
  file->addAction("Save &As...", QKeySequence::SaveAs, this, [this] { save_as(); });
  file->addAction("Re&vert", this, [this] { revert(); });
  file->addSeparator();
  file->addAction("&Import mesh as obstacle...", this, [this] {
    const QString path =
        QFileDialog::getOpenFileName(this, "Import mesh", QString(),
                                     "Meshes (*.obj *.gltf *.glb *.fbx *.ply *.stl *.dae *.3ds)");
    if (!path.isEmpty()) import_mesh(path);
  });
  file->addAction("&Export frames...", this, [this] { export_frames(); });
  file->addSeparator();
  file->addAction("&Quit", QKeySequence::Quit, this, [this] { close(); });

  QMenu* edit_menu = menuBar()->addMenu("&Edit");
  undo_ = edit_menu->addAction("&Undo", QKeySequence::Undo, this, [this] { undo(); });
  redo_ = edit_menu->addAction("&Redo", QKeySequence::Redo, this, [this] { redo(); });

  QMenu* view = menuBar()->addMenu("&View");
  view->addAction("&Frame selection", Qt::Key_F, this, [this] { viewport_->frame_selection(); });
  scene_camera_ = view->addAction("View from &scene camera", this,
                                  [this](bool on) { studio_.use_scene_camera = on; });
  scene_camera_->setCheckable(true);
  scene_camera_->setChecked(true);
  // The editor's layer of the snapshot (draw::Layer::overlay), as `pbm render --overlays`.
  overlays_ = view->addAction("&Overlays (springs, constraints, wireframe)", this,
                              [this](bool on) { studio_.overlays = on; });
  overlays_->setCheckable(true);
  QAction* msaa = view->addAction("&Antialiasing (4x)", this,
                                  [this](bool on) { studio_.samples = on ? 4 : 2; });
  msaa->setCheckable(true);

  QMenu* simulation = menuBar()->addMenu("&Simulation");
  simulation->addAction("&Play / pause", Qt::Key_Space, this, [this] {
    if (studio_.runner)
      studio_.runner->post(studio_.status.playing ? Command(Pause{}) : Command(Play{}));
  });
  simulation->addAction("&Step one frame", Qt::Key_Period, this, [this] {
    if (studio_.runner) studio_.runner->post(StepFrame{});
  });
  simulation->addAction("&Reset to start", Qt::Key_Home, this, [this] {
    if (studio_.runner) studio_.runner->post(ResetToStart{});
  });

  QMenu* help = menuBar()->addMenu("&Help");
  help->addAction("&Controls", this, [this] {
    QMessageBox::information(
        this, "Controls",
        "Left drag: orbit. Shift + left drag or middle drag: pan. Wheel: zoom.\n"
        "Click a body: select it. F: frame the selection. Space: play / pause.\n"
        "Ctrl + left drag or right drag on a body: pull it with a spring (sec. 6.4); the drag is "
        "recorded in the scene as a spring with keyframed targets.\n"
        "Drop a scene file to open it, or a mesh (OBJ, glTF, FBX, PLY, STL) to add an obstacle.");
  });
  help->addAction("&About", this, [this] {
    QMessageBox::about(this, "PBM Studio",
                       "PBM Studio: physics-based deformable models after D. Metaxas (1997).");
  });

  connect(&tick_, &QTimer::timeout, this, [this] {
    viewport_->update();
    update_title_and_actions();
  });
  tick_.start(16);
  connect(&autosave_timer_, &QTimer::timeout, this, [this] { autosave(); });
  autosave_timer_.start(kAutosaveMilliseconds);
  if (!smoke_) {
    previous_session_crashed_ = QFile::exists(running_marker());
    QFile marker(running_marker());
    if (marker.open(QIODevice::WriteOnly)) marker.write("pbm-studio\n");
  }
  resize(1280, 800);
}

MainWindow::~MainWindow() {
  tick_.stop();
  studio_.runner.reset();
  if (!smoke_) QFile::remove(running_marker());
}

void MainWindow::report(const QString& message) {
  if (smoke_) {
    std::cerr << "error: " << message.toStdString() << "\n";
  } else {
    QMessageBox::warning(this, "PBM Studio", message);
  }
  studio_.message = message.toStdString();
}

void MainWindow::start(const Scene& scene, const QString& path) {
  RunnerOptions options;
  options.real_time = true;
  options.speed = studio_.speed;
  auto runner = std::make_unique<Runner>(scene, options);  // throws on a bad scene: keep the old
  studio_.runner = std::move(runner);
  studio_.path = path.toStdString();
  studio_.history.clear();
  studio_.selection = {};
  studio_.snapshot.reset();
  studio_.plot.clear();
  studio_.last_plotted_frame = -1;
  studio_.camera_initialized = false;
  studio_.use_scene_camera = true;
  studio_.message.clear();
  studio_.status = studio_.runner->status();
  studio_.saved_revision = studio_.status.scene_revision;
  scene_camera_->setChecked(true);
  update_title_and_actions();
}

bool MainWindow::open_scene(const QString& path) {
  try {
    start(load_scene(path.toStdString()), path);
  } catch (const std::exception& e) {
    report(QString::fromStdString(e.what()));
    return false;
  }
  remember_recent(path);
  return true;
}

void MainWindow::new_scene() {
  start(default_scene(), QString());
}

void MainWindow::trigger_overlays() {
  overlays_->trigger();
}

std::string MainWindow::edit(const std::string& pointer, const json& value,
                             const std::string& label) {
  if (!studio_.runner || !studio_.status.scene) return "no scene";
  std::string error;
  if (!apply_edit(*studio_.status.scene, pointer, value, error)) return error;
  studio_.history.push(make_edit(*studio_.status.scene, pointer, value, label));
  studio_.runner->post(EditScene{pointer, value.dump()});
  studio_.message.clear();
  return "";
}

void MainWindow::undo() {
  if (!studio_.history.can_undo() || !studio_.runner) return;
  SceneEdit& e = studio_.history.undo();
  if (e.after.is_null() && studio_.status.scene) {  // a drag: redo restores what it recorded
    e.after = json::parse(scene_to_json(*studio_.status.scene));
  }
  studio_.runner->post(EditScene{e.pointer, e.before.dump()});
}

void MainWindow::redo() {
  if (!studio_.history.can_redo() || !studio_.runner) return;
  const SceneEdit& e = studio_.history.redo();
  studio_.runner->post(EditScene{e.pointer, e.after.dump()});
}

bool MainWindow::save() {
  if (studio_.path.empty()) return save_as();
  if (!studio_.runner) return false;
  // The runner's scene, with every edit it has applied; one posted in this very instant shows
  // up after it, and the title's "*" then says the file is behind.
  const RunnerStatus s = studio_.runner->status();
  try {
    save_scene(*s.scene, studio_.path);  // temporary file, then rename (scene_json.h)
  } catch (const std::exception& e) {
    report(QString::fromStdString(e.what()));
    return false;
  }
  studio_.saved_revision = s.scene_revision;
  remember_recent(QString::fromStdString(studio_.path));
  statusBar()->showMessage("saved " + QString::fromStdString(studio_.path), 3000);
  return true;
}

bool MainWindow::save_as() {
  const QString path = QFileDialog::getSaveFileName(
      this, "Save scene", QString::fromStdString(studio_.path), "Scenes (*.json)");
  if (path.isEmpty()) return false;
  studio_.path = path.toStdString();
  return save();
}

void MainWindow::revert() {
  if (studio_.path.empty()) return;
  if (studio_.dirty() &&
      QMessageBox::question(this, "Revert", "Discard the changes since the last save?") !=
          QMessageBox::Yes) {
    return;
  }
  open_scene(QString::fromStdString(studio_.path));
}

bool MainWindow::maybe_save() {
  if (!studio_.runner || !studio_.dirty() || smoke_) return true;
  const auto answer =
      QMessageBox::question(this, "Unsaved changes", "The scene has unsaved changes. Save them?",
                            QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
  if (answer == QMessageBox::Cancel) return false;
  if (answer == QMessageBox::Save) return save();
  return true;
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (maybe_save()) {
    event->accept();
  } else {
    event->ignore();
  }
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  for (const QUrl& url : event->mimeData()->urls()) {
    const QString path = url.toLocalFile();
    const QString suffix = QFileInfo(path).suffix().toLower();
    if (suffix == "json") {
      if (maybe_save()) open_scene(path);
      return;
    }
    if (kMeshSuffixes.contains(suffix)) import_mesh(path);
  }
}

void MainWindow::import_mesh(const QString& path) {
  if (!studio_.status.scene) return;
  json scene = json::parse(scene_to_json(*studio_.status.scene));
  json obstacles = scene.contains("obstacles") ? scene["obstacles"] : json::array();
  obstacles.push_back({{"name", QFileInfo(path).completeBaseName().toStdString()},
                       {"kind", "mesh"},
                       {"file", QFileInfo(path).absoluteFilePath().toStdString()},
                       {"position", {0, 0, 0}}});
  const std::string error = edit("/obstacles", obstacles, "import mesh");
  if (!error.empty()) report(QString::fromStdString(error));
}

void MainWindow::export_frames() {
  if (!studio_.status.scene) return;
  const QString folder = QFileDialog::getExistingDirectory(this, "Export frames to");
  if (folder.isEmpty()) return;
  // The headless renderer writes the same frames as `pbm render` (same scene, same solver).
  const QString scene_file = folder + "/scene.json";
  try {
    save_scene(*studio_.status.scene, scene_file.toStdString());
  } catch (const std::exception& e) {
    report(QString::fromStdString(e.what()));
    return;
  }
  auto* process = new QProcess(this);
  connect(process, &QProcess::finished, this, [this, process, folder](int code) {
    statusBar()->showMessage(code == 0
                                 ? "frames written to " + folder
                                 : "export failed: " + QString(process->readAllStandardError()),
                             10000);
    process->deleteLater();
  });
  process->start(QCoreApplication::applicationDirPath() + "/pbm",
                 {"render", scene_file, "--out", folder + "/frames"});
  statusBar()->showMessage("exporting frames to " + folder + " ...");
}

void MainWindow::autosave() {
  if (!studio_.runner || !studio_.status.scene || !studio_.dirty()) return;
  try {
    save_scene(*studio_.status.scene, autosave_path().toStdString());
  } catch (const std::exception& e) {
    statusBar()->showMessage(QString("autosave failed: ") + e.what(), 5000);
  }
}

void MainWindow::offer_recovery() {
  // The marker is written at start and removed at a clean exit: found at start means a crash.
  if (smoke_ || !previous_session_crashed_ || !QFile::exists(autosave_path())) return;
  if (QMessageBox::question(this, "Recover",
                            "PBM Studio did not close cleanly. Open the autosaved scene?") ==
      QMessageBox::Yes) {
    if (open_scene(autosave_path())) studio_.path.clear();  // the user chooses where to save it
  }
}

void MainWindow::update_title_and_actions() {
  const QString name = studio_.path.empty()
                           ? QString("untitled")
                           : QFileInfo(QString::fromStdString(studio_.path)).fileName();
  setWindowTitle(name + (studio_.dirty() ? " *" : "") + " - PBM Studio");
  const SceneEdit* u = studio_.history.next_undo();
  const SceneEdit* r = studio_.history.next_redo();
  undo_->setEnabled(u != nullptr);
  undo_->setText(u ? "&Undo " + QString::fromStdString(u->label) : "&Undo");
  redo_->setEnabled(r != nullptr);
  redo_->setText(r ? "&Redo " + QString::fromStdString(r->label) : "&Redo");
}

void MainWindow::remember_recent(const QString& path) {
  QSettings settings("pbm", "pbm-studio");
  QStringList recent = settings.value("recent").toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  recent.removeAll(absolute);
  recent.prepend(absolute);
  while (recent.size() > 10) recent.removeLast();
  settings.setValue("recent", recent);
  rebuild_recent_menu();
}

void MainWindow::rebuild_recent_menu() {
  recent_menu_->clear();
  const QStringList recent = QSettings("pbm", "pbm-studio").value("recent").toStringList();
  for (const QString& path : recent) {
    recent_menu_->addAction(path, this, [this, path] {
      if (maybe_save()) open_scene(path);
    });
  }
  recent_menu_->setEnabled(!recent.isEmpty());
}

}  // namespace pbm
