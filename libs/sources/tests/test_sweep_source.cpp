// SweepSource: decoded box-room points lie on the room's walls (geometry oracle for the whole
// generator -> pcap -> decoder -> assembler chain), and a live UDP replay gives the same sweeps
// as the pcap replay.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "roadslam/sources/boxroom.h"
#include "roadslam/sources/pcap_source.h"
#include "roadslam/sources/recording.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/sources/sweep_source.h"
#include "roadslam/sources/udp_receiver.h"

using namespace roadslam::sources;
namespace fs = std::filesystem;

namespace {

fs::path boxRoomFile(const BoxRoomParams& p, const char* name) {
  const fs::path f = fs::temp_directory_path() / (std::string(name) + std::to_string(getpid()) + ".pcap");
  writeBoxRoomPcap(f.string(), p);
  return f;
}

// Distance of a room-frame point to the nearest of the six boundary planes [m].
double distanceToBoundary(const BoxRoomParams& p, double x, double y, double z) {
  return std::min({std::abs(x), std::abs(x - p.length_m), std::abs(y), std::abs(y - p.width_m),
                   std::abs(z), std::abs(z - p.height_m)});
}

}  // namespace

TEST(SweepSource, BoxRoomPointsLieOnTheWalls) {
  BoxRoomParams p;
  p.revolutions = 3;
  const fs::path file = boxRoomFile(p, "sweep_walls_");
  SweepSource sweep_source(std::make_unique<PcapPacketSource>(file.string()));
  ScanSource& src = sweep_source;  // consumers see only the generic interface
  std::vector<roadslam::Scan> sweeps;
  while (auto s = src.next()) sweeps.push_back(std::move(*s));
  EXPECT_TRUE(src.finished());
  EXPECT_EQ(src.describe(), "pcap:" + file.string());
  ASSERT_EQ(sweeps.size(), 4u);  // partial lead-in, 2 complete, partial lead-out
  EXPECT_TRUE(sweeps.front().partial);
  EXPECT_TRUE(sweeps.back().partial);
  uint64_t total = 0;
  double worst = 0;
  for (const auto& s : sweeps) {
    total += s.points.size();
    for (const auto& q : s.points)
      worst = std::max(worst, distanceToBoundary(p, q.x + p.sensor_x_m, q.y + p.sensor_y_m,
                                                 q.z + p.sensor_z_m));
  }
  // One complete turn = 76 packets x 24 firings x 16 lasers, every beam returning.
  EXPECT_EQ(sweeps[1].points.size(), 76u * 24u * 16u);
  EXPECT_EQ(sweeps[2].points.size(), 76u * 24u * 16u);
  EXPECT_EQ(total, 3u * 76u * 24u * 16u);
  // Range quantisation (2 mm) and the 0.01 deg azimuth encoding at <= 9.4 m: well under 2 cm.
  EXPECT_LT(worst, 0.02);
  EXPECT_EQ(src.takeGpsFixes().size(), 3u);
  EXPECT_NEAR(sweep_source.sweepStats().sweepRate_hz(), 1.0 / (76 * 1327.104e-6), 1e-3);
  for (std::size_t i = 1; i < sweeps.size(); ++i) EXPECT_GT(sweeps[i].stamp_s, sweeps[i - 1].stamp_s);
  fs::remove(file);
}

// A consumer that never takes the GPS fixes (the jobs) keeps only the newest ones.
TEST(SweepSource, UntakenGpsFixesAreCappedKeepingTheNewest) {
  BoxRoomParams p;
  p.revolutions = 3;
  const fs::path file = boxRoomFile(p, "sweep_gps_cap_");
  std::vector<roadslam::gnss::GnssFix> all;
  {
    SweepSource ref(std::make_unique<PcapPacketSource>(file.string()));
    while (ref.next()) {
    }
    all = ref.takeGpsFixes();
  }
  ASSERT_EQ(all.size(), 3u);
  SweepSource capped(std::make_unique<PcapPacketSource>(file.string()));
  capped.setMaxPendingGpsFixes(2);
  while (capped.next()) {
  }
  const auto kept = capped.takeGpsFixes();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].t_receive_s, all[1].t_receive_s);
  EXPECT_EQ(kept[1].t_receive_s, all[2].t_receive_s);
  EXPECT_EQ(capped.sweepStats().gps_fixes_dropped, 1u);
  fs::remove(file);
}

