#pragma once
/// \file stop_signal.h
/// SIGINT / SIGTERM turn into a flag that long-running loops poll, so they stop between frames and
/// write a consistent result of what they processed (the second signal keeps the default action).

namespace roadslam {

/// Installs the handlers for SIGINT and SIGTERM (idempotent).
void installStopSignalHandlers();
/// True once a stop signal arrived (or requestStop() was called).
bool stopRequested();
void requestStop();
void clearStopRequest();

}  // namespace roadslam
