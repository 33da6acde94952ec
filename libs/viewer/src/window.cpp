#include "roadslam/viewer/window.h"

#include <mrpt/gui/CDisplayWindowGUI.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CObservation.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/viewer/replay.h"

namespace roadslam::viewer {

namespace {
constexpr int kListRows = 16;        // rows of the observation list shown around the current one
constexpr int kIdlePeriod_ms = 20;   // the GUI loop's idle period (playback tick)
constexpr int kFramesBeforeShot = 3; // ticks after the script's last key/select before a screenshot

std::optional<Key> keyOf(int glfw_key) {
  switch (glfw_key) {
    case GLFW_KEY_SPACE: return Key::Space;
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_RIGHT: return Key::Right;
    case GLFW_KEY_UP: return Key::Up;
    case GLFW_KEY_DOWN: return Key::Down;
    case GLFW_KEY_HOME: return Key::Home;
    case GLFW_KEY_END: return Key::End;
    case GLFW_KEY_KP_ADD: case GLFW_KEY_EQUAL: return Key::Plus;
    case GLFW_KEY_KP_SUBTRACT: case GLFW_KEY_MINUS: return Key::Minus;
    case GLFW_KEY_C: return Key::C;
    case GLFW_KEY_V: return Key::V;
    case GLFW_KEY_H: return Key::H;
    case GLFW_KEY_M: return Key::M;
    case GLFW_KEY_B: return Key::B;
    case GLFW_KEY_S: return Key::S;
    case GLFW_KEY_O: return Key::O;
    default: return std::nullopt;
  }
}

std::string rowText(const rawlog::ObservationIndex& idx, std::size_t i, double t0) {
  char buf[160];
  const auto& e = idx.entry(i);
  std::snprintf(buf, sizeof buf, "%6zu  %9.3f s  %-10s %-26s %7.1f kB", i, e.stamp_s - t0, idx.label(i).c_str(),
                idx.className(i).c_str(), e.size / 1e3);
  return buf;
}

// The framebuffer's pixels (the whole window: scene and widgets) as a PNG.
void writeFramebuffer(GLFWwindow* glfw, const std::string& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(glfw, &w, &h);
  std::vector<uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  mrpt::img::CImage img(w, h, mrpt::img::CH_RGB);
  for (int y = 0; y < h; ++y)  // OpenGL rows go bottom-up
    for (int x = 0; x < w; ++x) {
      const uint8_t* src = &rgb[(std::size_t(h - 1 - y) * std::size_t(w) + std::size_t(x)) * 3];
      auto* d = img.ptr<uint8_t>(x, y);  // BGR
      d[0] = src[2], d[1] = src[1], d[2] = src[0];
    }
  const std::string tmp = tempPathFor(path) + ".png";
  if (!img.saveToFile(tmp)) throw std::runtime_error("cannot write screenshot '" + path + "'");
  commitTempFile(tmp, path);
}

// CDisplayWindowGUI whose frame can be captured: nanogui::Screen::drawAll (clear, scene, widgets,
// swap) with the back buffer read between the widgets and the swap.
class CapturingWindow : public mrpt::gui::CDisplayWindowGUI {
 public:
  using CDisplayWindowGUI::CDisplayWindowGUI;
  /// Captures the next frame drawn into \p path.
  void requestShot(const std::string& path) { shot_path_ = path; shot_error_.clear(); }
  bool shotPending() const { return !shot_path_.empty(); }
  const std::string& shotError() const { return shot_error_; }

  void drawAll() override {
    glfwMakeContextCurrent(glfwWindow());
    glClearColor(mBackground[0], mBackground[1], mBackground[2], mBackground[3]);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    drawContents();
    drawWidgets();
    if (!shot_path_.empty()) {
      try {
        writeFramebuffer(glfwWindow(), shot_path_);
      } catch (const std::exception& e) {
        shot_error_ = e.what();
      }
      shot_path_.clear();
    }
    glfwSwapBuffers(glfwWindow());
  }