// openScanSource: a pcap opens as a SweepSource whose counters are the assembler's and the packet
// source's; what it refuses is named.
TEST(ScanSource, OpensAPcapByItsPathAndCountsPacketsAndSweeps) {
  BoxRoomParams p;
  p.revolutions = 3;
  const fs::path file = boxRoomFile(p, "scan_source_open_");
  mrpt::config::CConfigFileMemory cfg;
  auto src = openScanSource(file.string(), cfg);
  size_t n = 0;
  while (src->next()) ++n;
  EXPECT_TRUE(src->finished());
  EXPECT_EQ(src->describe(), "pcap:" + file.string());
  EXPECT_EQ(src->sizeHint(), 0u);
  EXPECT_TRUE(src->errorMessage().empty());
  EXPECT_TRUE(src->warnings().empty());
  const ScanSourceStats st = src->stats();
  EXPECT_EQ(n, 4u);
  EXPECT_EQ(st.sweeps, 4u);
  EXPECT_EQ(st.partial_sweeps, 2u);
  PcapPacketSource packets(file.string());
  while (packets.next()) {
  }
  EXPECT_EQ(st.packets, packets.stats().packets);
  EXPECT_GE(st.packets, 3u * 76u);
  EXPECT_EQ(st.malformed_packets, 0u);

  EXPECT_THROW(openScanSource(file.string() + ".missing", cfg), std::runtime_error);
  EXPECT_THROW(openScanSource(file.string(), cfg, "times.txt"), std::runtime_error);
  const fs::path other = fs::temp_directory_path() / ("scan_source_open_" + std::to_string(getpid()) + ".txt");
  { std::ofstream(other) << "x"; }
  try {
    openScanSource(other.string(), cfg);
    ADD_FAILURE() << "an unknown kind opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown kind"), std::string::npos) << e.what();
  }
  fs::remove(other);
  fs::remove(file);
}

