// GNSS in the grabber: NMEA from a serial port (a pseudo-terminal stands in for the receiver), from a
// real gpsd daemon reading that pty, and from a log replayed. Oracles: the fixes the test encoded
// (positions, receiver UTC), the host clock around the writes (receive times), the parser's own
// reading of the lossless sidecar, and the time order of the rawlog against the CAN observations.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CRawlog.h>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <pty.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <thread>

#include "grab_test_util.h"
#include "roadslam/gnss/nmea.h"
#include "roadslam/grabber/grabber.h"

using namespace roadslam;
using namespace roadslam::grabber;

namespace {

constexpr double kT0 = 1700000000.0;  // receiver UTC of epoch 0 [s]

gnss::GnssFix fixOf(int k) {
  gnss::GnssFix f;
  f.t_receiver_s = kT0 + 0.2 * k;
  f.time_of_day_s = std::fmod(f.t_receiver_s, 86400.0);
  f.has_position = true;
  f.position = {48.137 + 1e-5 * k, 11.575 - 2e-5 * k, 520.5};
  f.quality = 1;
  f.satellites = 9;
  f.hdop = 0.9;
  f.speed_mps = 10.0;
  f.course_rad = 0.5;
  f.sigma_lat_m = f.sigma_lon_m = 1.0;
  f.sigma_alt_m = 2.0;
  return f;
}

std::string epochText(int k) {
  const gnss::GnssFix f = fixOf(k);
  return gnss::encodeRmc(f) + "\r\n" + gnss::encodeGga(f) + "\r\n" + gnss::encodeGst(f) + "\r\n";
}

struct Pty {
  int master = -1, slave = -1;
  char name[128] = {};
  Pty() { EXPECT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0); }
  ~Pty() {
    ::close(slave);
    ::close(master);
  }
  void write(const std::string& s) const { (void)!::write(master, s.data(), s.size()); }
};

std::vector<mrpt::obs::CObservation::Ptr> observations(const std::string& rawlog) {
  mrpt::obs::CRawlog r;
  EXPECT_TRUE(r.loadFromRawLogFile(rawlog)) << rawlog;
  std::vector<mrpt::obs::CObservation::Ptr> out;
  for (std::size_t i = 0; i < r.size(); ++i) out.push_back(r.getAsObservation(i));
  return out;
}

/// The GNSS epochs of a rawlog; each must be one of fixOf(0..n) (matched by receiver time).
void expectFixesMatch(const std::vector<mrpt::obs::CObservation::Ptr>& obs, double t_lo, double t_hi,
                      std::size_t* count) {
  *count = 0;
  for (const auto& o : obs) {
    auto g = std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(o);
    if (!g) continue;
    ++*count;
    EXPECT_EQ(g->sensorLabel, "GNSS");
    const double t = mrpt::Clock::toDouble(g->timestamp);
    const int k = int(std::lround((t - kT0) / 0.2));
    EXPECT_NEAR(t, fixOf(k).t_receiver_s, 1e-3);  // the receiver's own UTC, not the host's
    ASSERT_TRUE(g->has_GGA_datum());
    const auto& gga = g->getMsgByClass<mrpt::obs::gnss::Message_NMEA_GGA>().fields;
    EXPECT_NEAR(gga.latitude_degrees, fixOf(k).position.lat_deg, 1e-7);
    EXPECT_NEAR(gga.longitude_degrees, fixOf(k).position.lon_deg, 1e-7);
    EXPECT_EQ(gga.fix_quality, 1);
    const double rx = mrpt::Clock::toDouble(g->originalReceivedTimestamp);  // the host clock
    EXPECT_GE(rx, t_lo);
    EXPECT_LE(rx, t_hi);
  }
}

}  // namespace

