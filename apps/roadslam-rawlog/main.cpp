// roadslam-rawlog: summarise and convert Velodyne recordings (.pcap, MRPT .rawlog); regenerate
// the bundled box-room capture. All logic lives in libs/sources; see docs/apps/roadslam-rawlog.md.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <exception>
#include <string>

#include "roadslam/sources/boxroom.h"

int main(int argc, char** argv) {
  CLI::App app{"Summarise and convert Velodyne recordings (.pcap, MRPT .rawlog)"};
  app.require_subcommand(1);

  std::string boxroom_out;
  auto* box = app.add_subcommand("make-boxroom",
                                 "Write the deterministic box-room VLP-16 capture (rawlogs/boxroom-vlp16.pcap)");
  box->add_option("OUT", boxroom_out, "output .pcap")->required();

  CLI11_PARSE(app, argc, argv);
  try {
    if (*box) {
      const auto s = roadslam::sources::writeBoxRoomPcap(boxroom_out);
      fmt::print("{}: {} data packets, {} position packets, {} points, {} complete sweeps\n",
                 boxroom_out, s.data_packets, s.position_packets, s.points, s.complete_sweeps);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "roadslam-rawlog: {}\n", e.what());
    return 1;
  }
  return 0;
}
