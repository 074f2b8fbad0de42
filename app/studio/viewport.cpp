#include "viewport.h"

#include <imgui.h>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "imgui_renderer.h"
#include "panels.h"
#include "picking.h"
#include "renderer.h"
#include "scene/scene_json.h"

namespace pbm {

using Vec3f = Eigen::Vector3f;

namespace {

void* qt_proc_address(const char* name) {
  return reinterpret_cast<void*>(QOpenGLContext::currentContext()->getProcAddress(name));
}

// ImGui 1.86 reads keys from io.KeysDown[] at indices the application chooses (io.KeyMap).
struct KeyMapping {
  Qt::Key qt;
  ImGuiKey imgui;
};
constexpr KeyMapping kKeys[] = {
    {Qt::Key_Tab, ImGuiKey_Tab},
    {Qt::Key_Left, ImGuiKey_LeftArrow},
    {Qt::Key_Right, ImGuiKey_RightArrow},
    {Qt::Key_Up, ImGuiKey_UpArrow},
    {Qt::Key_Down, ImGuiKey_DownArrow},
    {Qt::Key_PageUp, ImGuiKey_PageUp},
    {Qt::Key_PageDown, ImGuiKey_PageDown},
    {Qt::Key_Home, ImGuiKey_Home},
    {Qt::Key_End, ImGuiKey_End},
    {Qt::Key_Insert, ImGuiKey_Insert},
    {Qt::Key_Delete, ImGuiKey_Delete},
    {Qt::Key_Backspace, ImGuiKey_Backspace},
    {Qt::Key_Space, ImGuiKey_Space},
    {Qt::Key_Return, ImGuiKey_Enter},
    {Qt::Key_Enter, ImGuiKey_KeyPadEnter},
    {Qt::Key_Escape, ImGuiKey_Escape},
    {Qt::Key_A, ImGuiKey_A},
    {Qt::Key_C, ImGuiKey_C},
    {Qt::Key_V, ImGuiKey_V},
    {Qt::Key_X, ImGuiKey_X},
    {Qt::Key_Y, ImGuiKey_Y},
    {Qt::Key_Z, ImGuiKey_Z},
};

int key_slot(int qt_key) {
  for (int i = 0; i < static_cast<int>(std::size(kKeys)); ++i) {
    if (kKeys[i].qt == qt_key) return i + 1;
  }
  return -1;
}

}  // namespace

Viewport::Viewport(Studio& studio, StudioActions& actions, QWidget* parent)
    : QOpenGLWidget(parent), studio_(studio), actions_(actions) {
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true);
  IMGUI_CHECKVERSION();
  imgui_ = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is fixed; nothing to remember
  for (int i = 0; i < static_cast<int>(std::size(kKeys)); ++i) io.KeyMap[kKeys[i].imgui] = i + 1;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 0;
  ImGui::GetStyle().Alpha = 0.94f;
  clock_.start();
}

Viewport::~Viewport() {
  makeCurrent();
  renderer_.reset();
  ImGui::SetCurrentContext(imgui_);
  imgui_renderer_.reset();
  doneCurrent();
  ImGui::DestroyContext(imgui_);
}

void Viewport::initializeGL() {
  gl_ = gl::load_functions(qt_proc_address);
  gl::require_version(gl_, 3, 3);
  renderer_ = std::make_unique<Renderer>(gl_);
  ImGui::SetCurrentContext(imgui_);
  imgui_renderer_ = std::make_unique<ImGuiRenderer>(gl_);
}

void Viewport::refresh() {
  if (!studio_.runner) return;
  studio_.status = studio_.runner->status();
  if (auto snap = studio_.runner->snapshot()) studio_.snapshot = std::move(snap);
  const RunnerStatus& s = studio_.status;
  if (s.frame != studio_.last_plotted_frame) {
    StatsSample p;
    p.frame = s.frame;
    p.kinetic = static_cast<float>(s.stats.kinetic);
    p.elastic = static_cast<float>(s.stats.elastic);
    p.min_distance = s.stats.min_distance > 1e299 ? 0.0f : static_cast<float>(s.stats.min_distance);
    for (int k = 0; k < static_cast<int>(StepStage::count); ++k) {
      p.step_ms[k] = static_cast<float>(1e3 * s.stats.stage_seconds[k]);
    }
    for (const FigureFrameStats& figure : s.stats.figures) {
      for (const ControlSample& c : figure.controllers) {
        p.control.push_back({static_cast<float>(c.desired), static_cast<float>(c.reference),
                             static_cast<float>(c.actual)});
      }
    }
    studio_.plot.push_back(std::move(p));
    // About ten seconds of frames: the panel's plots cover "the last seconds".
    const double fps = s.scene ? s.scene->solver.fps : 30.0;
    while (static_cast<double>(studio_.plot.size()) > 10.0 * fps) studio_.plot.pop_front();
    studio_.last_plotted_frame = s.frame;
  }
}

