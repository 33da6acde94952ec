#pragma once
/// \file live_observations.h
/// Observations as a live source delivers them (roadslam-view --udp / --grab: the grabber's tap),
/// indexed like a rawlog (observation_index.h). post() may be called from any thread; poll(), on the
/// reader's thread, makes what was posted visible, so lookups need no lock and never see a half
/// update.
///
/// Memory is bounded by time: every observation's entry (40 bytes: ~20 MB for an hour of one VLP-16
/// and a CAN bus) is kept for the timeline and the list, its payload only while it is among the
/// newest `keep_s` seconds; load() of an older one says so.

#include <deque>
#include <mutex>

#include "roadslam/rawlog/observation_index.h"

namespace roadslam::sources {

class LiveObservations : public rawlog::ObservationIndex {
 public:
  /// \p keep_s: payloads kept for this long behind the newest stamp [s].
  explicit LiveObservations(std::string name, double keep_s = 30.0);
  ~LiveObservations() override;

  /// Thread-safe: queues \p obs (its stamp, label and class are read now).
  void post(std::shared_ptr<mrpt::obs::CObservation> obs);
  /// Reader's thread: appends the posted observations (in arrival order) and frees payloads that
  /// left the keep window; returns the index of the first new one (== size() when none came).
  std::size_t poll();
  /// Observations posted so far, polled or not (thread-safe) [count].
  std::size_t posted() const;
  double keepSeconds() const { return keep_s_; }

  std::size_t size() const override { return entries_.size(); }
  const rawlog::RawlogEntry& entry(std::size_t i) const override { return entries_.at(i); }
  const std::vector<std::string>& labels() const override { return labels_.names(); }
  const std::vector<std::string>& classNames() const override { return classes_.names(); }
  double firstStamp() const override { return time_.first(); }
  double lastStamp() const override { return time_.last(); }
  std::optional<std::size_t> findAtTime(double t_s) const override { return time_.atTime(t_s); }
  std::vector<std::size_t> findInRange(double t0_s, double t1_s) const override { return time_.inRange(t0_s, t1_s); }
  /// The payload of \p i; throws naming the source, the index and the keep window when it was
  /// freed.
  std::shared_ptr<mrpt::obs::CObservation> load(std::size_t i) override;

 private:
  struct Posted {
    std::shared_ptr<mrpt::obs::CObservation> obs;
    uint32_t bytes = 0;
  };
  void append(Posted& p);

  std::string name_;
  double keep_s_;
  mutable std::mutex mutex_;
  std::vector<Posted> queue_;
  std::size_t posted_ = 0;

  std::vector<rawlog::RawlogEntry> entries_;
  std::deque<std::shared_ptr<mrpt::obs::CObservation>> payload_;  // parallel to entries_
  std::size_t freed_ = 0;                 // payloads [0, freed_) released (arrival order)
  rawlog::TimeOrder time_;
  rawlog::NameIds labels_, classes_;
};

}  // namespace roadslam::sources
