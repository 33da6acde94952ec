// How far a recording has been read (PacketSource::readProgress): the bytes of its file(s) against
// their size on disk, for the jobs' progress and ETA. Oracles: the file sizes and the packet counts.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>

#include "roadslam/sources/pcap_source.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/sources/recording.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/sources/segmented_source.h"

using namespace roadslam::sources;
namespace fs = std::filesystem;

namespace {

const std::string kBox = std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap";

fs::path tempDir() {
  const fs::path d = fs::temp_directory_path() / ("roadslam_read_progress_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

/// Reads \p src to its end; the progress after each packet.
std::vector<ReadProgress> readAll(PacketSource& src) {
  std::vector<ReadProgress> out;
  while (src.next()) out.push_back(src.readProgress());
  return out;
}

/// The progress never goes back, never passes the total, and ends at the total.
void expectMonotoneToTotal(const std::vector<ReadProgress>& p, uint64_t total) {
  ASSERT_FALSE(p.empty());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p[i].bytes_total, total);
    EXPECT_LE(p[i].bytes_read, total);
    if (i > 0) {
      EXPECT_GE(p[i].bytes_read, p[i - 1].bytes_read) << i;
    }
  }
  EXPECT_LT(p.front().bytes_read, total / 2);
}

}  // namespace

TEST(ReadProgress, PcapBytesOfTheFile) {
  const uint64_t size = fs::file_size(kBox);
  PcapPacketSource src(kBox);
  EXPECT_EQ(src.readProgress().bytes_total, size);
  const auto p = readAll(src);
  expectMonotoneToTotal(p, size);
  EXPECT_EQ(src.readProgress().bytes_read, size);  // at the end of the file
  // Half the packets (all of one size) lie in about half the file.
  EXPECT_NEAR(double(p[p.size() / 2].bytes_read) / double(size), 0.5, 0.05);
}

TEST(ReadProgress, RawlogCompressedBytesOfTheFile) {
  const std::string rawlog = (tempDir() / "box.rawlog").string();
  convertToRawlog(kBox, rawlog);
  const uint64_t size = fs::file_size(rawlog);
  RawlogPacketSource src(rawlog);
  const auto p = readAll(src);
  expectMonotoneToTotal(p, size);
  EXPECT_EQ(src.readProgress().bytes_read, size);
  // Compressed bytes advance with the sweeps read (zlib reads ahead in chunks: a loose bound).
  EXPECT_NEAR(double(p[p.size() / 2].bytes_read) / double(size), 0.5, 0.25);
  fs::remove(rawlog);
  fs::remove(rawlog + ".ini");
}

TEST(ReadProgress, SessionSegmentsAddUp) {
  const fs::path dir = tempDir() / "session";
  fs::create_directories(dir);
  for (const char* name : {"grab_000.rawlog", "grab_001.rawlog"}) convertToRawlog(kBox, (dir / name).string());
  const uint64_t one = fs::file_size(dir / "grab_000.rawlog");
  SegmentedPacketSource src({(dir / "grab_000.rawlog").string(), (dir / "grab_001.rawlog").string()});
  const auto p = readAll(src);
  expectMonotoneToTotal(p, 2 * one);
  EXPECT_EQ(src.readProgress().bytes_read, 2 * one);
  EXPECT_NEAR(double(p[p.size() / 2].bytes_read), double(one), 0.3 * double(one));
  fs::remove_all(dir);
}

TEST(ReadProgress, ASweepSourcePassesItsPacketsOn) {
  mrpt::config::CConfigFileMemory no_ini;
  auto src = openScanSource(kBox, no_ini);
  EXPECT_EQ(src->readProgress().bytes_total, fs::file_size(kBox));
  while (src->next()) {
  }
  EXPECT_EQ(src->readProgress().bytes_read, fs::file_size(kBox));
}
