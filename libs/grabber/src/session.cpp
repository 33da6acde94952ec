#include "roadslam/grabber/session.h"

#include <chrono>
#include <filesystem>
#include <thread>

#include "roadslam/common/stop_signal.h"
#include "impl.h"

namespace roadslam::grabber {

GrabStatus runSession(const GrabParams& params, const SessionOptions& opt,
                      const std::function<void(const std::string&)>& print) {
  installStopSignalHandlers();
  Grabber grabber(params, opt.out_dir);
  if (!opt.ini_path.empty())
    std::filesystem::copy_file(opt.ini_path, opt.out_dir + "/grab.ini",
                               std::filesystem::copy_options::overwrite_existing);
  grabber.start();
  const double t0 = wallNow();
  double next_status = t0 + params.writer.status_period_s;
  constexpr auto kTick = std::chrono::milliseconds(20);  // reaction time to a signal
  while (!stopRequested() && (opt.duration_s <= 0 || wallNow() - t0 < opt.duration_s)) {
    std::this_thread::sleep_for(kTick);
    if (wallNow() < next_status) continue;
    next_status += params.writer.status_period_s;
    const GrabStatus st = grabber.status();
    for (const auto& e : st.events) print(e);
    print(Grabber::formatStatus(st));
    grabber.writeSummary(st);
  }
  grabber.stop();
  GrabStatus st = grabber.status();
  for (const auto& e : st.events) print(e);  // e.g. a model warning of a short session
  return st;
}

}  // namespace roadslam::grabber
