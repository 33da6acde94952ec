#pragma once
// Helpers shared by the grabber tests: simulated packets, a paced UDP sender, temp folders,
// ini text for a grabber on kernel-chosen loopback ports, rawlog read-back.
#include <arpa/inet.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <mrpt/config/CConfigFileMemory.h>

#include "roadslam/grabber/params.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sources/rawlog_source.h"

namespace roadslam::grabber::test {

struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag)
      : path(std::filesystem::temp_directory_path() / ("roadslam_grab_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string str() const { return path.string(); }
};

struct SimPacket {
  double capture_s;
  uint16_t port;  // 2368 data, 8308 position
  std::vector<uint8_t> bytes;
};

struct VectorSink : sim::PacketSink {
  std::vector<SimPacket> packets;
  void packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) override {
    packets.push_back({capture_s, port, std::vector<uint8_t>(data, data + size)});
  }
};

/// \p duration_s of the urban loop (fixed seed 1), data and position packets in capture order.
inline const std::vector<SimPacket>& simPackets(double duration_s) {
  static std::vector<std::pair<double, std::vector<SimPacket>>> cache;
  for (const auto& c : cache)
    if (c.first == duration_s) return c.second;
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.duration_s = duration_s;
  p.seed = 1;
  sim::Simulator s(p);
  VectorSink sink;
  s.run(sink);
  cache.emplace_back(duration_s, std::move(sink.packets));
  return cache.back().second;
}

inline std::vector<std::vector<uint8_t>> dataPayloads(const std::vector<SimPacket>& v) {
  std::vector<std::vector<uint8_t>> out;
  for (const auto& p : v)
    if (p.port == 2368) out.push_back(p.bytes);
  return out;
}

/// Sends packets to 127.0.0.1 (data -> data_port, position -> position_port) paced on their
/// capture times / speed, from \p src_addr. Returns the number of datagrams sent.
inline std::size_t sendPaced(const std::vector<SimPacket>& pkts, uint16_t data_port, uint16_t position_port,
                             double speed, const char* src_addr = "127.0.0.1",
                             std::atomic<std::size_t>* progress = nullptr) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in src{};
  src.sin_family = AF_INET;
  ::inet_pton(AF_INET, src_addr, &src.sin_addr);
  ::bind(fd, reinterpret_cast<sockaddr*>(&src), sizeof(src));
  sockaddr_in dst{};
  dst.sin_family = AF_INET;
  dst.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t sent = 0;
  for (const auto& p : pkts) {
    const double due = (p.capture_s - pkts.front().capture_s) / speed;
    std::this_thread::sleep_until(t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                           std::chrono::duration<double>(due)));
    dst.sin_port = htons(p.port == 2368 ? data_port : position_port);
    if (::sendto(fd, p.bytes.data(), p.bytes.size(), 0, reinterpret_cast<sockaddr*>(&dst), sizeof(dst)) ==
        ssize_t(p.bytes.size()))
      ++sent;
    if (progress) progress->store(sent);
  }
  ::close(fd);
  return sent;
}

/// Grabber ini for one sensor on kernel-chosen ports (0), no sidecar changes; \p extra is
/// appended to [grab] and \p sensor_extra to [lidar].
inline std::string testIni(const std::string& extra = "", const std::string& sensor_extra = "") {
  return "[grab]\nsensors = lidar\nflush_period_ms = 200\nstatus_period_ms = 200\n" + extra +
         "\n[lidar]\ndata_port = 0\nposition_port = 0\nmodel = vlp16\nsensor_label = LIDAR\n"
         "silent_after_ms = 400\n" + sensor_extra + "\n";
}

inline GrabParams paramsFromText(const std::string& text) {
  mrpt::config::CConfigFileMemory cfg(text);
  GrabParams p;
  p.loadFromConfigFile(cfg);
  return p;
}

/// Every data payload of a rawlog, in order; \p scans / \p error receive the counts and message.
inline std::vector<std::vector<uint8_t>> readRawlog(const std::string& path, std::size_t* scans = nullptr,
                                                    std::string* error = nullptr) {
  sources::RawlogPacketSource src(path);
  std::vector<std::vector<uint8_t>> out;
  while (!src.finished()) {
    auto p = src.next();
    if (p && p->payload.size() == 1206) out.push_back(p->payload);
  }
  if (scans) *scans = src.scansRead();
  if (error) *error = src.errorMessage();
  return out;
}

/// Paths of \p dir/<stem>_NNN<ext> in index order.
inline std::vector<std::string> segmentFiles(const std::string& dir, const std::string& stem, const std::string& ext) {
  std::vector<std::string> out;
  for (int i = 0;; ++i) {
    char idx[16];
    std::snprintf(idx, sizeof(idx), "_%03d", i);
    const std::string p = dir + "/" + stem + idx + ext;
    if (!std::filesystem::exists(p)) break;
    out.push_back(p);
  }
  return out;
}

/// Sends \p n frames over \p fd 1 ms apart: ids 0x100 + i; every 40th an error frame, the 100th
/// a bus-off error frame. Returns how many were error frames (\p bus_off: bus-off ones).
inline std::size_t sendCan(int fd, int n, std::size_t* bus_off) {
  std::size_t errors = 0;
  *bus_off = 0;
  for (int i = 0; i < n; ++i) {
    can_frame f{};
    f.can_id = canid_t(0x100 + i % 0x400);
    f.len = 8;
    for (int b = 0; b < 8; ++b) f.data[b] = uint8_t(i + b);
    if (i == 100) {
      f.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
      ++errors;
      ++*bus_off;
    } else if (i % 40 == 39) {
      f.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
      ++errors;
    }
    if (::send(fd, &f, sizeof(f), 0) != ssize_t(sizeof(f))) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return errors;
}

inline std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace roadslam::grabber::test
