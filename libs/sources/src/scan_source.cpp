#include "roadslam/sources/scan_source.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/sources/pcap_source.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/sources/segmented_source.h"
#include "roadslam/sources/sweep_source.h"
#include "roadslam/velodyne/decoder_params.h"

namespace fs = std::filesystem;

namespace roadslam::sources {
namespace {

/// A folder of KITTI NNNNNN.bin sweeps (libs/datasets), timed per the [kitti] section.
class KittiScanSource : public ScanSource {
 public:
  KittiScanSource(const std::string& dir, const std::string& times_path, const datasets::KittiParams& p)
      : folder_(dir, times_path, p), dir_(dir) {}
  std::optional<Scan> next() override {
    // one unreadable .bin is counted and skipped: one bad scan never ends the run
    while (i_ < folder_.size()) {
      try {
        auto scan = folder_.read(i_++);
        ++stats_.sweeps;
        return scan;
      } catch (const std::exception& e) {
        ++stats_.malformed_packets;
        if (error_.empty()) {
          error_ = e.what();
          sweeps_before_error_ = stats_.sweeps;
        }
      }
    }
    return std::nullopt;
  }
  bool finished() const override { return i_ >= folder_.size(); }
  ScanSourceStats stats() const override { return stats_; }
  std::string describe() const override { return "kitti:" + dir_; }
  std::string errorMessage() const override {
    return error_.empty() ? "" : error_ + (stats_.malformed_packets > 1 ? " (and " + std::to_string(stats_.malformed_packets - 1) + " more)" : "");
  }
  uint64_t sweepsBeforeDamage() const override { return error_.empty() ? stats_.sweeps : sweeps_before_error_; }
  size_t sizeHint() const override { return folder_.size(); }
  std::vector<std::string> warnings() const override {
    if (folder_.hasTimes()) return {};
    char period[32];
    std::snprintf(period, sizeof period, "%g", folder_.params().timing.period_s);
    return {"KITTI folder '" + dir_ + "' has no times file (times.txt beside the .bin files or one level up): "
            "the sweeps were stamped at the nominal [kitti] sweep_period_s = " + period + " s (" +
            std::to_string(static_cast<int>(std::lround(1.0 / folder_.params().timing.period_s))) +
            " Hz) assumed; give the real one with --times FILE"};
  }

 private:
  datasets::KittiScanFolder folder_;
  std::string dir_;
  size_t i_ = 0;
  ScanSourceStats stats_;
  std::string error_;
  uint64_t sweeps_before_error_ = 0;
};

std::string sweeps(uint64_t n) { return std::to_string(n) + (n == 1 ? " sweep" : " sweeps"); }

}  // namespace

std::string damageWarning(uint64_t sweeps_before, const std::string& what, uint64_t sweeps_after) {
  return "input damaged, " + sweeps(sweeps_before) + " read before it" +
         (sweeps_after > 0 ? ", and " + std::to_string(sweeps_after) + " after it" : std::string()) + ": " + what;
}

std::string damageWarning(const ScanSource& source) {
  const std::string what = source.errorMessage();
  if (what.empty()) return {};
  const uint64_t before = source.sweepsBeforeDamage();
  return damageWarning(before, what, source.stats().sweeps - before);
}

std::unique_ptr<ScanSource> openScanSource(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& times_path) {
  if (!fs::exists(path)) throw std::runtime_error("input '" + path + "' does not exist");
  if (fs::is_directory(path) && !rawlog::RawlogSession::segmentsOf(path).empty()) {  // a roadslam-grab session
    if (!times_path.empty()) throw std::runtime_error("a times file applies to a KITTI folder; '" + path + "' is a rawlog session");
    velodyne::DecoderParams dp;
    dp.loadFromConfigFile(cfg, "velodyne");
    auto sweeps = std::make_unique<SweepSource>(std::make_unique<SegmentedPacketSource>(rawlog::RawlogSession::segmentsOf(path)), dp);
    sweeps->setMaxPendingGpsFixes(SweepSource::kMaxPendingGpsFixes);
    return sweeps;
  }
  if (fs::is_directory(path)) {
    datasets::KittiParams kp;
    kp.loadFromConfigFile(cfg, "kitti");
    return std::make_unique<KittiScanSource>(path, times_path, kp);
  }
  if (!times_path.empty()) {
    throw std::runtime_error("a times file ('" + times_path + "') applies to a KITTI folder only; '" + path +
                             "' is a file whose packets carry their own stamps");
  }
  velodyne::DecoderParams dp;
  dp.loadFromConfigFile(cfg, "velodyne");
  const std::string ext = fs::path(path).extension().string();
  std::unique_ptr<PacketSource> packets;
  if (ext == ".pcap" || ext == ".pcapng") packets = std::make_unique<PcapPacketSource>(path);
  if (ext == ".rawlog" || ext == ".gz") packets = std::make_unique<RawlogPacketSource>(path);
  if (packets) {
    auto sweeps = std::make_unique<SweepSource>(std::move(packets), dp);
    sweeps->setMaxPendingGpsFixes(SweepSource::kMaxPendingGpsFixes);  // the jobs take no fixes
    return sweeps;
  }
  throw std::runtime_error("input '" + path +
                           "': unknown kind (expected .pcap, .rawlog or a folder of KITTI .bin sweeps)");
}

void loadSourceSections(const mrpt::config::CConfigFileBase& cfg) {
  velodyne::DecoderParams dp;
  dp.loadFromConfigFile(cfg, "velodyne");
  datasets::KittiParams kp;
  kp.loadFromConfigFile(cfg, "kitti");
}

}  // namespace roadslam::sources
