// NMEA sources: a serial port (a pseudo-terminal stands in for the receiver, the same termios read
// loop) and the log replay; what recordNmea writes replays to the same lines, and its rawlog holds
// one CObservationGPS per valid epoch.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CRawlog.h>
#include <pty.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "roadslam/gnss/nmea.h"
#include "roadslam/sources/nmea_source.h"

using namespace roadslam;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> epochSentences(int k) {
  gnss::GnssFix f;
  f.t_receiver_s = 1700000000.0 + k;
  f.time_of_day_s = std::fmod(f.t_receiver_s, 86400.0);
  f.has_position = true;
  f.position = {48.137 + 1e-5 * k, 11.575, 500};
  f.quality = 1;
  f.satellites = 9;
  f.hdop = 1.1;
  f.speed_mps = 1.0;
  f.course_rad = 0.5;
  return {gnss::encodeRmc(f), gnss::encodeGga(f)};
}
}  // namespace

TEST(NmeaSource, SerialPtyToLogAndRawlogAndReplay) {
  int master = -1, slave = -1;
  char name[128];
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
  sources::SerialNmeaSource serial(name, 115200);
  const fs::path dir = fs::temp_directory_path() / "roadslam_nmea_source";
  fs::create_directories(dir);
  // the "receiver": 5 epochs, CRLF line ends, one line cut in two writes, one corrupted line
  std::thread rx([&] {
    std::string all;
    for (int k = 0; k < 5; ++k)
      for (const auto& s : epochSentences(k)) all += s + "\r\n";
    all += "$GPGGA,garbage*00\r\n";
    const size_t half = all.size() / 2;
    (void)!::write(master, all.data(), half);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    (void)!::write(master, all.data() + half, all.size() - half);
  });
  const auto s = sources::recordNmea(serial, (dir / "rx.nmea").string(), (dir / "rx.rawlog").string(), 11);
  rx.join();
  ::close(slave);
  ::close(master);
  EXPECT_EQ(s.lines, 11u);
  EXPECT_EQ(s.epochs, 5u);
  // the log replays to the same sentences with their receive times
  sources::NmeaLogReplaySource replay((dir / "rx.nmea").string());
  sources::NmeaLine l;
  std::vector<std::string> got;
  while (replay.read(l, 10) == sources::NmeaRead::Line) {
    EXPECT_GT(l.receive_s, 1.6e9);
    got.push_back(l.text);
  }
  ASSERT_EQ(got.size(), 11u);
  EXPECT_EQ(got[0], epochSentences(0)[0]);
  EXPECT_EQ(got[10], "$GPGGA,garbage*00");
  const auto log = gnss::readNmeaLog((dir / "rx.nmea").string());
  EXPECT_EQ(log.fixes.size(), 5u);
  EXPECT_EQ(log.counters.bad_checksum, 1u);
  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile((dir / "rx.rawlog").string()));
  EXPECT_EQ(rawlog.size(), 5u);
}

TEST(NmeaSource, ReplayIsPacedAndMissingDeviceIsNamed) {
  const fs::path p = fs::temp_directory_path() / "roadslam_nmea_paced.nmea";
  std::ofstream(p) << "100.0 " << epochSentences(0)[0] << "\n100.2 " << epochSentences(1)[0] << "\n";
  sources::NmeaLogReplaySource replay(p.string(), 1.0);
  sources::NmeaLine l;
  const auto t0 = std::chrono::steady_clock::now();
  int n = 0;
  while (replay.read(l, 50) != sources::NmeaRead::End) n += l.text.empty() ? 0 : 1;
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(s, 0.18);
  EXPECT_LT(s, 1.0);
  EXPECT_DOUBLE_EQ(l.receive_s, 100.2);
  try {
    sources::SerialNmeaSource bad("/dev/nonexistent-gnss", 9600);
    FAIL() << "opened a missing device";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/nonexistent-gnss"), std::string::npos);
  }
  EXPECT_THROW(sources::SerialNmeaSource(p.string(), 12345), std::runtime_error);
}
