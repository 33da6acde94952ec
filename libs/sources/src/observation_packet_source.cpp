#include "roadslam/sources/observation_packet_source.h"

#include <mrpt/obs/CObservationVelodyneScan.h>

#include <chrono>

#include "roadslam/sources/rawlog_source.h"

namespace roadslam::sources {

ObservationPacketSource::ObservationPacketSource(std::string sensor_label, std::string name, const PortConfig& ports)
    : label_(std::move(sensor_label)), name_(std::move(name)), ports_(ports), gaps_(0, ports.model) {}

void ObservationPacketSource::post(const std::shared_ptr<mrpt::obs::CObservation>& obs) {
  const auto* v = dynamic_cast<const mrpt::obs::CObservationVelodyneScan*>(obs.get());
  auto packets = v && v->sensorLabel == label_ ? packetsOfScan(*v, ports_.data_port) : std::vector<velodyne::RawPacket>{};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return;
    for (auto& p : packets) queue_.push_back(std::move(p));
  }
  cv_.notify_one();
}

void ObservationPacketSource::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  cv_.notify_all();
}

bool ObservationPacketSource::finished() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return closed_ && queue_.empty();
}

std::optional<velodyne::RawPacket> ObservationPacketSource::next() {
  for (;;) {
    velodyne::RawPacket p;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!cv_.wait_for(lock, std::chrono::duration<double>(wait_s_), [&] { return closed_ || !queue_.empty(); }) ||
          queue_.empty())
        return std::nullopt;
      p = std::move(queue_.front());
      queue_.pop_front();
    }
    if (accountPacket(ports_, p, stats_, gaps_)) return p;
  }
}

}  // namespace roadslam::sources