Camera Viewport::view_camera() const {
  if (studio_.use_scene_camera && studio_.snapshot && studio_.snapshot->camera) {
    return camera_from_view(*studio_.snapshot->camera);
  }
  return studio_.camera;
}

void Viewport::frame_selection() {
  if (!studio_.snapshot) return;
  draw::Bounds bounds = studio_.snapshot->focus;
  if (studio_.selection.list == "bodies") {
    const draw::Bounds only = pick_bounds(*studio_.snapshot, studio_.selection.index);
    if (!only.empty()) bounds = only;
  }
  studio_.camera = frame_bounds(bounds, static_cast<float>(width()) / std::max(1, height()));
  studio_.use_scene_camera = false;
  update();
}

void Viewport::paintGL() {
  refresh();
  if (!studio_.camera_initialized && studio_.snapshot) {
    const float aspect = static_cast<float>(width()) / std::max(1, height());
    studio_.camera = studio_.snapshot->camera ? camera_from_view(*studio_.snapshot->camera)
                                              : frame_focus(*studio_.snapshot, aspect);
    studio_.camera_initialized = true;
  }
  const qreal ratio = devicePixelRatioF();
  const int w = std::max(1, static_cast<int>(width() * ratio));
  const int h = std::max(1, static_cast<int>(height() * ratio));
  if (studio_.snapshot) {
    RenderOptions options;
    options.width = w;
    options.height = h;
    options.samples = studio_.samples;
    options.overlays = studio_.overlays;
    renderer_->render(*studio_.snapshot, view_camera(), options);
    renderer_->present(defaultFramebufferObject());
  } else {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
    gl_.ClearColor(0.3f, 0.33f, 0.38f, 1);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
  }
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width()), static_cast<float>(height()));
  io.DisplayFramebufferScale = ImVec2(static_cast<float>(ratio), static_cast<float>(ratio));
  io.DeltaTime = std::max(1e-4f, static_cast<float>(clock_.restart()) * 1e-3f);
  ImGui::NewFrame();
  if (studio_.runner) draw_panels(studio_, actions_, io.DisplaySize.x, io.DisplaySize.y);
  ImGui::Render();
  imgui_renderer_->draw(ImGui::GetDrawData(), w, h);
}

bool Viewport::imgui_wants_mouse() const {
  ImGui::SetCurrentContext(imgui_);
  return ImGui::GetIO().WantCaptureMouse;
}

void Viewport::set_mouse(QMouseEvent* event, bool) {
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos =
      ImVec2(static_cast<float>(event->position().x()), static_cast<float>(event->position().y()));
  const Qt::MouseButtons b = event->buttons();
  io.MouseDown[0] = b & Qt::LeftButton;
  io.MouseDown[1] = b & Qt::RightButton;
  io.MouseDown[2] = b & Qt::MiddleButton;
  io.KeyCtrl = event->modifiers() & Qt::ControlModifier;
  io.KeyShift = event->modifiers() & Qt::ShiftModifier;
  io.KeyAlt = event->modifiers() & Qt::AltModifier;
}

void Viewport::mousePressEvent(QMouseEvent* event) {
  set_mouse(event, true);
  update();
  if (imgui_wants_mouse() || !studio_.snapshot || !studio_.runner) return;
  last_ = event->position();
  const bool spring =
      event->button() == Qt::RightButton ||
      (event->button() == Qt::LeftButton && (event->modifiers() & Qt::ControlModifier));
  if (spring) {
    const Camera camera = view_camera();
    const Ray ray = pixel_ray(camera, static_cast<float>(last_.x()), static_cast<float>(last_.y()),
                              width(), height());
    const std::optional<Pick> pick = pick_body(*studio_.snapshot, ray);
    const std::optional<FigurePick> segment = pick_figure(*studio_.snapshot, ray);
    // The nearer of a body and a figure's segment under the cursor takes the spring.
    if (segment && (!pick || segment->distance < pick->distance)) {
      spring_point_ = segment->point;
      studio_.runner->post(FigureSpringBegin{segment->figure, segment->segment,
                                             segment->point.cast<Real>(),
                                             segment->point.cast<Real>()});
      studio_.selection = {"figures", segment->figure};
      drag_ = Drag::spring;
      if (studio_.status.scene) {
        drag_scene_before_ = nlohmann::json::parse(scene_to_json(*studio_.status.scene));
      }
    } else if (pick) {
      spring_point_ = pick->point;
      studio_.runner->post(SpringBegin{pick->body, pick->node, pick->point.cast<Real>()});
      studio_.selection = {"bodies", pick->body};
      drag_ = Drag::spring;
      if (studio_.status.scene) {
        drag_scene_before_ = nlohmann::json::parse(scene_to_json(*studio_.status.scene));
      }
    }
    return;
  }
  if (event->button() == Qt::LeftButton) {
    drag_ = (event->modifiers() & Qt::ShiftModifier) ? Drag::pan : Drag::orbit;
  } else if (event->button() == Qt::MiddleButton) {
    drag_ = Drag::pan;
  }
}

