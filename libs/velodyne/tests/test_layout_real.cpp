// The layout check on the real captures of ../shared/data/velodyne (skipped when absent): the two
// HDL-32E and the two VLP-16 captures are told apart by their packets, whatever their product byte
// (the VeloView VLP-16 capture reports the HDL-32E byte 0x21, README of the data folder).
#include <gtest/gtest.h>

#include "oracle_util.h"
#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/velodyne/layout.h"
#include "roadslam/velodyne/model_choice.h"

using namespace roadslam;
using namespace roadslam::velodyne;

namespace {

LayoutVerdict layoutOfCapture(const std::string& pcap) {
  LayoutDetector d;
  pcap::PcapReader reader(pcap);
  pcap::UdpDatagram dg;
  while (!d.full() && reader.next(dg) == pcap::ReadStatus::Ok)
    if (dg.dst_port == kDefaultDataPort) d.add(dg.payload.data(), dg.payload.size());
  return d.verdict();
}

struct Capture {
  const char* file;
  Model layout;
  int product_byte;
};

}  // namespace

TEST(LayoutReal, EveryCaptureIsToldByItsPackets) {
  const Capture captures[] = {{"mrpt_sample_velodyne_hdl32.pcap", Model::HDL32, 0x21},
                              {"veloview_monterey-first-100-packets.pcap", Model::HDL32, 0x21},
                              {"mrpt_sample_velodyne_vlp16_gps.pcap", Model::VLP16, 0x22},
                              {"veloview_vlp-16-test-90deg-1-50-frames.pcap", Model::VLP16, 0x21}};
  for (const auto& c : captures) {
    const std::string path = test::dataFile(c.file);
    if (!test::exists(path)) GTEST_SKIP() << "missing " << path;
    const LayoutVerdict v = layoutOfCapture(path);
    EXPECT_EQ(v.model, c.layout) << c.file << ": " << v.describe();
    EXPECT_EQ(v.product_byte, c.product_byte) << c.file;
    const double nominal = c.layout == Model::VLP16 ? 110.592 : 46.08;
    EXPECT_NEAR(v.block_period_us / nominal, 1.0, 0.05) << c.file << ": " << v.describe();
  }
}

TEST(LayoutReal, VeloViewVlp16WithTheHdl32ByteIsDecodedAsVlp16WithAWarning) {
  const std::string path = test::dataFile("veloview_vlp-16-test-90deg-1-50-frames.pcap");
  if (!test::exists(path)) GTEST_SKIP() << "missing " << path;
  const ModelChoice c = chooseModel(Model::Unknown, layoutOfCapture(path));
  EXPECT_EQ(c.model, Model::VLP16);
  EXPECT_EQ(c.source, ModelSource::PacketLayout);
  EXPECT_EQ(c.warning.rfind("packets have the VLP-16 layout (11", 0), 0u) << c.warning;
  EXPECT_NE(c.warning.find(" us per block) but product byte 0x21 says HDL-32E; decoding as VLP-16; set [velodyne] "
                           "model = hdl32 to force"),
            std::string::npos)
      << c.warning;
}
