#include "roadslam/common/sweep_timing.h"

#include <cmath>
#include <stdexcept>

namespace roadslam {

double SweepTiming::stampFraction() const {
  switch (stamp_reference) {
    case StampReference::Start: return 0.0;
    case StampReference::Middle: return 0.5;
    case StampReference::End: return 1.0;
  }
  return 0.0;
}

double SweepTiming::pointTime(const ScanPoint& p) const {
  const double phi = std::atan2(static_cast<double>(p.y), static_cast<double>(p.x));
  const double cut = cut_azimuth_deg * M_PI / 180.0;
  // clockwise seen from above is decreasing phi
  double a = spin == SpinDirection::Clockwise ? cut - phi : phi - cut;
  a = std::fmod(a, 2 * M_PI);
  if (a < 0) a += 2 * M_PI;
  return a / (2 * M_PI) * period_s;
}

void timesFromAzimuth(Scan& scan, const SweepTiming& timing) {
  for (auto& p : scan.points) p.t = static_cast<float>(timing.pointTime(p));
  scan.stamp_s -= timing.stampFraction() * timing.period_s;
  scan.has_point_times = true;
  scan.times_from_azimuth = true;
}

std::string toString(SpinDirection d) { return d == SpinDirection::Clockwise ? "clockwise" : "counterclockwise"; }

std::string toString(StampReference r) {
  return r == StampReference::Start ? "start" : r == StampReference::Middle ? "middle" : "end";
}

SpinDirection spinDirectionFromString(const std::string& s, const std::string& where) {
  if (s == "clockwise") return SpinDirection::Clockwise;
  if (s == "counterclockwise") return SpinDirection::CounterClockwise;
  throw std::runtime_error(where + " = '" + s + "': expected clockwise or counterclockwise");
}

StampReference stampReferenceFromString(const std::string& s, const std::string& where) {
  if (s == "start") return StampReference::Start;
  if (s == "middle") return StampReference::Middle;
  if (s == "end") return StampReference::End;
  throw std::runtime_error(where + " = '" + s + "': expected start, middle or end");
}

const char* pointTimesName(const Scan& scan) {
  if (!scan.has_point_times) return "none";
  return scan.times_from_azimuth ? "azimuth" : "sensor";
}

}  // namespace roadslam
