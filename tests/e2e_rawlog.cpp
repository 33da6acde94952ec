// End-to-end: the roadslam-rawlog binary on the bundled box room (oracle: the generator's own
// analytic count) and on MRPT's real VLP-16 capture (oracle: its MANIFEST and MRPT's unit test),
// convert -> info consistency, MRPT reading our rawlog, damaged recordings read up to the damage,
// and bad inputs failing with one line.
#include <gtest/gtest.h>

#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/CRawlog.h>
#include <arpa/inet.h>
#include <fmt/core.h>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "roadslam/pcap/pcap_writer.h"
#include "roadslam/sources/boxroom.h"
#include "roadslam/sources/pcap_source.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kBox = std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap";
const std::string kMrpt =
    std::string(ROADSLAM_SHARED_DATA) + "/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap";

struct AppRun {
  int exit_code = -1;
  std::string out, err;
};

fs::path tmpDir() {
  const fs::path d = fs::temp_directory_path() / ("roadslam_e2e_rawlog_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

AppRun run(const std::string& args) {
  const fs::path o = tmpDir() / "stdout.txt", e = tmpDir() / "stderr.txt";
  const std::string cmd = std::string(ROADSLAM_RAWLOG_BIN) + " " + args + " >" + o.string() +
                          " 2>" + e.string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  AppRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(o);
  r.err = slurp(e);
  return r;
}

json info(const std::string& file, const std::string& extra = "") {
  const AppRun r = run("info " + file + " --json " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return json::parse(r.out);
}

void expectOneLineFailureNaming(const AppRun& r, const std::string& name) {
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(name), std::string::npos) << "stderr: " << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line expected: " << r.err;
}

}  // namespace

TEST(RawlogApp, HelpExitsZero) {
  const AppRun r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("convert"), std::string::npos);
  EXPECT_NE(r.out.find("info"), std::string::npos);
}

TEST(RawlogApp, BoxRoomInfoMatchesTheGeneratorsAnalyticCount) {
  ASSERT_TRUE(fs::exists(kBox)) << kBox;
  // The generator's own oracle (same default parameters as the bundled file).
  const auto expected = roadslam::sources::writeBoxRoomPcap((tmpDir() / "box.pcap").string());
  const json j = info(kBox);
  EXPECT_EQ(j["sweeps"], expected.complete_sweeps);
  EXPECT_EQ(j["partial_sweeps"], expected.partial_sweeps);
  EXPECT_EQ(j["points"], expected.points);  // every beam hits a wall: 16 returns per firing
  EXPECT_EQ(j["packets"], expected.data_packets);
  EXPECT_EQ(j["gps_fixes"], expected.position_packets);
  EXPECT_EQ(j["malformed_packets"], 0);
  EXPECT_EQ(j["missing_packets"], 0);
  EXPECT_NEAR(j["duration_s"].get<double>(), expected.duration_s, 2e-6);
  EXPECT_NEAR(j["sweeps_per_s"].get<double>(), 1.0 / (76 * 1327.104e-6), 0.01);
}

TEST(RawlogApp, MrptSampleInfoMatchesManifest) {
  if (!fs::exists(kMrpt)) GTEST_SKIP() << "missing " << kMrpt;
  const json j = info(kMrpt, "--model vlp16");
  EXPECT_EQ(j["packets"], 293);          // MANIFEST: 293 data packets
  EXPECT_EQ(j["position_packets"], 57);  // MANIFEST: 57 position packets
  EXPECT_GT(j["gps_fixes"].get<int>(), 0);
  EXPECT_EQ(j["malformed_packets"], 0);
  // MRPT's test expects 4 scans: CVelodyneScanner emits a scan at every azimuth wrap (so the
  // leading partial one counts) and loses the one in progress at end of file.
  EXPECT_EQ(j["sweeps"].get<int>() + j["partial_sweeps"].get<int>() - 1, 4);
  EXPECT_NEAR(j["duration_s"].get<double>(), 0.39, 0.01);  // MANIFEST: 0.39 s
  EXPECT_NEAR(j["sweeps_per_s"].get<double>(), 10.0, 0.2);  // MANIFEST: 10 Hz
}

