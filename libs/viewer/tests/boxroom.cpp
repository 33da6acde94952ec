#include "boxroom.h"

#include <unistd.h>

#include "roadslam/sources/recording.h"

namespace fs = std::filesystem;

namespace roadslam::viewer::test {

fs::path tempDir() {
  const fs::path d = fs::temp_directory_path() / ("roadslam_viewer_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

const std::string& boxroomRawlog() {
  static const std::string path = [] {
    const std::string p = (tempDir() / "boxroom.rawlog").string();
    sources::convertToRawlog(std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap", p);
    return p;
  }();
  return path;
}

}  // namespace roadslam::viewer::test