 private:
  std::string shot_path_, shot_error_;
};

class ViewerWindow {
 public:
  ViewerWindow(Replay& replay, const WindowOptions& opt, std::ostream& out, std::ostream& err)
      : replay_(replay), out_(out), err_(err), status_fn_(opt.status), warned_(replay.model().warnings().size()) {
    if (!opt.script.empty()) script_ = readScript(opt.script);
    win_ = std::make_shared<CapturingWindow>("roadslam-view: " + replay.model().inputs().name(),
                                             unsigned(opt.width_px), unsigned(opt.height_px));
    {
      std::lock_guard<std::mutex> lck(win_->background_scene_mtx);
      win_->background_scene = mrpt::opengl::COpenGLScene::Create();
    }
    buildTimeline(opt.height_px);
    buildList(opt.width_px);
    buildHelp();
    win_->setKeyboardCallback([this](int key, int, int action, int) {
      if (action != GLFW_PRESS && action != GLFW_REPEAT) return false;
      const auto k = keyOf(key);
      if (!k) return false;
      replay_.handleKey(*k);
      return true;
    });
    win_->setLoopCallback([this]() { tick(); });
    win_->performLayout();
    refresh(true);
    win_->drawAll();
    win_->setVisible(true);
  }

  int exitCode() const { return exit_code_; }

 private:
  void buildTimeline(int height_px) {
    auto* w = new nanogui::Window(win_.get(), "Timeline");
    w->setPosition({10, std::max(40, height_px - 185)});  // bottom left: the scene's HUD line stays visible
    w->setLayout(new nanogui::GroupLayout(6, 4));
    auto* row = w->add<nanogui::Widget>();
    row->setLayout(new nanogui::BoxLayout(nanogui::Orientation::Horizontal, nanogui::Alignment::Middle, 0, 4));
    const auto button = [&](const char* caption, Key key) {
      row->add<nanogui::Button>(caption)->setCallback([this, key] { replay_.handleKey(key); });
    };
    button("|<", Key::Home);
    button("<", Key::Left);
    play_ = row->add<nanogui::Button>("play");
    play_->setCallback([this] { replay_.handleKey(Key::Space); });
    button(">", Key::Right);
    button(">|", Key::End);
    button("-", Key::Minus);
    speed_ = row->add<nanogui::Label>("1.0x");
    speed_->setFixedWidth(44);
    button("+", Key::Plus);
    button("?", Key::H);
    slider_ = w->add<nanogui::Slider>();
    slider_->setFixedWidth(420);
    slider_->setCallback([this](float v) {
      const auto& m = replay_.model();
      replay_.seek(m.startTime() + double(v) * (m.endTime() - m.startTime()));
    });
    time_ = w->add<nanogui::Label>("");
    if (status_fn_) {
      status_ = w->add<nanogui::Label>("live: waiting for the first status");
      status_->setFixedWidth(420);
    }
    auto* jump = w->add<nanogui::Widget>();
    jump->setLayout(new nanogui::BoxLayout(nanogui::Orientation::Horizontal, nanogui::Alignment::Middle, 0, 4));
    jump->add<nanogui::Label>("jump to obs");
    auto* obs = jump->add<nanogui::IntBox<int>>(0);
    obs->setEditable(true);
    obs->setFixedWidth(80);
    obs->setCallback([this](int i) { if (i >= 0) replay_.jumpToObservation(std::size_t(i)); });
    jump->add<nanogui::Label>("or time [s]");
    auto* t = jump->add<nanogui::FloatBox<float>>(0.f);
    t->setEditable(true);
    t->setFixedWidth(80);
    t->setCallback([this](float s) { replay_.seek(replay_.model().startTime() + double(s)); });
  }

  std::string listHeader() const {
    const auto& m = replay_.model();
    const bool damaged = m.rawlog() && !m.rawlog()->complete();
    std::string state = damaged ? " (damaged: see stderr)" : m.live() ? " (live)" : "";
    if (m.indexing()) state = " (indexing: " + std::to_string(int(100 * m.indexProgress())) + " %)";
    return std::to_string(m.recording().size()) + " observations, " + std::to_string(m.recording().labels().size()) +
           " sensor labels" + state;
  }

  void buildList(int width_px) {
    auto* w = new nanogui::Window(win_.get(), "Observations");
    w->setPosition({std::max(10, width_px - 470), 40});
    w->setLayout(new nanogui::GroupLayout(6, 2));
    list_header_ = w->add<nanogui::Label>(listHeader());
    w->add<nanogui::Label>("   index  time        label      type                          size");
    for (int r = 0; r < kListRows; ++r) {
      auto* b = w->add<nanogui::Button>("");
      b->setFontSize(14);
      b->setFixedWidth(450);
      b->setFlags(nanogui::Button::ToggleButton);
      b->setCallback([this, r] {
        if (r < int(rows_index_.size())) select(rows_index_[std::size_t(r)]);
      });
      rows_.push_back(b);
    }
    details_ = w->add<nanogui::Label>("");
    details_->setFixedWidth(450);
    details_->setFontSize(14);
  }

