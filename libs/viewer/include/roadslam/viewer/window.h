#pragma once
/// \file window.h
/// The replay window: mrpt::gui::CDisplayWindowGUI (nanogui widgets over an MRPT OpenGL scene) with
/// a timeline (play/pause, step, speed, a time slider, jump to an observation), the observation list
/// (index, time, sensor label, type, size) with a details panel, keyboard shortcuts with a help
/// overlay, and a command script for tests and demos:
///   key NAME          a shortcut (names as replay.h parseKey: space, right, +, c, ...)
///   wait SECONDS      let the window run (and play) for that long
///   select INDEX      select an observation in the list (shows its details, jumps to it)
///   screenshot PATH   write the window's pixels (the whole window, widgets included) to a PNG
///   quit              close the window
/// Lines starting with '#' and empty lines are ignored.

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace roadslam::viewer {

class Replay;

struct WindowOptions {
  int width_px = 1280, height_px = 720;
  std::string script;  ///< command file; empty: interactive
  /// Live view: a status line (the grabber's counters) shown under the timeline, once a second.
  std::function<std::string()> status;
};

struct ScriptCommand {
  std::string verb;  ///< key, wait, select, screenshot, quit
  std::string arg;
  int line = 0;
};
/// Parses a command script; throws std::runtime_error naming file:line on an unknown command.
std::vector<ScriptCommand> readScript(const std::string& path);

/// Throws std::runtime_error when the window cannot run: a bad script (naming file:line) or no
/// display. Called before anything is opened, so such a run fails at once.
void checkWindowRequest(const WindowOptions& options);

/// Opens the window and runs until it is closed (or the script quits); returns the exit code.
int runWindow(Replay& replay, const WindowOptions& options, std::ostream& out, std::ostream& err);

}  // namespace roadslam::viewer
