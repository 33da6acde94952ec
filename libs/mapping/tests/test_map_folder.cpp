// A map folder round-trips its keyframes and descriptors exactly; an older, foreign, other-version or
// damaged folder fails with a message naming the file.
#include <gtest/gtest.h>
#include <roadslam/common/atomic_file.h>
#include <roadslam/mapping/map_folder.h>

#include <filesystem>
#include <fstream>
#include <random>

namespace roadslam::mapping {
namespace {

std::string freshDir(const std::string& name) {
  const std::string d = std::string(ROADSLAM_BINARY_DIR) + "/test-out-map-folder-" + name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::vector<Keyframe> someKeyframes(PoseVector& T) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-30, 30);
  std::vector<Keyframe> kfs(3);
  for (size_t i = 0; i < kfs.size(); ++i) {
    kfs[i].frame_index = 10 * i;
    kfs[i].stamp_s = 1.5 * static_cast<double>(i);
    kfs[i].path_m = 4.0 * static_cast<double>(i);
    for (int k = 0; k < 500; ++k) kfs[i].points_lidar.emplace_back(u(rng), u(rng), 0.1f * u(rng));
    Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
    P.linear() = Eigen::AngleAxisd(0.3 * static_cast<double>(i), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    P.translation() << 4.0 * static_cast<double>(i), 0.5, -0.1;
    T.push_back(P);
  }
  return kfs;
}

TEST(MapFolder, RoundTripsKeyframesAndDescriptors) {
  PoseVector T;
  const auto kfs = someKeyframes(T);
  const std::string d = freshDir("ok");
  const place::ScanContextParams sc;
  writeMapFolder(d, kfs, T, sc);
  const MapFolder m = readMapFolder(d);
  EXPECT_EQ(m.version, kMapFolderVersion);
  ASSERT_EQ(m.keyframes.size(), kfs.size());
  for (size_t i = 0; i < kfs.size(); ++i) {
    EXPECT_EQ(m.keyframes[i].frame_index, kfs[i].frame_index);
    EXPECT_EQ(m.keyframes[i].points_lidar, kfs[i].points_lidar);
    EXPECT_TRUE(m.T_map_kf[i].isApprox(T[i], 1e-12));
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : kfs[i].points_lidar) pts.push_back(p.cast<double>());
    EXPECT_EQ(m.keyframes[i].descriptor.bins, place::makeScanContext(pts, sc).bins);
  }
}

void expectErrorNaming(const std::string& dir, const std::string& file, const std::string& words) {
  try {
    readMapFolder(dir);
    ADD_FAILURE() << "no error for " << dir;
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find(words), std::string::npos) << msg;
  }
}

TEST(MapFolder, OlderForeignOtherVersionAndDamagedFoldersFailNamingTheFile) {
  PoseVector T;
  const auto kfs = someKeyframes(T);
  const std::string older = freshDir("older");  // a folder of roadslam-map before map.json existed
  writeFileAtomically(older + "/posegraph.graph", "");
  expectErrorNaming(older, older + "/map.json", "missing");
  const std::string foreign = freshDir("foreign");
  writeFileAtomically(foreign + "/map.json", "{\"format\": \"somebody-else\", \"version\": 1}\n");
  expectErrorNaming(foreign, foreign + "/map.json", "foreign");
  const std::string v2 = freshDir("v2");
  writeMapFolder(v2, kfs, T, place::ScanContextParams{});
  writeFileAtomically(v2 + "/map.json", "{\"format\": \"roadslam-map\", \"version\": 2}\n");
  expectErrorNaming(v2, v2 + "/map.json", "version 2");
  const std::string cut = freshDir("truncated");
  writeMapFolder(cut, kfs, T, place::ScanContextParams{});
  std::filesystem::resize_file(cut + "/keyframes.bin", std::filesystem::file_size(cut + "/keyframes.bin") - 100);
  expectErrorNaming(cut, cut + "/keyframes.bin", "truncated");
}

}  // namespace
}  // namespace roadslam::mapping
