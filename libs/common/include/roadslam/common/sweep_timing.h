#pragma once
/// \file sweep_timing.h
/// Per-point times for sweeps whose format stores none (KITTI .bin), from each point's azimuth.
/// A spinning LiDAR fires at a constant rate, so a point's time within the sweep is its angle from
/// the sweep's cut, in the direction of rotation, over 2 pi (KISS-ICP GetTimestamps, Vizzo et al.
/// 2023, for KITTI). What the format leaves open is a property of the source: the spin direction,
/// the azimuth where sweeps are cut, and which moment of the sweep the file's stamp names.
/// Azimuth phi = atan2(y, x) in the lidar frame (x forward, y left, z up).

#include <string>

#include "roadslam/common/param_table.h"
#include "roadslam/common/scan.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {

/// Seen from above (z up). Velodyne sensors turn clockwise (VLP-16 manual 9.3).
enum class SpinDirection { Clockwise, CounterClockwise };

/// The moment of the sweep a source's stamp refers to. KITTI raw: the moment the sensor faces
/// forward, which with the cut behind the car is the middle (KITTI raw data readme: the cameras are
/// triggered "when the Velodyne lasers face forward").
enum class StampReference { Start, Middle, End };

struct SweepTiming {
  double period_s = 0.1;                             ///< one revolution [s]
  SpinDirection spin = SpinDirection::Clockwise;
  double cut_azimuth_deg = 180;                      ///< azimuth where a sweep starts and ends [deg]
  StampReference stamp_reference = StampReference::Start;

  /// Fraction of the sweep at which the source's stamp lies: 0, 0.5 or 1.
  double stampFraction() const;
  /// Time of \p p after the first firing [s], in [0, period_s).
  double pointTime(const ScanPoint& p) const;
};

/// Fills ScanPoint::t from the azimuth, sets has_point_times and times_from_azimuth, and moves
/// scan.stamp_s from the source's reference to the first firing (Scan::stamp_s's meaning).
void timesFromAzimuth(Scan& scan, const SweepTiming& timing);

/// "clockwise" / "counterclockwise", "start" / "middle" / "end" (one name table each, for
/// ParamTable::choice); parse errors name the key.
const NameTable<SpinDirection>& spinDirectionNames();
const NameTable<StampReference>& stampReferenceNames();
std::string toString(SpinDirection d);
std::string toString(StampReference r);
SpinDirection spinDirectionFromString(const std::string& s, const std::string& where);
StampReference stampReferenceFromString(const std::string& s, const std::string& where);

/// How a sweep was timed, for reports: "sensor", "azimuth" or "none".
const char* pointTimesName(const Scan& scan);

}  // namespace roadslam
