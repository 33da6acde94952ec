#include "roadslam/sources/gps_fix.h"

#include <filesystem>

#include "roadslam/rawlog/rawlog_index.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/velodyne/position.h"

namespace fs = std::filesystem;

namespace roadslam::sources {

std::optional<gnss::GnssFix> decodeGpsFix(const velodyne::RawPacket& pkt) {
  velodyne::PositionPacket pos;
  if (!velodyne::decodePositionPacket(pkt.payload.data(), pkt.payload.size(), pos) || !pos.fix)
    return std::nullopt;
  pos.fix->t_receive_s = pkt.stamp_s;
  pos.fix->label = kPositionPacketsLabel;
  return pos.fix;
}

std::map<std::string, std::size_t> gpsSourcesOf(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".pcap" || ext == ".pcapng") return {{kPositionPacketsLabel, 0}};
  std::vector<std::string> files = fs::is_directory(path) ? rawlog::RawlogSession::segmentsOf(path) : std::vector<std::string>{};
  if (ext == ".rawlog" || ext == ".gz") files = {path};
  rawlog::RawlogIndexOptions opt;
  opt.write_cache = false;  // a mapping run leaves the recording's folder as it found it
  std::map<std::string, std::size_t> out;
  for (const auto& f : files) {
    const auto index = rawlog::RawlogIndex::open(f, opt);
    for (std::size_t i = 0; i < index->size(); ++i)
      if (index->className(i).find("CObservationGPS") != std::string::npos) ++out[index->label(i)];
  }
  return out;
}

}  // namespace roadslam::sources
