#include "roadslam/rawlog/background_rawlog_index.h"

#include <mrpt/obs/CObservation.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "rawlog_index_impl.h"

namespace roadslam::rawlog {

std::unique_ptr<BackgroundRawlogIndex> BackgroundRawlogIndex::open(const std::string& path,
                                                                   const RawlogIndexOptions& options) {
  std::unique_ptr<BackgroundRawlogIndex> b(new BackgroundRawlogIndex());
  b->path_ = path;
  b->file_size_ = std::max<uint64_t>(1, detail::stampOf(path).size);  // throws naming a missing file
  RawlogIndexOptions fast = options;
  if (options.use_cache) {  // a fresh index file: the whole index at once
    const auto files = RawlogIndex::indexFiles(path, options).read;
    std::error_code ec;
    if (std::any_of(files.begin(), files.end(), [&ec](const std::string& f) { return std::filesystem::exists(f, ec); })) {
      bool stale = false;
      fast.on_build = [&stale](const std::string&) { stale = true; };
      // open() builds when the sidecar is stale: abandon at the first progress call instead
      auto idx = RawlogIndex::open(path, fast, [&stale](const RawlogIndex::Impl&) { return !stale; });
      if (idx) {
        b->full_ = std::move(idx);
        return b;
      }
    }
  }
  b->stream_ = std::make_unique<detail::SeekableStream>(path);
  BackgroundRawlogIndex* self = b.get();
  RawlogIndexOptions build = options;
  build.use_cache = false;
  b->thread_ = std::thread([self, build] {
    std::unique_ptr<RawlogIndex> idx;
    std::string error;
    try {
      idx = RawlogIndex::open(self->path_, build, [self](const RawlogIndex::Impl& im) { return self->publish(im); });
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard<std::mutex> lock(self->mutex_);
    self->finished_ = std::move(idx);
    self->thread_error_ = error;
    self->thread_done_ = true;
  });
  return b;
}

BackgroundRawlogIndex::~BackgroundRawlogIndex() {
  abandon_ = true;
  if (thread_.joinable()) thread_.join();
}

bool BackgroundRawlogIndex::publish(const RawlogIndex::Impl& im) {
  if (abandon_) return false;
  compressed_read_ = im.stream->compressedPosition();
  const auto& pts = im.stream->accessPoints();
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.insert(pending_.end(), im.entries.begin() + long(published_entries_), im.entries.end());
  published_entries_ = im.entries.size();
  if (im.labels.names().size() != pending_labels_.size()) pending_labels_ = im.labels.names();
  if (im.classes.names().size() != pending_classes_.size()) pending_classes_ = im.classes.names();
  for (; published_points_ < pts.size(); ++published_points_)
    pending_points_.push_back(std::make_shared<detail::GzAccessPoint>(pts[published_points_]));
  return true;
}

std::size_t BackgroundRawlogIndex::poll() {
  if (full_) return 0;
  const std::size_t before = entries_.size();
  std::lock_guard<std::mutex> lock(mutex_);
  if (thread_done_) {
    if (finished_) {
      full_ = std::move(finished_);
      entries_.clear();
      time_.clear();
      points_.clear();
      stream_.reset();
      return full_->size() - std::min(before, full_->size());
    }
    if (error_.empty()) error_ = path_ + ": indexing stopped: " + thread_error_;
  }
  for (const auto& e : pending_) {
    const auto i = uint32_t(entries_.size());
    entries_.push_back(e);
    time_.add(i, e.stamp_s);
  }
  pending_.clear();
  if (!pending_labels_.empty()) labels_ = pending_labels_;
  if (!pending_classes_.empty()) classes_ = pending_classes_;
  if (!pending_points_.empty()) {
    for (const auto& p : pending_points_) points_.push_back(*p);
    pending_points_.clear();
    stream_->setAccessPoints(points_);
  }
  return entries_.size() - before;
}

void BackgroundRawlogIndex::waitUntilDone() {
  while (!full_) {
    poll();
    if (!error_.empty()) throw std::runtime_error(error_);
    if (!full_) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

double BackgroundRawlogIndex::progress() const {
  return full_ ? 1.0 : std::min(1.0, double(compressed_read_.load()) / double(file_size_));
}

std::size_t BackgroundRawlogIndex::size() const { return full_ ? full_->size() : entries_.size(); }
const RawlogEntry& BackgroundRawlogIndex::entry(std::size_t i) const { return full_ ? full_->entry(i) : entries_.at(i); }
const std::vector<std::string>& BackgroundRawlogIndex::labels() const { return full_ ? full_->labels() : labels_; }
const std::vector<std::string>& BackgroundRawlogIndex::classNames() const {
  return full_ ? full_->classNames() : classes_;
}
double BackgroundRawlogIndex::firstStamp() const { return full_ ? full_->firstStamp() : time_.first(); }
double BackgroundRawlogIndex::lastStamp() const { return full_ ? full_->lastStamp() : time_.last(); }
std::optional<std::size_t> BackgroundRawlogIndex::findAtTime(double t_s) const {
  return full_ ? full_->findAtTime(t_s) : time_.atTime(t_s);
}
std::vector<std::size_t> BackgroundRawlogIndex::findInRange(double t0_s, double t1_s) const {
  return full_ ? full_->findInRange(t0_s, t1_s) : time_.inRange(t0_s, t1_s);
}

std::shared_ptr<mrpt::obs::CObservation> BackgroundRawlogIndex::load(std::size_t i) {
  if (full_) return full_->load(i);
  const RawlogEntry& e = entries_.at(i);
  if (!e.known)
    throw std::runtime_error(path_ + ": observation " + std::to_string(i) + " is of class '" + className(i) +
                             "', unknown to this build");
  return detail::loadEntry(*stream_, e, path_, i);
}

}  // namespace roadslam::rawlog
