#include "roadslam/sources/rawlog_source.h"

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>

#include <cmath>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include "gz_read_stream.h"
#include "roadslam/rawlog/mrpt_message.h"
#include "roadslam/rawlog/mrpt_stamp.h"

#include "roadslam/common/param_table.h"

namespace roadslam::sources {

using rawlog::detail::innermostMessage;

using mrpt::obs::CObservationVelodyneScan;

namespace {
constexpr double kHour_s = 3600.0;

/// The sensor's microsecond counter of a packet (bytes 1200-1203, little-endian), read byte by byte:
/// MRPT's packed 1206-byte struct sits at unaligned addresses in scan_packets, where its
/// gps_timestamp() binds a misaligned uint32_t reference (UBSan: misaligned address).
uint32_t packetCounter_us(const CObservationVelodyneScan::TVelodyneRawPacket& raw) {
  const auto* b = reinterpret_cast<const uint8_t*>(&raw) + 1200;
  return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 | static_cast<uint32_t>(b[2]) << 16 |
         static_cast<uint32_t>(b[3]) << 24;
}

using unit::kKnot;


}  // namespace

gnss::GnssFix gpsFixFromObservation(const mrpt::obs::CObservationGPS& o) {
  gnss::GnssFix fix;
  const auto ts = o.originalReceivedTimestamp != INVALID_TIMESTAMP ? o.originalReceivedTimestamp
                                                                    : o.timestamp;
  fix.t_receive_s = mrpt::Clock::toDouble(ts);
  fix.label = o.sensorLabel;
  if (o.hasMsgClass<mrpt::obs::gnss::Message_NMEA_GGA>()) {
    const auto& g = o.getMsgByClass<mrpt::obs::gnss::Message_NMEA_GGA>().fields;
    fix.quality = g.fix_quality;
    if (g.thereis_HDOP) fix.hdop = g.HDOP;
    fix.time_of_day_s = g.UTCTime.hour * 3600.0 + g.UTCTime.minute * 60.0 + g.UTCTime.sec;
    // ellipsoidal height = MSL altitude + geoid separation (NMEA GGA)
    fix.position = {g.latitude_degrees, g.longitude_degrees, g.altitude_meters + g.geoidal_distance};
    fix.has_position = true;
  }
  if (!o.hasMsgClass<mrpt::obs::gnss::Message_NMEA_RMC>()) return fix;
  const auto& f = o.getMsgByClass<mrpt::obs::gnss::Message_NMEA_RMC>().fields;
  fix.time_of_day_s = f.UTCTime.hour * 3600.0 + f.UTCTime.minute * 60.0 + f.UTCTime.sec;
  fix.rmc_status = f.validity_char;
  if (f.validity_char != 'A' && fix.quality > 0) fix.quality = 0;  // a void RMC: no fix, whatever the GGA says
  if (f.date_year != 0) {  // RMC carries a two-digit year
    std::tm t{};
    t.tm_year = 2000 + f.date_year - 1900;
    t.tm_mon = f.date_month - 1;
    t.tm_mday = f.date_day;
    fix.t_receiver_s = static_cast<double>(timegm(&t)) + fix.time_of_day_s;
  }
  fix.position.lat_deg = f.latitude_degrees;
  fix.position.lon_deg = f.longitude_degrees;
  fix.has_position = true;
  fix.speed_mps = f.speed_knots * kKnot;
  fix.course_rad = f.direction_degrees * M_PI / 180.0;
  return fix;
}

struct RawlogPacketSource::Impl {
  detail::GzReadStream in;
  std::deque<mrpt::obs::CObservation::Ptr> pending;  // observations of a sensory frame
};

RawlogPacketSource::RawlogPacketSource(const std::string& path, const PortConfig& ports)
    : impl_(std::make_unique<Impl>()), path_(path), ports_(ports), gaps_(0, ports.model) {
  if (!mrpt::system::fileExists(path))
    throw std::runtime_error("rawlog '" + path + "' does not exist");
  if (!impl_->in.open(path)) throw std::runtime_error("cannot open rawlog '" + path + "'");
}

RawlogPacketSource::~RawlogPacketSource() = default;

// Reads the next record; returns false at end of file. A record cut short or that fails to
// deserialize ends the replay (the stream position is lost) and sets error_.
bool RawlogPacketSource::readMore() {
  mrpt::obs::CObservation::Ptr obs;
  if (!impl_->pending.empty()) {
    obs = impl_->pending.front();
    impl_->pending.pop_front();
  } else {
    mrpt::serialization::CSerializable::Ptr rec;
    const uint64_t start = impl_->in.getPosition();
    try {
      rec = mrpt::serialization::archiveFrom(impl_->in).ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
      // EOF before the first byte of a record is the clean end; inside one, a truncated file.
      if (impl_->in.getPosition() != start) error_ = path_ + ": " + rawlog::detail::stopPlace(start);
      return false;
    } catch (const std::exception& e) {
      // the first record unreadable: not a rawlog at all; a later one: damage (words as RawlogIndex's)
      const std::string cause = innermostMessage(e.what());
      if (start == 0) error_ = path_ + ": not a readable MRPT rawlog (record at byte 0: " + cause + ")";
      else error_ = path_ + ": " + rawlog::detail::stopPlace(start, rawlog::detail::isCutShort(e.what()) ? "" : cause);
      return false;
    }
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(rec)) {
      for (const auto& o : *sf) impl_->pending.push_back(o);
      return true;
    }
    obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(rec);
  }
  if (auto v = std::dynamic_pointer_cast<CObservationVelodyneScan>(obs)) {
    ++scans_;
    scan_label_ = v->sensorLabel;
    for (auto& pkt : packetsOfScan(*v, ports_.data_port))
      if (accountPacket(ports_, pkt, stats_, gaps_)) queue_.push_back(std::move(pkt));
  } else if (auto g = std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(obs)) {
    if (g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_RMC>() || g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_GGA>()) {
      gps_.push_back(gpsFixFromObservation(*g));
      ++stats_.position_packets;
    } else {
      ++stats_.skipped_packets;
    }
  } else {
    ++other_;
    if (keep_other_ && obs)
      others_.push_back({obs->sensorLabel, obs->GetRuntimeClass()->className, rawlog::stampSeconds(obs->timestamp)});
  }
  return true;
}