void Viewport::mouseMoveEvent(QMouseEvent* event) {
  set_mouse(event, false);
  update();
  if (drag_ == Drag::none) return;
  const QPointF p = event->position();
  const float dx = static_cast<float>(p.x() - last_.x()),
              dy = static_cast<float>(p.y() - last_.y());
  if (drag_ == Drag::spring) {
    const Camera camera = view_camera();
    const Ray ray =
        pixel_ray(camera, static_cast<float>(p.x()), static_cast<float>(p.y()), width(), height());
    studio_.runner->post(SpringMove{drag_target(camera, ray, spring_point_).cast<Real>()});
    return;
  }
  if (std::abs(dx) + std::abs(dy) < 1) return;
  if (studio_.use_scene_camera) {
    studio_.camera = view_camera();  // navigation starts from what is shown
    studio_.use_scene_camera = false;
  }
  Camera& c = studio_.camera;
  const Vec3f offset = c.position - c.target;
  const Vec3f forward = -offset.normalized();
  const Vec3f right = forward.cross(c.up).normalized();
  if (drag_ == Drag::orbit) {
    // Turntable: about the world up through the target, then about the view's right axis
    // (kept off the poles so the view never flips).
    const Eigen::AngleAxisf yaw(-0.008f * dx, c.up.normalized());
    Vec3f o = yaw * offset;
    const Vec3f r = (yaw * right).normalized();
    const Vec3f pitched = Eigen::AngleAxisf(-0.008f * dy, r) * o;
    if (std::abs(pitched.normalized().dot(c.up.normalized())) < 0.98f) o = pitched;
    c.position = c.target + o;
  } else {
    const Vec3f up = right.cross(forward);
    const float scale = offset.norm() * 2.0f * std::tan(0.5f * c.fov * 3.14159265f / 180.0f) /
                        std::max(1, height());
    const Vec3f shift = (-dx * right + dy * up) * scale;
    c.position += shift;
    c.target += shift;
  }
  last_ = p;
}

void Viewport::mouseReleaseEvent(QMouseEvent* event) {
  set_mouse(event, false);
  update();
  if (drag_ == Drag::spring) {
    studio_.runner->post(SpringEnd{});
    if (!drag_scene_before_.is_null()) {
      studio_.history.push({"", std::move(drag_scene_before_), nullptr, "drag"});
      drag_scene_before_ = nullptr;
    }
  } else if (drag_ == Drag::orbit && (event->position() - last_).manhattanLength() < 3 &&
             studio_.snapshot) {
    // A click without a drag selects the body under the cursor.
    const Ray ray = pixel_ray(view_camera(), static_cast<float>(event->position().x()),
                              static_cast<float>(event->position().y()), width(), height());
    const std::optional<Pick> pick = pick_body(*studio_.snapshot, ray);
    const std::optional<FigurePick> segment = pick_figure(*studio_.snapshot, ray);
    if (segment && (!pick || segment->distance < pick->distance)) {
      studio_.selection = {"figures", segment->figure};
    } else if (pick) {
      studio_.selection = {"bodies", pick->body};
    }
  }
  drag_ = Drag::none;
}

void Viewport::wheelEvent(QWheelEvent* event) {
  ImGui::SetCurrentContext(imgui_);
  ImGui::GetIO().MouseWheel += static_cast<float>(event->angleDelta().y()) / 120.0f;
  update();
  if (imgui_wants_mouse()) return;
  if (studio_.use_scene_camera) {
    studio_.camera = view_camera();
    studio_.use_scene_camera = false;
  }
  Camera& c = studio_.camera;
  const float factor = std::pow(0.9f, static_cast<float>(event->angleDelta().y()) / 120.0f);
  c.position = c.target + (c.position - c.target) * factor;
}

void Viewport::keyPressEvent(QKeyEvent* event) {
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  const int slot = key_slot(event->key());
  if (slot >= 0) io.KeysDown[slot] = true;
  io.KeyCtrl = event->modifiers() & Qt::ControlModifier;
  io.KeyShift = event->modifiers() & Qt::ShiftModifier;
  if (!event->text().isEmpty() && !(event->modifiers() & Qt::ControlModifier)) {
    io.AddInputCharactersUTF8(event->text().toUtf8().constData());
  }
  update();
  if (io.WantCaptureKeyboard || io.WantTextInput) return;
  if (event->key() == Qt::Key_F) frame_selection();
  if (event->key() == Qt::Key_Space && studio_.runner) {
    studio_.runner->post(studio_.status.playing ? Command(Pause{}) : Command(Play{}));
  }
}

void Viewport::keyReleaseEvent(QKeyEvent* event) {
  ImGui::SetCurrentContext(imgui_);
  const int slot = key_slot(event->key());
  if (slot >= 0) ImGui::GetIO().KeysDown[slot] = false;
  update();
}

}  // namespace pbm