// Serial: 6 epochs at 5 Hz (the epoch-idle flush closes each), a bad checksum and a no-fix epoch
// on the line, the RAV4 CAN log replayed beside it: the rawlog holds the 6 fixes at their receiver
// time, every observation in host-time order, and the sidecar every line.
TEST(GrabGnss, SerialPtyEpochsInTimeOrderWithCan) {
  const std::string log = std::string(ROADSLAM_SHARED_DATA) + "/can/rav4-2017/rav4_2018-08-02_seg40.candump.log";
  const std::string vini = std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/toyota-rav4-2017.ini";
  const bool with_can = std::filesystem::exists(log);
  Pty pty;
  test::TempDir dir("gnss_serial");
  std::string can = with_can ? "can = can\n" : "";
  std::string can_sec = with_can ? "[can]\nsource = candump\ncandump_file = " + log + "\nvehicle_ini = " + vini + "\n" : "";
  const std::string ini = test::testIni(can + "gnss = gnss\nreorder_window_ms = 1000\n") + can_sec +
                          "[gnss]\nsource = serial\nbaud = 115200\nepoch_idle_ms = 60\ndevice = " + pty.name + "\n";
  Grabber g(test::paramsFromText(ini), dir.str());
  const double t_start = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  g.start();
  for (int k = 0; k < 6; ++k) {
    pty.write(epochText(k));
    if (k == 2) pty.write("$GPGGA,garbage*00\r\n");
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  gnss::GnssFix nofix = fixOf(6);
  nofix.quality = 0;
  nofix.has_position = false;
  pty.write(gnss::encodeGga(nofix) + "\r\n");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  g.stop();
  const double t_end = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const GrabStatus st = g.status();
  EXPECT_EQ(st.gnss.lines, 6u * 3 + 2);
  EXPECT_EQ(st.gnss.epochs, 6u);
  EXPECT_EQ(st.gnss.nmea.bad_checksum, 1u);
  EXPECT_EQ(st.gnss.nmea.no_fix, 1u);
  EXPECT_EQ(st.gnss.split_epochs, 0u);
  EXPECT_EQ(st.gnss.queue_drops, 0u);
  EXPECT_EQ(st.writer.late, 0u);

  const auto obs = observations(dir.str() + "/grab_000.rawlog");
  std::size_t n = 0;
  expectFixesMatch(obs, t_start, t_end, &n);
  EXPECT_EQ(n, 6u);
  // One clock, one order: GNSS by receive time, CAN observations by their (restamped) time.
  double prev = 0;
  std::size_t can_obs = 0;
  for (const auto& o : obs) {
    const bool gps = bool(std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(o));
    const double t = mrpt::Clock::toDouble(o->getOriginalReceivedTimeStamp());  // GPS: receive time
    EXPECT_GE(t, prev) << o->sensorLabel;
    prev = t;
    can_obs += gps ? 0 : 1;
  }
  if (with_can) {
    EXPECT_GT(can_obs, 100u);
  }
  // Lossless sidecar: every line, re-read by the parser to the same fixes and counts.
  const auto side = gnss::readNmeaLog(dir.str() + "/gnss_000.nmea.log");
  EXPECT_EQ(side.counters.lines, st.gnss.lines);
  ASSERT_EQ(side.fixes.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(side.fixes[std::size_t(k)].position.lat_deg, fixOf(k).position.lat_deg, 1e-7);
  EXPECT_EQ(side.counters.bad_checksum, 1u);
  const auto summary = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_EQ(summary["gnss"]["nmea"]["bad checksum"], 1);
  EXPECT_EQ(summary["gnss"]["epochs"], 6);
}

// Replay backend: a log with every kind of bad input goes through counted and named; the sidecar
// is the log itself (restamp off).
TEST(GrabGnss, NmeaLogReplayCountsBadInput) {
  test::TempDir dir("gnss_replay");
  std::string text;
  double rx = kT0 + 0.05;
  auto add = [&](const std::string& line) {
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%.6f ", rx);
    text += stamp + line + "\n";
    rx += 0.01;
  };
  for (int k = 0; k < 4; ++k) {
    for (const auto& s : {gnss::encodeRmc(fixOf(k)), gnss::encodeGga(fixOf(k))}) add(s);
    rx += 0.17;
  }
  add("$GPRMC,not,a,sentence*7F");                          // bad checksum
  add(gnss::nmeaSentence("GPDTM,999,,0.0,N,0.0,E,0.0,999"));  // another datum: the next epoch is dropped
  add(gnss::encodeGga(fixOf(4)));
  add(gnss::nmeaSentence("GPDTM,W84,,0.0,N,0.0,E,0.0,W84"));
  add(gnss::encodeGga(fixOf(30)));  // 5.2 s later: a time jump, kept
  add(gnss::encodeGga(fixOf(31)));
  const std::string path = dir.str() + "/in.nmea";
  std::ofstream(path) << text;
  const std::string ini = test::testIni("gnss = gnss\n") +
                          "[gnss]\nsource = nmea_log\nreplay_speed = 0\nrestamp = false\nnmea_file = " + path + "\n";
  Grabber g(test::paramsFromText(ini), dir.str() + "/out");
  g.start();
  for (int i = 0; i < 100 && !(g.status().gnss.lines == 14u && g.status().writer.gps == 6u); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  g.stop();
  const GrabStatus st = g.status();
  EXPECT_EQ(st.gnss.lines, 14u);
  EXPECT_EQ(st.gnss.nmea.bad_checksum, 1u);
  EXPECT_EQ(st.gnss.nmea.other_datum, 1u);
  EXPECT_EQ(st.gnss.nmea.time_jumps, 1u);
  EXPECT_EQ(st.writer.gps, 6u);  // epochs 0-3, 30, 31
  EXPECT_FALSE(st.gnss.problems.empty());
  EXPECT_EQ(test::readAll(dir.str() + "/out/gnss_000.nmea.log"), text);
  std::size_t n = 0;
  expectFixesMatch(observations(dir.str() + "/out/grab_000.rawlog"), kT0, kT0 + 1, &n);  // log receive times
}

// gpsd for real (Debian gpsd): the daemon reads the pty, the grabber is its client.
TEST(GrabGnss, GpsdRelaysThePtyReceiver) {
  if (!std::filesystem::exists("/usr/sbin/gpsd")) GTEST_SKIP() << "gpsd is not installed (apt install gpsd)";
  Pty pty;
  // a free TCP port for gpsd: bind to 0, read it back, close
  int port = 0;
  {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    port = ntohs(a.sin_port);
    ::close(fd);
  }
  test::TempDir dir("gnss_gpsd");
  const std::string ctl = dir.str() + "/gpsd.sock", port_text = std::to_string(port);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/usr/sbin/gpsd", "gpsd", "-N", "-n", "-b", "-S", port_text.c_str(), "-F", ctl.c_str(), pty.name,
            static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_GT(pid, 0);
  std::atomic<bool> feeding{true};
  std::thread rx([&] {
    for (int k = 0; feeding && k < 200; ++k) {
      pty.write(epochText(k));
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  std::unique_ptr<Grabber> g;
  std::string why;
  const std::string ini = test::testIni("gnss = gnss\n") + "[gnss]\nsource = gpsd\ngpsd_host = 127.0.0.1\ngpsd_port = " +
                          port_text + "\n";
  const double t_start = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  for (int i = 0; i < 50 && !g; ++i) {  // gpsd takes a moment to listen
    try {
      g = std::make_unique<Grabber>(test::paramsFromText(ini), dir.str() + "/out");
    } catch (const std::exception& e) {
      why = e.what();
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  if (g) {
    g->start();
    for (int i = 0; i < 100 && g->status().gnss.epochs < 5; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    g->stop();
  }
  feeding = false;
  rx.join();
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!g) GTEST_SKIP() << "gpsd did not start on " << pty.name << ": " << why;
  const double t_end = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const GrabStatus st = g->status();
  EXPECT_NE(st.gnss.source.find("gpsd:127.0.0.1"), std::string::npos);
  EXPECT_GE(st.gnss.epochs, 5u);
  EXPECT_EQ(st.gnss.nmea.bad_checksum, 0u);
  std::size_t n = 0;
  expectFixesMatch(observations(dir.str() + "/out/grab_000.rawlog"), t_start, t_end, &n);
  EXPECT_EQ(n, st.gnss.epochs);
}
