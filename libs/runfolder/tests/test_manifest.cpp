// run.json: written by the writers, checked by the readers; an older or foreign folder fails naming it.
#include <gtest/gtest.h>

#include "roadslam/runfolder/run_folder.h"
#include "test_util.h"

using namespace roadslam::runfolder;
using namespace roadslam::runfolder::test;

TEST(Manifest, RoundTrip) {
  const std::string d = freshDir("manifest-round-trip");
  Manifest m;
  m.program = kMapProgram;
  m.input = "velodyne.pcap (VLP-16)";
  writeManifest(d, m);
  const Manifest r = readManifest(d, kMapProgram);
  EXPECT_EQ(r.format, "roadslam-run");
  EXPECT_EQ(r.format_version, kFormatVersion);
  EXPECT_EQ(r.program, "roadslam-map");
  EXPECT_EQ(r.input, m.input);
  EXPECT_EQ(r.program_version.rfind("roadslam-map ", 0), 0u) << r.program_version;
}

TEST(Manifest, AFolderWithoutOneFailsNamingTheFileAndTheProgram) {
  const std::string d = freshDir("manifest-missing");
  writeText(d + "/trajectory.tum", "0 0 0 0 0 0 0 1\n");  // as a roadslam-map before run.json wrote it
  const std::string e = thrown([&] { openMapRun(d); });
  EXPECT_NE(e.find(d + "/run.json: missing"), std::string::npos) << e;
  EXPECT_NE(e.find("re-create it with roadslam-map"), std::string::npos) << e;
  const std::string b = thrown([&] { openBoundsRun(d); });
  EXPECT_NE(b.find("re-create it with roadslam-bounds"), std::string::npos) << b;
  EXPECT_NE(thrown([&] { openMapRun(d + "/nope"); }).find("not a folder"), std::string::npos);
}

TEST(Manifest, ForeignFormatVersionOrProgramFailsNamingTheFile) {
  const std::string d = freshDir("manifest-foreign");
  const std::string path = d + "/run.json";
  writeText(path, R"({"format": "roadslam-map", "version": 1})");  // a map folder's map.json, say
  EXPECT_NE(thrown([&] { openMapRun(d); }).find(path + ": not a run manifest"), std::string::npos);
  writeText(path, R"({"format": "other-tool", "format_version": 1, "program": "roadslam-map"})");
  EXPECT_NE(thrown([&] { openMapRun(d); }).find(path + ": format 'other-tool'"), std::string::npos);
  writeText(path, R"({"format": "roadslam-run", "format_version": 99, "program": "roadslam-map"})");
  const std::string v = thrown([&] { openMapRun(d); });
  EXPECT_NE(v.find(path + ": format_version 99, this build reads 1"), std::string::npos) << v;
  writeText(path, R"({"format": "roadslam-run", "format_version": 1, "program": "roadslam-bounds"})");
  EXPECT_NE(thrown([&] { openMapRun(d); }).find(path + ": written by 'roadslam-bounds', not by roadslam-map"),
            std::string::npos);
  EXPECT_NO_THROW(openBoundsRun(d));
  writeText(path, "{ not json");
  EXPECT_NE(thrown([&] { openBoundsRun(d); }).find(path + ": not a run manifest"), std::string::npos);
}
