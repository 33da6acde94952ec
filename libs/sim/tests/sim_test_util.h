#pragma once
// Helpers shared by the simulator's oracle tests.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roadslam/sim/simulator.h"

namespace roadslam::sim::test {

inline std::string iniPath(const std::string& name) {
  return std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + name;
}

/// A fresh folder under the system temp dir, removed by the destructor.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag)
      : path(std::filesystem::temp_directory_path() / ("roadslam_sim_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string str() const { return path.string(); }
};

inline std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct CapturedPacket {
  double capture_s;
  uint16_t port;
  std::vector<uint8_t> bytes;
};

/// Keeps every payload in memory.
struct VectorSink : PacketSink {
  std::vector<CapturedPacket> packets;
  void packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) override {
    packets.push_back({capture_s, port, std::vector<uint8_t>(data, data + size)});
  }
};

}  // namespace roadslam::sim::test