  void buildHelp() {
    help_ = new nanogui::Window(win_.get(), "Shortcuts (h)");
    help_->setLayout(new nanogui::GridLayout(nanogui::Orientation::Horizontal, 2, nanogui::Alignment::Minimum, 8, 4));
    for (const auto& [keys, what] : shortcuts()) {
      help_->add<nanogui::Label>(keys)->setFontSize(18);
      help_->add<nanogui::Label>(what)->setFontSize(18);
    }
    help_->setPosition({10, 40});
    help_->setVisible(false);
  }

  // A selected observation keeps its details until the time moves (the scene shows the sweep at
  // its time; a GPS record selected shows its own details).
  void select(std::size_t i) {
    replay_.jumpToObservation(i);
    pinned_ = i;
    pinned_time_ = replay_.time();
    selected_ = i;
    details_->setCaption(replay_.details(i));
    dirty_ = true;
  }

  // Rebuilds the scene and the widgets when what they show changed.
  // Updates the widgets; rebuilds the scene and the list only when what they show changed (the
  // observation shown, the frames so far, the options), not on every tick of playback.
  void refresh(bool force) {
    const auto cur = replay_.currentObservation();
    const auto& o = replay_.options();
    const auto& m = replay_.model();
    help_->setVisible(replay_.helpShown());
    play_->setCaption(replay_.playing() ? "pause" : "play");
    char text[160];
    std::snprintf(text, sizeof text, "%.1fx", replay_.speed());
    speed_->setCaption(text);
    const double span = std::max(1e-9, m.endTime() - m.startTime());
    slider_->setValue(float((replay_.time() - m.startTime()) / span));
    std::snprintf(text, sizeof text, "t %.2f / %.2f s   observation %s / %zu", replay_.time() - m.startTime(), span,
                  cur ? std::to_string(*cur).c_str() : "-", m.recording().size());
    time_->setCaption(text);
    if (pinned_ && replay_.time() != pinned_time_) pinned_.reset();
    const std::string key = std::to_string(cur.value_or(SIZE_MAX)) + "|" + std::to_string(pinned_.value_or(SIZE_MAX)) +
                            "|" + std::to_string(m.framesUpTo(replay_.time() + 0.06)) + "|" + toString(o.color_by) +
                            toString(o.camera) + std::to_string(o.show_map) + std::to_string(o.show_boundaries) +
                            std::to_string(o.show_sweep) + std::to_string(o.show_objects);
    if (!force && key == last_key_ && !dirty_) return;
    last_key_ = key;
    dirty_ = false;
    // the list: a page of rows around the current observation
    const std::size_t n = m.recording().size(), c = pinned_.value_or(cur.value_or(0));
    const std::size_t first = c > kListRows / 2 ? std::min(c - kListRows / 2, n > kListRows ? n - kListRows : 0) : 0;
    rows_index_.clear();
    if (m.live() || list_header_->caption() != listHeader()) list_header_->setCaption(listHeader());
    for (int r = 0; r < kListRows; ++r) {
      const std::size_t i = first + std::size_t(r);
      rows_[std::size_t(r)]->setVisible(i < n);
      if (i >= n) continue;
      rows_index_.push_back(i);
      rows_[std::size_t(r)]->setCaption(rowText(m.recording(), i, m.startTime()));
      rows_[std::size_t(r)]->setPushed(i == c);
    }
    if (!pinned_ && cur && (!selected_ || *selected_ != *cur)) {
      selected_ = cur;
      details_->setCaption(replay_.details(*cur));
    }
    // the scene
    CameraView view;
    {
      std::lock_guard<std::mutex> lck(win_->background_scene_mtx);
      view = buildScene(m, replay_.state(), o, *win_->background_scene);
    }
    auto& cam = win_->camera();
    cam.setCameraPointing(float(view.target.x()), float(view.target.y()), float(view.target.z()));
    if (o.camera != CameraMode::Orbit || force) {  // orbit: the user's mouse owns the angles
      cam.setAzimuthDegrees(float(view.azimuth_deg));
      cam.setElevationDegrees(float(view.elevation_deg));
      cam.setZoomDistance(float(view.distance_m));
    }
    win_->performLayout();
  }

