#pragma once
/// \file observation_index.h
/// Random access, by position and by time, to a sequence of MRPT observations: a rawlog on disk
/// (rawlog_index.h) or what a live source has delivered so far (live_observations.h). The replay
/// viewer reads either through this interface.

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::rawlog {

/// One observation of the sequence.
struct RawlogEntry {
  uint64_t offset = 0;   ///< uncompressed byte offset of the record holding it [bytes] (live: 0)
  uint32_t size = 0;     ///< uncompressed bytes of that record, as serialized [bytes]
  int32_t sub = -1;      ///< position inside a CSensoryFrame record; -1: the record is the observation
  double stamp_s = 0;    ///< CObservation::timestamp [s, Unix epoch]; NaN when the record has none
  uint16_t label = 0;    ///< index into labels() (sensorLabel)
  uint16_t cls = 0;      ///< index into classNames()
  bool known = true;     ///< false: a class this build cannot read (listed, skipped)
};

/// Observations' indices in time order (those with a finite stamp): the time lookups every
/// ObservationIndex answers.
class TimeOrder {
 public:
  /// Observation \p i stamped \p t_s (NaN: not on the timeline); one that arrives late goes where
  /// it belongs (amortized O(1) for observations in time order).
  void add(uint32_t i, double t_s);
  void clear() { by_time_.clear(); }
  bool empty() const { return by_time_.empty(); }
  double first() const { return by_time_.empty() ? 0.0 : by_time_.front().first; }
  double last() const { return by_time_.empty() ? 0.0 : by_time_.back().first; }
  /// The last observation stamped at or before \p t_s, else the first; nullopt when empty.
  std::optional<std::size_t> atTime(double t_s) const;
  /// Observations stamped in [t0_s, t1_s), in time order.
  std::vector<std::size_t> inRange(double t0_s, double t1_s) const;

 private:
  std::vector<std::pair<double, uint32_t>> by_time_;
};

/// Sensor labels or class names, each stored once and referred to by a 16-bit id.
class NameIds {
 public:
  /// The id of \p s, added when new (past 65535 names every new one shares id 0).
  uint16_t id(const std::string& s);
  const std::vector<std::string>& names() const { return names_; }
  void clear();

 private:
  std::vector<std::string> names_;
  std::map<std::string, uint16_t> ids_;
};

class ObservationIndex {
 public:
  virtual ~ObservationIndex() = default;

  virtual std::size_t size() const = 0;
  virtual const RawlogEntry& entry(std::size_t i) const = 0;
  virtual const std::vector<std::string>& labels() const = 0;
  virtual const std::vector<std::string>& classNames() const = 0;
  const std::string& label(std::size_t i) const { return labels()[entry(i).label]; }
  const std::string& className(std::size_t i) const { return classNames()[entry(i).cls]; }

  /// First and last finite stamps [s]; both 0 without any.
  virtual double firstStamp() const = 0;
  virtual double lastStamp() const = 0;
  /// The observation shown at time \p t_s: the last one (in time order) stamped at or before it,
  /// else the first; nullopt when no observation has a stamp.
  virtual std::optional<std::size_t> findAtTime(double t_s) const = 0;
  /// Indices of the observations whose stamp lies in [t0_s, t1_s), in time order.
  virtual std::vector<std::size_t> findInRange(double t0_s, double t1_s) const = 0;

  /// Observation \p i. Throws std::runtime_error naming the source and the index when it cannot be
  /// had (an unknown class, an I/O error, no longer held).
  virtual std::shared_ptr<mrpt::obs::CObservation> load(std::size_t i) = 0;
};

}  // namespace roadslam::rawlog