ReadProgress RawlogPacketSource::readProgress() const {
  return {impl_->in.compressedPosition(), impl_->in.getTotalBytesCount()};
}

std::vector<RawlogPacketSource::OtherRecord> RawlogPacketSource::takeOtherRecords() {
  std::vector<OtherRecord> out;
  out.swap(others_);
  return out;
}

std::vector<gnss::GnssFix> RawlogPacketSource::takeDecodedFixes() {
  std::vector<gnss::GnssFix> out;
  out.swap(gps_);
  return out;
}

std::optional<velodyne::RawPacket> RawlogPacketSource::next() {
  while (queue_.empty() && !finished_) finished_ = !readMore();
  if (queue_.empty()) return std::nullopt;
  velodyne::RawPacket p = std::move(queue_.front());
  queue_.pop_front();
  return p;
}

std::vector<velodyne::RawPacket> packetsOfScan(const CObservationVelodyneScan& v, uint16_t data_port) {
  const auto t0 = v.originalReceivedTimestamp != INVALID_TIMESTAMP ? v.originalReceivedTimestamp : v.timestamp;
  const double stamp0 = mrpt::Clock::toDouble(t0);
  const double counter0 = v.scan_packets.empty() ? 0 : packetCounter_us(v.scan_packets[0]) * 1e-6;
  std::vector<velodyne::RawPacket> out;
  out.reserve(v.scan_packets.size());
  for (const auto& raw : v.scan_packets) {
    velodyne::RawPacket pkt;
    double dt = packetCounter_us(raw) * 1e-6 - counter0;
    if (dt < -kHour_s / 2) dt += kHour_s;  // sensor counter wraps at the top of the hour
    pkt.stamp_s = stamp0 + dt;
    pkt.dst_port = data_port;
    const auto* b = reinterpret_cast<const uint8_t*>(&raw);
    pkt.payload.assign(b, b + velodyne::kDataPacketSize);
    out.push_back(std::move(pkt));
  }
  return out;
}

}  // namespace roadslam::sources
