#include "roadslam/common/stop_signal.h"

#include <csignal>

namespace roadslam {
namespace {
volatile std::sig_atomic_t g_stop = 0;

extern "C" void onStopSignal(int sig) {
  g_stop = 1;
  std::signal(sig, SIG_DFL);  // a second Ctrl-C ends the process at once
}
}  // namespace

void installStopSignalHandlers() {
  std::signal(SIGINT, onStopSignal);
  std::signal(SIGTERM, onStopSignal);
}
bool stopRequested() { return g_stop != 0; }
void requestStop() { g_stop = 1; }
void clearStopRequest() { g_stop = 0; }

}  // namespace roadslam
