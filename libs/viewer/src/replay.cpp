#include "roadslam/viewer/replay.h"

#include <mrpt/obs/CObservation.h>

#include <algorithm>
#include <cmath>

namespace roadslam::viewer {

namespace {
constexpr std::size_t kMaxBackSteps = 200;  // observations searched back for one holding points
}

std::optional<Key> parseKey(const std::string& n) {
  static const std::vector<std::pair<std::string, Key>> names = {
      {"space", Key::Space}, {"left", Key::Left}, {"right", Key::Right}, {"up", Key::Up},
      {"down", Key::Down},   {"home", Key::Home}, {"end", Key::End},     {"+", Key::Plus},
      {"plus", Key::Plus},   {"-", Key::Minus},   {"minus", Key::Minus}, {"c", Key::C},
      {"v", Key::V},         {"h", Key::H},       {"m", Key::M},         {"b", Key::B},
      {"s", Key::S},         {"o", Key::O}};
  for (const auto& [name, key] : names)
    if (name == n) return key;
  return std::nullopt;
}

const std::vector<std::pair<std::string, std::string>>& shortcuts() {
  static const std::vector<std::pair<std::string, std::string>> s = {
      {"space", "play / pause"},
      {"right / left", "next / previous sweep"},
      {"up / down", "1 s forward / back"},
      {"Home / End", "first / last observation"},
      {"+ / -", "speed x2 / x0.5 (0.1x-10x)"},
      {"c", "colour: height, intensity, ring, time"},
      {"v", "camera: follow, top-down, orbit"},
      {"m / b / s / o", "map / boundaries / sweep / objects on-off"},
      {"h", "this help"}};
  return s;
}

Replay::Replay(ViewerModel& model)
    : model_(model), t_s_(model.live() ? model.endTime() : model.startTime()), playing_(model.live() != nullptr) {}
Replay::~Replay() = default;

void Replay::seek(double t_s) {
  t_s_ = std::clamp(t_s, model_.startTime(), model_.endTime());
  if (model_.live()) playing_ = false;  // looking back: the live edge moves on without the picture
}

void Replay::jumpToObservation(std::size_t i) {
  if (i >= model_.recording().size()) return;
  const double t = model_.recording().entry(i).stamp_s;
  if (std::isfinite(t)) seek(t);
}

bool Replay::holdsPoints(std::size_t i) const {
  const auto& idx = model_.recording();
  return idx.entry(i).known && holdsSweep(idx.className(i));
}

std::optional<std::size_t> Replay::currentObservation() const {
  const auto at = model_.recording().findAtTime(t_s_);
  if (!at) return std::nullopt;
  for (std::size_t k = 0, i = *at; k < kMaxBackSteps; ++k, --i) {
    if (holdsPoints(i)) return i;
    if (i == 0) break;
  }
  return at;
}

void Replay::stepSweep(int direction) {
  const auto& idx = model_.recording();
  const auto cur = currentObservation();
  if (!cur) return;
  for (long i = long(*cur) + direction; i >= 0 && i < long(idx.size()); i += direction)
    if (holdsPoints(std::size_t(i)) && std::isfinite(idx.entry(std::size_t(i)).stamp_s)) {
      seek(idx.entry(std::size_t(i)).stamp_s);
      return;
    }
}

void Replay::setSpeed(double s) { speed_ = std::clamp(s, kMinSpeed, kMaxSpeed); }
void Replay::changeSpeed(int direction) { setSpeed(direction > 0 ? speed_ * 2 : speed_ / 2); }

void Replay::advance(double wall_s) {
  if (!playing_) return;
  if (model_.live()) {
    t_s_ = model_.endTime();  // the live edge
    return;
  }
  seek(t_s_ + wall_s * speed_);
  if (t_s_ >= model_.endTime()) playing_ = false;
}

bool Replay::handleKey(Key key) {
  if (model_.live() && key == Key::End) {
    playing_ = true;
    t_s_ = model_.endTime();
    return true;
  }
  switch (key) {
    case Key::Space: playing_ = !playing_; return true;
    case Key::Right: stepSweep(+1); return true;
    case Key::Left: stepSweep(-1); return true;
    case Key::Up: seek(t_s_ + 1.0); return true;
    case Key::Down: seek(t_s_ - 1.0); return true;
    case Key::Home: seek(model_.startTime()); return true;
    case Key::End: seek(model_.endTime()); return true;
    case Key::Plus: changeSpeed(+1); return true;
    case Key::Minus: changeSpeed(-1); return true;
    case Key::C: options_.color_by = ColorBy((int(options_.color_by) + 1) % 4); return true;
    case Key::V: options_.camera = CameraMode((int(options_.camera) + 1) % 3); return true;
    case Key::M: options_.show_map = !options_.show_map; return true;
    case Key::B: options_.show_boundaries = !options_.show_boundaries; return true;
    case Key::S: options_.show_sweep = !options_.show_sweep; return true;
    case Key::O: options_.show_objects = !options_.show_objects; return true;
    case Key::H: help_ = !help_; return true;
  }
  return false;
}

void Replay::loadIfNeeded(std::size_t i) {
  if (loaded_index_ == i) return;
  loaded_index_ = i;
  loaded_.reset();
  loaded_sweep_.reset();
  error_.clear();
  try {
    loaded_ = model_.recording().load(i);
    if (loaded_) loaded_sweep_ = sweepOf(*loaded_);
  } catch (const std::exception& e) {
    error_ = e.what();
  }
}

std::shared_ptr<mrpt::obs::CObservation> Replay::observation(std::size_t i) {
  loadIfNeeded(i);
  return loaded_;
}

const SweepPoints* Replay::currentSweep() {
  const auto i = currentObservation();
  if (!i) return nullptr;
  loadIfNeeded(*i);
  return loaded_sweep_ ? &*loaded_sweep_ : nullptr;
}

std::string Replay::details(std::size_t i) {
  const auto& idx = model_.recording();
  if (i >= idx.size()) return {};
  if (!idx.entry(i).known) return "class " + idx.className(i) + ": unknown to this build, skipped";
  loadIfNeeded(i);
  if (!loaded_) return error_.empty() ? "not an observation (" + idx.className(i) + ")" : error_;
  return describe(*loaded_, loaded_sweep_ ? &*loaded_sweep_ : nullptr);
}

SceneState Replay::state() {
  SceneState s;
  s.t_s = t_s_;
  s.sweep = currentSweep();
  s.observation = currentObservation();
  return s;
}

}  // namespace roadslam::viewer
