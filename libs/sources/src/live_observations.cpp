#include "roadslam/sources/live_observations.h"

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "roadslam/rawlog/mrpt_stamp.h"

namespace roadslam::sources {

LiveObservations::LiveObservations(std::string name, double keep_s) : name_(std::move(name)), keep_s_(keep_s) {}
LiveObservations::~LiveObservations() = default;

void LiveObservations::post(std::shared_ptr<mrpt::obs::CObservation> obs) {
  if (!obs) return;
  // The size the list shows is the record's, as a rawlog would hold it; measured here, on the
  // poster's thread, not on the one that draws.
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf).WriteObject(obs.get());
  Posted p{std::move(obs), uint32_t(std::min<uint64_t>(buf.getTotalBytesCount(), 0xffffffffu))};
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.push_back(std::move(p));
  ++posted_;
}

std::size_t LiveObservations::posted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return posted_;
}

void LiveObservations::append(Posted& p) {
  rawlog::RawlogEntry e;
  e.size = p.bytes;
  e.stamp_s = p.obs->timestamp != INVALID_TIMESTAMP ? rawlog::stampSeconds(p.obs->timestamp)
                                                    : std::numeric_limits<double>::quiet_NaN();
  e.label = labels_.id(p.obs->sensorLabel);
  std::string cls = p.obs->GetRuntimeClass()->className;
  const auto colons = cls.rfind("::");
  e.cls = classes_.id(colons == std::string::npos ? cls : cls.substr(colons + 2));
  const auto i = uint32_t(entries_.size());
  entries_.push_back(e);
  payload_.push_back(std::move(p.obs));
  time_.add(i, e.stamp_s);  // in time order but for the writer's late ones
}

std::size_t LiveObservations::poll() {
  std::vector<Posted> q;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    q.swap(queue_);
  }
  const std::size_t first_new = entries_.size();
  for (auto& p : q) append(p);
  const double horizon = lastStamp() - keep_s_;
  while (freed_ < entries_.size() && !(entries_[freed_].stamp_s >= horizon)) {
    if (entries_.size() - freed_ <= 1) break;  // the newest stays, stamped or not
    payload_[freed_++].reset();
  }
  return first_new;
}

std::shared_ptr<mrpt::obs::CObservation> LiveObservations::load(std::size_t i) {
  if (i >= entries_.size())
    throw std::runtime_error(name_ + ": observation " + std::to_string(i) + " does not exist (" +
                             std::to_string(entries_.size()) + " so far)");
  if (!payload_[i])
    throw std::runtime_error(name_ + ": observation " + std::to_string(i) +
                             " is no longer held (a live view keeps the last " +
                             std::to_string(int(keep_s_)) + " s)");
  return payload_[i];
}

}  // namespace roadslam::sources
