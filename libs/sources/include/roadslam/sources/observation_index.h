#pragma once
/// \file observation_index.h
/// Random access, by position and by time, to a sequence of MRPT observations: a rawlog on disk
/// (rawlog_index.h) or what a live source has delivered so far (live_observations.h). The replay
/// viewer reads either through this interface.

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::sources {

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

}  // namespace roadslam::sources
