#pragma once
/// \file background_rawlog_index.h
/// A rawlog that opens at once however long it is: with a fresh index file ("<rawlog>.idx", or
/// RawlogIndexOptions::cache_path's) it is a RawlogIndex read from it; otherwise the index is built
/// on a thread of its own (RawlogIndex::open, which writes the index file at the end) while the
/// observations indexed so far can already be listed, looked up by time and loaded (each through the
/// access points recorded so far: a seek decompresses at most one span). poll() on the reader's thread publishes the progress; once the
/// build is done the complete RawlogIndex takes over, with the same indices.
///
/// The replay viewer opens recordings this way: an hour-long rawlog shows its first sweep in well
/// under a second the first time, and its timeline grows while the rest is indexed.

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "roadslam/rawlog/rawlog_index.h"

namespace roadslam::rawlog {

namespace detail {
class SeekableStream;
struct GzAccessPoint;
}  // namespace detail

class BackgroundRawlogIndex : public ObservationIndex {
 public:
  /// Throws std::runtime_error naming \p path when it does not exist or cannot be read at all.
  static std::unique_ptr<BackgroundRawlogIndex> open(const std::string& path, const RawlogIndexOptions& options = {});
  /// Abandons a build in progress (no index file is written) and joins.
  ~BackgroundRawlogIndex() override;
  BackgroundRawlogIndex(const BackgroundRawlogIndex&) = delete;
  BackgroundRawlogIndex& operator=(const BackgroundRawlogIndex&) = delete;

  /// Reader's thread: makes what was indexed since visible; returns how many observations came.
  std::size_t poll();
  /// Polls until the build is done. Rethrows what stopped the build thread (an I/O error).
  void waitUntilDone();
  /// The complete index, once a poll() saw the build finish (or an index file was fresh); else nullptr.
  const RawlogIndex* done() const { return full_.get(); }
  /// Share of the file indexed [0, 1] (compressed bytes read / file size).
  double progress() const;
  const std::string& path() const { return path_; }
  /// What stopped the build thread, if anything did (empty otherwise).
  const std::string& error() const { return error_; }

  std::size_t size() const override;
  const RawlogEntry& entry(std::size_t i) const override;
  const std::vector<std::string>& labels() const override;
  const std::vector<std::string>& classNames() const override;
  double firstStamp() const override;
  double lastStamp() const override;
  std::optional<std::size_t> findAtTime(double t_s) const override;
  std::vector<std::size_t> findInRange(double t0_s, double t1_s) const override;
  std::shared_ptr<mrpt::obs::CObservation> load(std::size_t i) override;

 private:
  BackgroundRawlogIndex() = default;
  bool publish(const RawlogIndex::Impl& building);  // the build thread's progress call

  std::string path_;
  std::unique_ptr<RawlogIndex> full_;  // once done
  // shared with the build thread
  mutable std::mutex mutex_;
  std::vector<RawlogEntry> pending_;
  std::vector<std::string> pending_labels_, pending_classes_;
  std::vector<std::shared_ptr<detail::GzAccessPoint>> pending_points_;
  std::size_t published_entries_ = 0, published_points_ = 0;  // build thread only
  std::unique_ptr<RawlogIndex> finished_;
  std::string thread_error_;
  bool thread_done_ = false;
  std::atomic<bool> abandon_{false};
  std::atomic<uint64_t> compressed_read_{0};
  uint64_t file_size_ = 1;
  std::thread thread_;
  // visible while building (reader's thread)
  std::vector<RawlogEntry> entries_;
  std::vector<std::string> labels_, classes_;
  TimeOrder time_;
  std::unique_ptr<detail::SeekableStream> stream_;
  std::vector<detail::GzAccessPoint> points_;
  std::string error_;
};

}  // namespace roadslam::rawlog