TEST(RawlogApp, OtherRealCapturesMatchTheirOracles) {
  const std::string dir = std::string(ROADSLAM_SHARED_DATA) + "/velodyne/";
  const std::string hdl32 = dir + "mrpt_sample_velodyne_hdl32.pcap";
  const std::string vlp16 = dir + "veloview_vlp-16-test-90deg-1-50-frames.pcap";
  const std::string monterey = dir + "veloview_monterey-first-100-packets.pcap";
  if (!fs::exists(hdl32) || !fs::exists(vlp16) || !fs::exists(monterey))
    GTEST_SKIP() << "missing one of " << hdl32 << ", " << vlp16 << ", " << monterey;
  // MRPT unit test sample_hdl32_dataset: 3 scans (wrap-closed sweeps, see above); 500 packets.
  const json h = info(hdl32, "--model hdl32");
  EXPECT_EQ(h["packets"], 500);
  EXPECT_EQ(h["sweeps"].get<int>() + h["partial_sweeps"].get<int>() - 1, 3);
  EXPECT_EQ(h["missing_packets"], 0);
  // VeloView vlp-16.test: frame_count 52 (partial first/last frames count); 1,902 data packets.
  // Its product byte says HDL-32E: decoded by its layout, it is the VLP-16 the model forced gives
  // (nothing "missing", the same points); forced to the byte's HDL-32E, every step is a gap.
  const json v = info(vlp16, "--model vlp16");
  EXPECT_EQ(v["sweeps"].get<int>() + v["partial_sweeps"].get<int>(), 52);
  EXPECT_EQ(v["packets"], 1902);
  EXPECT_EQ(v["missing_packets"], 0);
  EXPECT_EQ(v["lidar_model_source"], "ini");
  EXPECT_NEAR(v["sweeps_per_s"].get<double>(), 20.0, 0.2);  // MANIFEST: 20 Hz
  const json by_layout = info(vlp16);
  EXPECT_EQ(by_layout["lidar_model"], "VLP-16");
  EXPECT_EQ(by_layout["lidar_model_source"], "packet layout");
  EXPECT_EQ(by_layout["model"], "vlp16");
  EXPECT_EQ(by_layout["missing_packets"], 0);
  EXPECT_EQ(by_layout["points"], v["points"]);
  ASSERT_EQ(by_layout["warnings"].size(), 1u);
  EXPECT_NE(by_layout["warnings"][0].get<std::string>().find("but product byte 0x21 says HDL-32E; decoding as VLP-16"),
            std::string::npos);
  EXPECT_GT(info(vlp16, "--model hdl32")["missing_packets"].get<int>(), 1000);
  // VeloView monterey.test: frame_count 19; TestPositionReader: 299 position packets.
  const json m = info(monterey);
  EXPECT_EQ(m["sweeps"].get<int>() + m["partial_sweeps"].get<int>(), 19);
  EXPECT_EQ(m["packets"], 2702);
  EXPECT_EQ(m["gps_fixes"], 299);
  EXPECT_EQ(m["model"], "hdl32");
  EXPECT_EQ(m["lidar_model"], "HDL-32E");
  EXPECT_EQ(m["lidar_model_source"], "product byte");
  EXPECT_EQ(m["warnings"].size(), 0u);
}

TEST(RawlogApp, ConvertThenInfoGivesTheSameCountsAndMrptReadsIt) {
  for (const std::string& in : {kBox, kMrpt}) {
    if (!fs::exists(in)) continue;
    const fs::path out = tmpDir() / (fs::path(in).stem().string() + ".rawlog");
    const AppRun c = run("convert " + in + " " + out.string());
    ASSERT_EQ(c.exit_code, 0) << c.err;
    const json a = info(in), b = info(out.string());
    for (const char* key : {"sweeps", "partial_sweeps", "packets", "points", "gps_fixes"})
      EXPECT_EQ(a[key], b[key]) << in << " key " << key;
    EXPECT_EQ(b["format"], "rawlog");
    // The configuration used is written next to the output (STYLE.md rule 4).
    const std::string used = slurp(out.string() + ".ini");
    EXPECT_NE(used.find("[velodyne]"), std::string::npos) << used;
    EXPECT_NE(used.find("[rawlog]"), std::string::npos) << used;

    mrpt::obs::CRawlog rawlog;  // MRPT's own loader: RawLogViewer / rawlog-edit use it
    ASSERT_TRUE(rawlog.loadFromRawLogFile(out.string()));
    std::size_t scans = 0, packets = 0, gps = 0;
    mrpt::Clock::time_point last{};
    for (std::size_t i = 0; i < rawlog.size(); ++i) {
      auto o = rawlog.getAsObservation(i);
      EXPECT_GE(o->timestamp, last) << in << ": observations in time order, record " << i;
      last = o->timestamp;
      if (auto v = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(o)) {
        ++scans;
        packets += v->scan_packets.size();
      }
      if (std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(o)) ++gps;
    }
    EXPECT_EQ(scans, a["sweeps"].get<std::size_t>() + a["partial_sweeps"].get<std::size_t>());
    EXPECT_EQ(packets, a["packets"].get<std::size_t>());
    EXPECT_EQ(gps, a["gps_fixes"].get<std::size_t>());
  }
}

namespace {
uint16_t freeUdpPort() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  close(fd);
  return ntohs(a.sin_port);
}
}  // namespace

