#pragma once
/// \file rawlog_session.h
/// A recording cut into segments, as roadslam-grab writes a session folder (<prefix>_000.rawlog,
/// _001, ... rotated by size or time), as one sequence of observations. Every segment is indexed in
/// the background at once (BackgroundRawlogIndex, each with its own index file); the session shows the
/// segments in order, a later one only once every earlier one is wholly indexed, so indices only
/// ever grow at the end. Labels and classes are renumbered into one table for the session.

#include <memory>
#include <string>
#include <vector>

#include "roadslam/rawlog/background_rawlog_index.h"

namespace roadslam::rawlog {

class RawlogSession : public ObservationIndex {
 public:
  /// The rawlog segments of \p folder: files "<prefix>_NNN.rawlog" (NNN: digits) sharing one prefix,
  /// in segment order; empty when the folder holds none.
  static std::vector<std::string> segmentsOf(const std::string& folder);
  /// Opens \p segments (in time order); throws naming a segment that does not exist or a list that is
  /// empty.
  static std::unique_ptr<RawlogSession> open(const std::vector<std::string>& segments,
                                             const RawlogIndexOptions& options = {});
  ~RawlogSession() override;

  /// Takes in what the segments' indexing found since; returns how many observations came.
  std::size_t poll();
  /// True once every segment is wholly indexed and shown.
  bool done() const { return shown_ == parts_.size(); }
  void waitUntilDone();
  /// Share of the session's bytes indexed [0, 1].
  double progress() const;
  std::size_t segments() const { return parts_.size(); }
  /// Segment \p k (its damage, unknown classes and how its index was opened once it is done).
  const BackgroundRawlogIndex& segment(std::size_t k) const { return *parts_.at(k); }
  /// Problems of the segments' indexing threads, one line each (empty when none).
  std::vector<std::string> errors() const;

  std::size_t size() const override { return entries_.size(); }
  const RawlogEntry& entry(std::size_t i) const override { return entries_.at(i); }
  const std::vector<std::string>& labels() const override { return labels_.names(); }
  const std::vector<std::string>& classNames() const override { return classes_.names(); }
  double firstStamp() const override { return time_.first(); }
  double lastStamp() const override { return time_.last(); }
  std::optional<std::size_t> findAtTime(double t_s) const override { return time_.atTime(t_s); }
  std::vector<std::size_t> findInRange(double t0_s, double t1_s) const override { return time_.inRange(t0_s, t1_s); }
  std::shared_ptr<mrpt::obs::CObservation> load(std::size_t i) override;

 private:
  RawlogSession() = default;

  std::vector<std::unique_ptr<BackgroundRawlogIndex>> parts_;
  std::vector<uint64_t> sizes_;         // bytes per segment (progress)
  std::size_t shown_ = 0;               // segments wholly shown
  std::size_t taken_ = 0;               // entries of segment shown_ taken so far
  std::vector<RawlogEntry> entries_;    // renumbered labels and classes
  std::vector<std::pair<uint32_t, uint32_t>> where_;  // session index -> (segment, index in it)
  TimeOrder time_;
  NameIds labels_, classes_;
};

}  // namespace roadslam::rawlog