// A roadslam-grab session whose first segment a crash cut short: reading goes on with the next one,
// and the damage counts the sweeps before it (those of the cut segment read alone), not all of them.
TEST(ScanSource, DamageInASessionCountsTheSweepsBeforeIt) {
  BoxRoomParams p;
  p.revolutions = 6;
  const fs::path pcap = boxRoomFile(p, "session_damage_");
  const fs::path dir = fs::temp_directory_path() / ("session_damage_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  convertToRawlog(pcap.string(), (dir / "whole.rawlog").string());
  std::string bytes;
  {
    std::ifstream f(dir / "whole.rawlog", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  fs::create_directories(dir / "session");
  std::ofstream(dir / "session" / "grab_000.rawlog", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  fs::copy_file(dir / "whole.rawlog", dir / "session" / "grab_001.rawlog");
  mrpt::config::CConfigFileMemory cfg;
  const auto count = [&cfg](const fs::path& path) {
    auto src = openScanSource(path.string(), cfg);
    while (src->next()) {
    }
    return std::pair<uint64_t, std::string>(src->stats().sweeps, damageWarning(*src));
  };
  const auto [cut_alone, cut_warning] = count(dir / "session" / "grab_000.rawlog");
  const auto [whole, whole_warning] = count(dir / "whole.rawlog");
  EXPECT_EQ(whole_warning, "");
  ASSERT_NE(cut_warning, "");
  auto session = openScanSource((dir / "session").string(), cfg);
  while (session->next()) {
  }
  EXPECT_EQ(session->sweepsBeforeDamage(), cut_alone);
  EXPECT_GT(session->stats().sweeps, cut_alone + whole / 2);
  EXPECT_EQ(damageWarning(*session).rfind("input damaged, " + std::to_string(cut_alone) + " sweeps read before it, and " +
                                              std::to_string(session->stats().sweeps - cut_alone) + " after it: ",
                                          0),
            0u)
      << damageWarning(*session);
  fs::remove_all(dir);
  fs::remove(pcap);
}

TEST(SweepSource, LiveUdpReplayGivesTheSameSweepsAsThePcap) {
  BoxRoomParams p;
  p.revolutions = 3;
  const fs::path file = boxRoomFile(p, "sweep_live_");
  std::vector<roadslam::velodyne::RawPacket> packets;
  std::vector<std::size_t> expected;
  {
    PcapPacketSource pcap(file.string());
    while (auto pkt = pcap.next()) packets.push_back(*pkt);
    SweepSource ref(std::make_unique<PcapPacketSource>(file.string()));
    while (auto s = ref.next()) expected.push_back(s->points.size());
  }
  UdpReceiver::Params up;
  up.ports = {0, 0};
  up.bind_address = "127.0.0.1";
  up.poll_timeout_s = 0.05;
  auto rx = std::make_unique<UdpReceiver>(up);
  const uint16_t data_port = rx->dataPort(), pos_port = rx->positionPort();
  SweepSource live(std::move(rx));
  std::thread sender([&] {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (std::size_t i = 0; i < packets.size(); ++i) {
      to.sin_port = htons(packets[i].dst_port == 2368 ? data_port : pos_port);
      sendto(fd, packets[i].payload.data(), packets[i].payload.size(), 0,
             reinterpret_cast<sockaddr*>(&to), sizeof to);
      if (i % 10 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    close(fd);
  });
  // A live stream never ends: the sweep in progress at the end stays open.
  std::vector<std::size_t> got;
  int idle = 0;
  while (got.size() + 1 < expected.size() && idle < 40) {
    auto s = live.next();
    s ? got.push_back(s->points.size()) : void(++idle);
  }
  sender.join();
  ASSERT_EQ(got.size() + 1, expected.size());
  EXPECT_FALSE(live.finished()) << "a live source never finishes";
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], expected[i]) << "sweep " << i;
  EXPECT_EQ(live.packets().stats().kernel_drops, 0u);
  fs::remove(file);
}

// The VeloView VLP-16 capture reports the HDL-32E product byte (../shared/data README): on model =
// auto it is decoded by its packets' layout, as the same capture with the model set to vlp16 (the
// VeloView oracle test's setting), and the source says why and warns.
TEST(SweepSource, RealVlp16WithTheHdl32ByteDecodesAsTheVlp16ItIs) {
  const std::string pcap =
      std::string(ROADSLAM_SHARED_DATA) + "/velodyne/veloview_vlp-16-test-90deg-1-50-frames.pcap";
  if (!fs::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  struct Run {
    std::unique_ptr<SweepSource> src;
    std::vector<size_t> sizes;  // points per sweep
  };
  auto run = [&](roadslam::velodyne::Model model) {
    roadslam::velodyne::DecoderParams p;
    p.model = model;
    Run r{std::make_unique<SweepSource>(std::make_unique<PcapPacketSource>(pcap), p), {}};
    while (auto s = r.src->next()) r.sizes.push_back(s->points.size());
    return r;
  };
  const Run by_layout = run(roadslam::velodyne::Model::Unknown), forced = run(roadslam::velodyne::Model::VLP16);
  EXPECT_EQ(by_layout.sizes.size(), 52u);  // VeloView's frame_count
  EXPECT_EQ(by_layout.sizes, forced.sizes);
  ASSERT_TRUE(by_layout.src->lidarModel());
  EXPECT_EQ(by_layout.src->lidarModel()->model, "VLP-16");
  EXPECT_EQ(by_layout.src->lidarModel()->source, "packet layout");
  ASSERT_EQ(by_layout.src->warnings().size(), 1u);
  EXPECT_NE(by_layout.src->warnings()[0].find("but product byte 0x21 says HDL-32E; decoding as VLP-16; set [velodyne] "
                                          "model = hdl32 to force"),
            std::string::npos);
  EXPECT_EQ(forced.src->lidarModel()->source, "ini");
  EXPECT_TRUE(forced.src->warnings().empty());
  EXPECT_EQ(by_layout.src->stats().packets, forced.src->stats().packets);
}
