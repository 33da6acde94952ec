#pragma once
/// \file live_gnss.h
/// The online GNSS correction on a live feed: CObservationGPS records as they arrive
/// (roadslam-grab's receiver epochs, a car's CAN_GPS) and the odometry's frames, in one
/// gnss_fusion::OnlineGnssFusion. The ENU frame is at the first valid fix (as jobs/gnss_outputs.h).
/// Fixes are stamped with their receive time: the frames of a live feed carry the host's receive
/// time, and the receiver's UTC is another clock (a replayed log's is the recording's day).
/// One GPS source is fused, never a mix of receivers (their antennas, clocks and errors differ; as
/// roadslam-map --gnss-label): the one named by GnssFusionParams::live_source_label, else the first
/// whose record has a valid fix. The others' records are counted and left out.
/// Thread-safe: fixes are posted from the feed's thread, frames corrected on the odometry's.

#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/gnss/geo.h"
#include "roadslam/gnss_fusion/gnss_fusion_online.h"
#include "roadslam/sources/gps_fix.h"

namespace roadslam::pipeline {

/// A recording's fix (a CObservationGPS record, a position packet's RMC) as a fusion factor at \p t_s
/// in \p enu: a GGA's HDOP x uere gives its covariance (gnss::GnssFix::covarianceEnu); without HDOP
/// (an RMC alone carries no height), fallback_sigma_m horizontally and the height free (sigma 1 km).
/// The one rule of the live correction and of the whole-drive fusion of a recording's fixes.
gnss_fusion::GnssFactor recordedFixFactor(const gnss::GnssFix& f, double t_s, const gnss::EnuFrame& enu,
                                          const gnss_fusion::GnssFusionParams& p);

struct LiveGnssCounts {
  /// Records of the source fused, and those without a valid fix [count]; until a source has a fix,
  /// every record posted (none has a fix).
  std::size_t epochs = 0, no_fix = 0;
  std::size_t fixes = 0;               ///< valid fixes handed to the online mode [count]
  std::size_t solves = 0, failed = 0, rejected = 0;  ///< gnss_fusion::GnssOnlineStats [count]
  bool anchored = false;
  std::string source;          ///< the label of the source fused (empty until one gives a fix)
  bool source_chosen = false;  ///< named by live_source_label (else the first source with a fix)
  std::size_t other_sources = 0;  ///< records of other sources, left out (also their no-fix ones before the choice) [count]
};

class LiveGnss {
 public:
  explicit LiveGnss(const gnss_fusion::GnssFusionParams& p);
  /// A fix as it arrived (any thread); one of another source than the one fused is only counted.
  void post(const gnss::GnssFix& f);
  /// The frame at \p t_s with the odometry's pose; its T_enu_lidar once the online mode anchored.
  /// The fixes posted with a stamp up to \p t_s are added first (causal).
  std::optional<Eigen::Isometry3d> correct(double t_s, const Eigen::Isometry3d& T_map_lidar);
  LiveGnssCounts counts() const;
  /// "GNSS from LABEL (live_source_label | first seen; K records of other sources left out): N fixes (M no fix), S solves (F failed),
  /// R rejected, corrected | waiting for fixes" for a status line.
  std::string statusLine() const;
  /// The ENU origin (the first valid fix), when one arrived.
  std::optional<gnss::Geodetic> origin() const;

 private:
  mutable std::mutex m_;
  std::vector<gnss::GnssFix> pending_;
  std::optional<gnss::EnuFrame> enu_;
  std::optional<gnss::Geodetic> origin_;
  gnss_fusion::OnlineGnssFusion online_;
  gnss_fusion::GnssFusionParams p_;
  LiveGnssCounts counts_;
  bool has_source_ = false;  ///< the source is set (chosen, or the first with a fix)
  std::map<std::string, std::size_t> no_fix_before_source_;  ///< per label, until a source is set [count]
  void chooseSource(const std::string& label);
};

}  // namespace roadslam::pipeline
