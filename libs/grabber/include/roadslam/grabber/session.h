#pragma once
/// \file session.h
/// A whole recording session as `roadslam-grab` runs it: copies the ini into the session folder,
/// starts a Grabber, prints a status line (and refreshes summary.json) every status period, reports
/// watchdog events, stops on SIGINT/SIGTERM (roadslam/common/stop_signal.h) or after a duration,
/// then drains, closes and writes the final summary.json.

#include <functional>
#include <string>

#include "roadslam/grabber/grabber.h"

namespace roadslam::grabber {

struct SessionOptions {
  std::string ini_path;    ///< copied to <out_dir>/grab.ini (the ini as given)
  std::string out_dir;     ///< session folder (created)
  double duration_s = 0;   ///< stop after this long [s]; 0 = until a stop signal
};

/// Runs the session; \p print receives status lines and events. Throws at the configuration /
/// file boundary (ports, folder, CAN interface); per-packet problems are counted in the status.
GrabStatus runSession(const GrabParams& params, const SessionOptions& opt,
                      const std::function<void(const std::string&)>& print);

}  // namespace roadslam::grabber