TEST(RawlogApp, RecordCapturesLiveLoopbackTrafficThatInfoReads) {
  ASSERT_TRUE(fs::exists(kBox)) << kBox;
  std::vector<roadslam::velodyne::RawPacket> packets;
  {
    roadslam::sources::PcapPacketSource src(kBox);
    while (auto p = src.next()) packets.push_back(*p);
  }
  const uint16_t data_port = freeUdpPort(), pos_port = freeUdpPort();
  const fs::path out = tmpDir() / "live.pcap";
  constexpr int kWanted = 300;
  std::atomic<bool> done{false};
  AppRun rec;
  std::thread app([&] {
    rec = run(fmt::format("record {} --bind 127.0.0.1 --port {} --position-port {} --packets {} --duration 20",
                  out.string(), data_port, pos_port, kWanted));
    done = true;
  });
  // The app binds at its own pace: send the box room over and over until it has enough.
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (std::size_t i = 0; !done; ++i) {
    const auto& p = packets[i % packets.size()];
    to.sin_port = htons(p.dst_port == 2368 ? data_port : pos_port);
    sendto(fd, p.payload.data(), p.payload.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
    if (i % 10 == 0) std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  close(fd);
  app.join();
  ASSERT_EQ(rec.exit_code, 0) << rec.err;
  EXPECT_NE(rec.out.find(fmt::format("{} packets", kWanted)), std::string::npos) << rec.out;
  const std::string used = slurp(out.string() + ".ini");
  EXPECT_NE(used.find(fmt::format("data_port = {}", data_port)), std::string::npos) << used;
  // Recorded on the standard ports whatever the live ones: info reads it as any capture.
  const json j = info(out.string());
  EXPECT_EQ(j["packets"].get<int>() + j["position_packets"].get<int>(), kWanted);
  EXPECT_EQ(j["malformed_packets"], 0);
  EXPECT_GT(j["points"].get<int>(), 0);

  const AppRun none = run(fmt::format("record {} --bind 127.0.0.1 --port {} --position-port {} --duration 0.2",
                              (tmpDir() / "none.pcap").string(), freeUdpPort(), freeUdpPort()));
  expectOneLineFailureNaming(none, (tmpDir() / "none.pcap").string());
  EXPECT_FALSE(fs::exists(tmpDir() / "none.pcap"));
}

// Ctrl-C (common/stop_signal.h) ends an unlimited recording cleanly: exit 0, the summary line,
// a complete capture that info reads, no temporary file left.
TEST(RawlogApp, CtrlCEndsARecordingWithACompleteCapture) {
  ASSERT_TRUE(fs::exists(kBox)) << kBox;
  std::vector<roadslam::velodyne::RawPacket> packets;
  {
    roadslam::sources::PcapPacketSource src(kBox);
    while (auto p = src.next()) packets.push_back(*p);
  }
  const uint16_t data_port = freeUdpPort(), pos_port = freeUdpPort();
  const fs::path out = tmpDir() / "sigint.pcap", o = tmpDir() / "sigint.out", e = tmpDir() / "sigint.err";
  const std::string cmd = fmt::format("exec {} record {} --bind 127.0.0.1 --port {} --position-port {} --duration 30 >{} 2>{} </dev/null",
                                      ROADSLAM_RAWLOG_BIN, out.string(), data_port, pos_port, o.string(), e.string());
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Send for a while (the app binds at its own pace), then Ctrl-C it.
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; std::chrono::steady_clock::now() - t0 < std::chrono::milliseconds(1500); ++i) {
    const auto& p = packets[i % packets.size()];
    to.sin_port = htons(p.dst_port == 2368 ? data_port : pos_port);
    sendto(fd, p.payload.data(), p.payload.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
    if (i % 10 == 0) std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  close(fd);
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string err = slurp(e), stdout_text = slurp(o);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0) << "\n" << err;
  EXPECT_EQ(WEXITSTATUS(status), 0) << err;
  EXPECT_NE(stdout_text.find(out.string() + ": "), std::string::npos) << stdout_text;
  const json j = info(out.string());
  EXPECT_GT(j["packets"].get<int>(), 0);
  EXPECT_EQ(j["malformed_packets"], 0);
  for (const auto& entry : fs::directory_iterator(tmpDir()))
    EXPECT_EQ(entry.path().string().find(out.string() + ".tmp"), std::string::npos) << entry.path();
}

// A capture cut mid-record (a power cut) reads as the whole records before the cut: info and convert
// give the figures of the pcap made of those records alone (cut at the record boundary, by the
// format: 24-byte file header, 16-byte record headers with the captured length at byte 8), exit 0,
// and state the damage on one line of stderr, in roadslam-map's words. A rawlog cut in half too.
TEST(RawlogApp, DamagedRecordingsAreReadUpToTheDamage) {
  const fs::path d = tmpDir();
  ASSERT_TRUE(fs::exists(kBox)) << kBox;
  const std::string bytes = slurp(kBox);
  const std::size_t cut = 100000;  // mid-record
  std::size_t whole_end = 24;
  for (;;) {
    uint32_t incl = 0;
    std::memcpy(&incl, bytes.data() + whole_end + 8, 4);
    if (whole_end + 16 + incl > cut) break;
    whole_end += 16 + incl;
  }
  ASSERT_LT(whole_end, cut);
  const std::string truncated = (d / "truncated.pcap").string(), clean = (d / "clean.pcap").string();
  std::ofstream(truncated, std::ios::binary).write(bytes.data(), cut);
  std::ofstream(clean, std::ios::binary).write(bytes.data(), std::streamsize(whole_end));

  const AppRun r = run("info " + truncated + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line expected: " << r.err;
  EXPECT_EQ(r.err.rfind("roadslam-rawlog: warning: input damaged, ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(truncated), std::string::npos) << r.err;
  const json damaged = json::parse(r.out), whole = info(clean);
  EXPECT_EQ(damaged["damage"].get<std::string>() + "\n", r.err.substr(std::string("roadslam-rawlog: warning: ").size()));
  EXPECT_EQ(whole["damage"], "");
  for (const char* k : {"packets", "sweeps", "partial_sweeps", "points", "position_packets"}) EXPECT_EQ(damaged[k], whole[k]) << k;
  const auto sweeps = damaged["sweeps"].get<int>() + damaged["partial_sweeps"].get<int>();
  EXPECT_NE(r.err.find(fmt::format("damaged, {} sweeps read before it: ", sweeps)), std::string::npos) << r.err;

  const AppRun c = run("convert " + truncated + " " + (d / "truncated.rawlog").string());
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.err, r.err);
  EXPECT_EQ(info((d / "truncated.rawlog").string())["packets"], whole["packets"]);

  const std::string cut_rawlog = (d / "cut.rawlog").string();
  {
    ASSERT_EQ(run("convert " + kBox + " " + (d / "whole.rawlog").string()).exit_code, 0);
    const std::string rawlog = slurp(d / "whole.rawlog");
    std::ofstream(cut_rawlog, std::ios::binary).write(rawlog.data(), std::streamsize(rawlog.size() / 2));
  }
  const AppRun rc = run("info " + cut_rawlog + " --json");
  EXPECT_EQ(rc.exit_code, 0) << rc.err;
  EXPECT_EQ(rc.err.rfind("roadslam-rawlog: warning: input damaged, ", 0), 0u) << rc.err;
  EXPECT_NE(rc.err.find(cut_rawlog + ": truncated record at uncompressed byte "), std::string::npos) << rc.err;
  EXPECT_GT(json::parse(rc.out)["packets"].get<int>(), 0);
  EXPECT_LT(json::parse(rc.out)["packets"].get<int>(), info((d / "whole.rawlog").string())["packets"].get<int>());
}

TEST(RawlogApp, BadInputsFailWithOneLineNamingTheFile) {
  const fs::path d = tmpDir();
  const std::string missing = (d / "missing.pcap").string();
  expectOneLineFailureNaming(run("info " + missing), missing);
  expectOneLineFailureNaming(run("convert " + missing + " " + (d / "x.rawlog").string()), missing);
  EXPECT_FALSE(fs::exists(d / "x.rawlog"));

  const std::string empty = (d / "empty.pcap").string();
  std::ofstream(empty).close();
  expectOneLineFailureNaming(run("info " + empty), empty);

  const std::string text = (d / "notes.txt").string();
  std::ofstream(text) << "not a recording\n";
  expectOneLineFailureNaming(run("info " + text), text);

  const std::string dns = (d / "dns.pcap").string();
  {
    roadslam::pcap::PcapWriter w(dns);
    const std::vector<uint8_t> payload(80, 3);
    for (int i = 0; i < 10; ++i) w.writeUdp(100.0 + i, 5353, 53, payload.data(), payload.size());
    w.close();
  }
  expectOneLineFailureNaming(run("info " + dns), dns);
  expectOneLineFailureNaming(run("convert " + dns + " " + (d / "dns.rawlog").string()), dns);
  EXPECT_FALSE(fs::exists(d / "dns.rawlog"));

  const std::string unwritable = "/nonexistent-dir-roadslam/out.rawlog";
  expectOneLineFailureNaming(run("convert " + kBox + " " + unwritable), unwritable);

  const AppRun bad_model = run("info " + kBox + " --model hdl64");
  EXPECT_NE(bad_model.exit_code, 0);
}