  void tick() {
    const auto now = std::chrono::steady_clock::now();
    const double dt = last_tick_ ? std::chrono::duration<double>(now - *last_tick_).count() : 0.0;
    last_tick_ = now;
    if (replay_.model().poll() > 0) dirty_ = true;  // live, or indexed in the background, since
    for (const auto& w = replay_.model().warnings(); warned_ < w.size(); ++warned_)
      err_ << "roadslam-view: warning: " << w[warned_] << "\n";  // found once the index is done
    if (status_fn_ && (!last_status_ || now - *last_status_ > std::chrono::seconds(1))) {
      last_status_ = now;
      status_->setCaption(status_fn_());
    }
    replay_.advance(dt);
    if (replay_.model().takePosted() > 0) dirty_ = true;  // results streamed in by another thread
    refresh(false);
    ++frames_since_change_;
    runScript(now);
  }

  void runScript(std::chrono::steady_clock::time_point now) {
    while (next_ < script_.size()) {
      if (now < wait_until_) return;
      const ScriptCommand& c = script_[next_];
      if (c.verb == "wait") {
        wait_until_ = now + std::chrono::microseconds(int64_t(std::stod(c.arg) * 1e6));
        ++next_;
        return;
      }
      if (c.verb == "screenshot") {
        if (frames_since_change_ < kFramesBeforeShot) return;  // let the change reach the screen
        if (!shot_requested_) {
          win_->requestShot(c.arg);
          shot_requested_ = true;
          return;
        }
        if (win_->shotPending()) return;  // the next frame takes it
        shot_requested_ = false;
        if (win_->shotError().empty()) {
          const auto cur = replay_.currentObservation();
          char at[96];
          std::snprintf(at, sizeof at, " t=%.3f obs=%s", replay_.time() - replay_.model().startTime(),
                        cur ? std::to_string(*cur).c_str() : "-");
          out_ << "screenshot " << c.arg << at << "\n";
        } else {
          err_ << "roadslam-view: " << win_->shotError() << "\n";
          exit_code_ = 1;
        }
      } else if (c.verb == "key") {
        replay_.handleKey(*parseKey(c.arg));
        refresh(false);
        frames_since_change_ = 0;
      } else if (c.verb == "select") {
        select(std::stoul(c.arg));
        refresh(true);
        frames_since_change_ = 0;
      } else if (c.verb == "quit") {
        win_->setVisible(false);
        nanogui::leave();
        ++next_;
        return;
      }
      ++next_;
    }
  }

  Replay& replay_;
  std::ostream& out_;
  std::ostream& err_;
  std::shared_ptr<CapturingWindow> win_;
  bool shot_requested_ = false;
  nanogui::Button* play_ = nullptr;
  nanogui::Label *speed_ = nullptr, *time_ = nullptr, *details_ = nullptr;
  nanogui::Slider* slider_ = nullptr;
  nanogui::Window* help_ = nullptr;
  std::vector<nanogui::Button*> rows_;
  std::vector<std::size_t> rows_index_;
  std::optional<std::size_t> selected_, pinned_;
  double pinned_time_ = 0;
  std::string last_key_;
  bool dirty_ = false;
  int frames_since_change_ = 0;
  std::optional<std::chrono::steady_clock::time_point> last_tick_, last_status_;
  std::function<std::string()> status_fn_;
  nanogui::Label* status_ = nullptr;
  nanogui::Label* list_header_ = nullptr;
  std::size_t warned_;  // model warnings printed so far
  std::vector<ScriptCommand> script_;
  std::size_t next_ = 0;
  std::chrono::steady_clock::time_point wait_until_{};
  int exit_code_ = 0;
};
}  // namespace

void checkWindowRequest(const WindowOptions& options) {
  if (!options.script.empty()) readScript(options.script);
  const char* display = std::getenv("DISPLAY");
  if ((!display || !*display) && !std::getenv("WAYLAND_DISPLAY"))
    throw std::runtime_error("no display ($DISPLAY is not set): run it on a desktop, under xvfb-run, or render "
                             "headless with --render OUT.png --at T");
}

int runWindow(Replay& replay, const WindowOptions& options, std::ostream& out, std::ostream& err) {
  checkWindowRequest(options);
  nanogui::init();
  int code = 0;
  {
    ViewerWindow window(replay, options, out, err);
    nanogui::mainloop(kIdlePeriod_ms, kIdlePeriod_ms);
    code = window.exitCode();
  }
  nanogui::shutdown();
  return code;
}

}  // namespace roadslam::viewer
