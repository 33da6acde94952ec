#pragma once
/// \file replay.h
/// The replay state shared by the window, the command script and the headless renders: the current
/// time, play/pause, speed (0.1x-10x), stepping sweep by sweep, jumps, the colour and camera modes,
/// and the keyboard shortcuts as named keys (so a script and a test drive exactly what a user does).
/// The observation at the current time is loaded lazily through the rawlog index.
///
/// A live view (ViewerModel::live()) plays by following the newest observation: pausing freezes
/// the picture (the data keep arriving behind it), playing or End goes back to the live edge, and
/// a seek or a step pauses.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/viewer/model.h"
#include "roadslam/viewer/scene.h"
#include "roadslam/viewer/sweep.h"

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::viewer {

/// Shortcut keys, independent of the GUI toolkit.
enum class Key { Space, Left, Right, Up, Down, Home, End, Plus, Minus, C, V, H, M, B, S, O };
/// "space", "left", "right", "up", "down", "home", "end", "+"/"plus", "-"/"minus", "c", "v", "h",
/// "m", "b", "s", "o"; nullopt for any other name.
std::optional<Key> parseKey(const std::string& name);
/// The help overlay: one line per shortcut.
const std::vector<std::pair<std::string, std::string>>& shortcuts();

class Replay {
 public:
  static constexpr double kMinSpeed = 0.1, kMaxSpeed = 10.0;
  explicit Replay(ViewerModel& model);
  ~Replay();

  ViewerModel& model() { return model_; }
  double time() const { return t_s_; }
  bool playing() const { return playing_; }
  double speed() const { return speed_; }
  bool helpShown() const { return help_; }
  SceneOptions& options() { return options_; }

  /// Moves to \p t_s (clamped to the recording).
  void seek(double t_s);
  /// Moves to observation \p i of the rawlog (its time).
  void jumpToObservation(std::size_t i);
  /// To the next (+1) or previous (-1) observation holding points.
  void stepSweep(int direction);
  void setPlaying(bool on) { playing_ = on; }
  /// Doubles (+1) or halves (-1) the speed within [0.1, 10].
  void changeSpeed(int direction);
  void setSpeed(double s);
  /// Advances the time by \p wall_s of wall time times the speed when playing; stops at the end.
  /// Live: when playing, moves to the newest observation.
  void advance(double wall_s);
  /// Applies a shortcut; returns false for a key without an action.
  bool handleKey(Key key);

  /// The observation shown now: the last one holding points at or before the time (else the
  /// observation at the time).
  std::optional<std::size_t> currentObservation() const;
  /// Its points (loaded on first use, cached), nullptr when it has none or cannot be read.
  const SweepPoints* currentSweep();
  /// The observation itself (loaded, cached) and the text of the details panel.
  std::shared_ptr<mrpt::obs::CObservation> observation(std::size_t i);
  std::string details(std::size_t i);
  /// A read error of the last load (empty when none).
  const std::string& lastError() const { return error_; }

  SceneState state();

 private:
  void loadIfNeeded(std::size_t i);
  bool holdsPoints(std::size_t i) const;

  ViewerModel& model_;
  SceneOptions options_;
  double t_s_ = 0, speed_ = 1.0;
  bool playing_ = false, help_ = false;
  std::optional<std::size_t> loaded_index_;
  std::shared_ptr<mrpt::obs::CObservation> loaded_;
  std::optional<SweepPoints> loaded_sweep_;
  std::string error_;
};

}  // namespace roadslam::viewer
