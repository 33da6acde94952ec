#include "roadslam/sources/sweep_source.h"

namespace roadslam::sources {

double SweepSourceStats::sweepRate_hz() const {
  const double span = last_wrap_stamp_s - first_wrap_stamp_s;
  return wrap_sweeps >= 2 && span > 0 ? double(wrap_sweeps - 1) / span : 0.0;
}

SweepSource::SweepSource(std::unique_ptr<PacketSource> packets, const velodyne::DecoderParams& params,
                         std::string force_setting)
    : packets_(std::move(packets)), params_(params), force_setting_(std::move(force_setting)), assembler_(params) {}

std::vector<std::string> SweepSource::warnings() const {
  if (!choice_ || choice_->warning.empty()) return {};
  return {choice_->warning};
}

std::optional<LidarModelReport> SweepSource::lidarModel() const {
  if (!choice_) return LidarModelReport{"undecided", "", ""};
  return LidarModelReport{velodyne::displayName(choice_->model), velodyne::toString(choice_->source),
                          choice_->layout.describe()};
}

bool SweepSource::chooseModel() {
  while (!layout_.full()) {
    ReadAhead r{packets_->next(), packets_->takeDecodedFixes()};
    const bool got = r.packet.has_value();
    if (got && r.packet->payload.size() == velodyne::kDataPacketSize)
      layout_.add(r.packet->payload.data(), r.packet->payload.size());
    if (got || !r.fixes.empty()) ahead_.push_back(std::move(r));
    if (got) continue;
    if (!packets_->finished()) return false;  // live: the window is not full yet
    break;
  }
  choice_ = velodyne::chooseModel(params_.model, layout_.verdict(), force_setting_);
  assembler_.setStreamModel(choice_->model);
  return true;
}

std::optional<velodyne::RawPacket> SweepSource::nextPacket(bool& waiting) {
  waiting = false;
  while (!ahead_.empty()) {
    ReadAhead r = std::move(ahead_.front());
    ahead_.pop_front();
    for (auto& f : r.fixes) keepFix(f);
    if (r.packet) return std::move(r.packet);  // else fixes alone: on to the next
  }
  auto pkt = packets_->next();
  for (auto& f : packets_->takeDecodedFixes()) keepFix(f);
  waiting = !pkt && !packets_->finished();
  return pkt;
}

ScanSourceStats SweepSource::stats() const {
  const auto& a = assembler_.stats();
  const auto& s = packets_->stats();
  return {a.sweeps, a.partial_sweeps, s.packets, s.malformed_packets + a.malformed()};
}

void SweepSource::keepFix(const gnss::GnssFix& f) {
  if (max_pending_fixes_ > 0 && fixes_.size() >= max_pending_fixes_) {
    fixes_.pop_front();
    ++stats_.gps_fixes_dropped;
  }
  fixes_.push_back(f);
}

Scan SweepSource::deliver(Scan s) {
  ++stats_.sweeps;
  stats_.points += s.points.size();
  if (s.partial) ++stats_.partial_sweeps;
  // Every sweep but the stream's first begins where the azimuth crossed the cut.
  if (stats_.sweeps > 1) {
    if (stats_.wrap_sweeps == 0) stats_.first_wrap_stamp_s = s.stamp_s;
    stats_.last_wrap_stamp_s = s.stamp_s;
    ++stats_.wrap_sweeps;
  }
  return s;
}

std::optional<Scan> SweepSource::next() {
  if (!choice_ && !chooseModel()) return std::nullopt;  // live: nothing decided within the timeout
  // The damage is met on the call after the sweep that met it; packets the model choice read ahead
  // come before it, so it counts only once they are used.
  if (!damage_seen_ && ahead_.empty() && !packets_->errorMessage().empty()) {
    damage_seen_ = true;
    sweeps_before_damage_ = stats().sweeps;
  }
  while (!assembler_.hasSweep()) {
    if (finished_) return std::nullopt;
    bool waiting = false;
    auto pkt = nextPacket(waiting);
    if (!pkt) {
      if (waiting) return std::nullopt;  // live: nothing within the timeout
      finished_ = true;
      assembler_.finish();
      continue;
    }
    std::size_t closed = 0;
    if (pkt->payload.size() == velodyne::kPositionPacketSize) {
      if (auto fix = decodeGpsFix(*pkt)) keepFix(*fix);
    } else {
      const std::size_t before = assembler_.stats().sweeps + assembler_.stats().empty_sweeps_dropped;
      if (assembler_.addPacket(pkt->payload.data(), pkt->payload.size(), pkt->stamp_s) !=
          velodyne::DecodeStatus::Ok)
        ++stats_.undecodable_packets;
      closed = assembler_.stats().sweeps + assembler_.stats().empty_sweeps_dropped - before;
    }
    if (observer_) observer_(*pkt, closed);
  }
  return deliver(assembler_.takeSweep());
}

std::vector<gnss::GnssFix> SweepSource::takeGpsFixes() {
  std::vector<gnss::GnssFix> out(fixes_.begin(), fixes_.end());
  fixes_.clear();
  stats_.gps_fixes += out.size();
  return out;
}

}  // namespace roadslam::sources
