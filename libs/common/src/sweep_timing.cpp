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

const NameTable<SpinDirection>& spinDirectionNames() {
  static const NameTable<SpinDirection> t{{SpinDirection::Clockwise, "clockwise"},
                                          {SpinDirection::CounterClockwise, "counterclockwise"}};
  return t;
}

const NameTable<StampReference>& stampReferenceNames() {
  static const NameTable<StampReference> t{
      {StampReference::Start, "start"}, {StampReference::Middle, "middle"}, {StampReference::End, "end"}};
  return t;
}

std::string toString(SpinDirection d) { return nameOf(spinDirectionNames(), d); }
std::string toString(StampReference r) { return nameOf(stampReferenceNames(), r); }

SpinDirection spinDirectionFromString(const std::string& s, const std::string& where) {
  try {
    return valueOf(spinDirectionNames(), s, where);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

StampReference stampReferenceFromString(const std::string& s, const std::string& where) {
  try {
    return valueOf(stampReferenceNames(), s, where);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

const char* pointTimesName(const Scan& scan) {
  if (!scan.has_point_times) return "none";
  return scan.times_from_azimuth ? "azimuth" : "sensor";
}

}  // namespace roadslam
