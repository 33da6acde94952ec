// The command-line conventions every roadslam-* program keeps, checked on
// the built programs run as child processes: --version (the commit is the source tree's HEAD),
// --quiet prints nothing on stdout, readable summaries with --json for the machine form, full-precision
// stamps through roadslam-map, --times for KITTI folders and the warning without one, and
// roadslam-eval's pairing warning and KITTI calibration.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "roadslam/common/version.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/datasets/trajectory_io.h"

namespace fs = std::filesystem;
using namespace roadslam;

namespace {
const std::string kBin = std::string(ROADSLAM_BINARY_DIR) + "/bin/";
const std::string kIni = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct AppRun {
  int code = -1;
  std::string out, err;
};

/// Runs bin/<program> <args> with stdout and stderr captured apart.
AppRun run(const std::string& program, const std::string& args) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("apps_cli_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string o = (dir / "stdout").string(), e = (dir / "stderr").string();
  const std::string cmd = kBin + program + " " + args + " > " + o + " 2> " + e + " < /dev/null";
  const int st = std::system(cmd.c_str());
  AppRun r;
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = slurp(o);
  r.err = slurp(e);
  return r;
}

bool built(const std::string& program) { return fs::exists(kBin + program); }

/// A standing car in a walled yard: \p n identical KITTI sweeps (walls, ground, pillars) in DIR/velodyne.
std::string kittiYard(const std::string& name, int n) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("apps_cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "velodyne");
  Scan s;
  auto add = [&](double x, double y, double z) {
    ScanPoint p;
    p.x = static_cast<float>(x), p.y = static_cast<float>(y), p.z = static_cast<float>(z), p.intensity = 0.5f;
    s.points.push_back(p);
  };
  for (double a = -12; a <= 12; a += 0.15)
    for (double z = -1.7; z <= 2.0; z += 0.15) add(a, 9.0, z), add(a, -7.0, z), add(14.0, a * 0.7, z), add(-10.0, a * 0.7, z);
  for (double x = -9.5; x <= 13.5; x += 0.3)
    for (double y = -6.5; y <= 8.5; y += 0.3) add(x, y, -1.73);
  for (int k = 0; k < 6; ++k)
    for (double z = -1.7; z <= 1.5; z += 0.1)
      for (double t = 0; t < 6.28; t += 0.4) add(3.0 * k - 6 + 0.3 * std::cos(t), (k % 2 ? 4.0 : -3.0) + 0.3 * std::sin(t), z);
  for (int i = 0; i < n; ++i) {
    char file[32];
    std::snprintf(file, sizeof file, "%06d.bin", i);
    datasets::writeKittiBin((dir / "velodyne" / file).string(), s);
  }
  return dir.string();
}

const char* kPrograms[] = {"roadslam-bounds", "roadslam-can",    "roadslam-eval",   "roadslam-experiment",
                           "roadslam-grab",   "roadslam-map",    "roadslam-rawlog", "roadslam-report",
                           "roadslam-sim",    "roadslam-view"};
}  // namespace

// Every program reports the commit its build recorded (the build tree's generated git_version.h, as
// Version.CommitIsTheOneTheBuildRecorded checks it names a commit): a program not relinked after the
// header changed says another. Not git's HEAD at test time, which a later commit or edit moves.
TEST(AppsCli, VersionNamesProgramVersionCommitAndBuildType) {
  const std::string recorded = roadslam::recordedGitCommit(ROADSLAM_BINARY_DIR);
  ASSERT_FALSE(recorded.empty()) << "no generated git_version.h under " ROADSLAM_BINARY_DIR;
  for (const char* p : kPrograms) {
    if (!built(p)) {
      ADD_FAILURE() << p << " not built";
      continue;
    }
    const AppRun r = run(p, "--version");
    EXPECT_EQ(r.code, 0) << p << ": " << r.err;
    EXPECT_EQ(r.err, "") << p;
    // "<program> <version> (commit <hash>[-dirty], <type> build)"
    const std::string start = std::string(p) + " " + ROADSLAM_PROJECT_VERSION + " (commit ";
    ASSERT_EQ(r.out.rfind(start, 0), 0u) << r.out;
    const std::string rest = r.out.substr(start.size());
    EXPECT_EQ(rest.substr(0, rest.find(',')), recorded) << p << " was linked before the build tree last recorded the commit: " << r.out;
    EXPECT_NE(rest.find(", " ROADSLAM_BUILD_TYPE " build)\n"), std::string::npos) << r.out;
  }
}

TEST(AppsCli, MapQuietTextJsonTimesAndTheNominalRateWarning) {
  if (!built("roadslam-map")) GTEST_SKIP() << "roadslam-map not built";
  const std::string yard = kittiYard("map", 4);
  const std::string vel = yard + "/velodyne", out = yard + "/out";

  // No times file: stamped at the nominal rate, and said so (stderr and summary.json).
  const AppRun quiet = run("roadslam-map", "--config " + kIni + " --input " + vel + " --out " + out + " --quiet");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.out, "") << "--quiet printed on stdout";
  EXPECT_NE(quiet.err.find("roadslam-map: warning: KITTI folder"), std::string::npos) << quiet.err;
  EXPECT_NE(quiet.err.find("10 Hz"), std::string::npos) << quiet.err;
  const auto s1 = nlohmann::json::parse(slurp(out + "/summary.json"));
  ASSERT_EQ(s1["warnings"].size(), 1u) << s1["warnings"];
  EXPECT_NE(s1["warnings"][0].get<std::string>().find("--times"), std::string::npos);

  // --times FILE (not times.txt): epoch stamps with microseconds reach every output, no warning.
  const std::vector<double> t = {1700000000.123456, 1700000000.223457, 1700000000.323458, 1700000000.423459};
  const std::string times = yard + "/stamps_utc.txt";
  {
    std::ofstream f(times);
    for (double v : t) f << std::fixed << std::setprecision(6) << v << "\n";
  }
  const AppRun text = run("roadslam-map", "--config " + kIni + " --input " + vel + " --out " + out + " --times " + times);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_EQ(text.err.find("warning"), std::string::npos) << text.err;
  EXPECT_NE(text.out.find("\nframes "), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find('{'), std::string::npos) << "text summary expected:\n" << text.out;
  for (const char* label : {"input", "failed", "distance", "duration", "ms per frame", "loop closures", "warnings", "outputs"})
    EXPECT_NE(("\n" + text.out).find(std::string("\n") + label + " "), std::string::npos) << label << "\n" << text.out;
  const auto stamps = datasets::readTimes(out + "/trajectory_times.txt");
  const auto tum = datasets::readTum(out + "/trajectory.tum");
  ASSERT_EQ(stamps.size(), t.size());
  ASSERT_EQ(tum.stamps_s.size(), t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(stamps[i], tum.stamps_s[i], 1e-6) << i;
    // the pose time is the times file's stamp less a fixed share of the sweep period: steps are kept
    if (i > 0) {
      EXPECT_NEAR(stamps[i] - stamps[i - 1], t[i] - t[i - 1], 1e-6) << i;
    }
    EXPECT_NEAR(stamps[i], t[i], 0.1) << i;
  }

  const AppRun json = run("roadslam-map", "--config " + kIni + " --input " + vel + " --out " + out + " --times " + times + " --json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["frames"].get<int>(), 4);
  EXPECT_TRUE(j["warnings"].empty());

  const AppRun bad = run("roadslam-map", "--config " + kIni + " --input " + vel + " --out " + out + " --times /nonexistent/times.txt");
  EXPECT_NE(bad.code, 0);
  EXPECT_EQ(bad.out, "");
}

TEST(AppsCli, SimQuietPrintsNothing) {
  const fs::path root = fs::path(::testing::TempDir()) / ("apps_cli_sim_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const std::string dir = root.string();
  const std::string args = "--config " + std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini --duration 0.3 --out ";
  const AppRun text = run("roadslam-sim", args + dir + "/text");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("sweeps"), std::string::npos) << text.out;
  const AppRun quiet = run("roadslam-sim", args + dir + "/quiet --quiet");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.out, "") << "--quiet printed on stdout";
  EXPECT_TRUE(fs::exists(dir + "/quiet/velodyne.pcap"));
  fs::remove_all(root);
}

TEST(AppsCli, BoundsQuietTextAndJson) {
  if (!built("roadslam-bounds")) GTEST_SKIP() << "roadslam-bounds not built";
  const std::string yard = kittiYard("bounds", 3);
  const std::string ini = std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini";
  const std::string args = "--config " + ini + " --input " + yard + "/velodyne --out " + yard + "/out --png-every 0";
  const AppRun quiet = run("roadslam-bounds", args + " --quiet");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.out, "");
  EXPECT_NE(quiet.err.find("roadslam-bounds: warning: KITTI folder"), std::string::npos) << quiet.err;
  {
    std::ofstream f(yard + "/stamps.txt");
    f << "1700000000.1\n1700000000.2\n1700000000.3\n";
  }
  const AppRun text = run("roadslam-bounds", args + " --times " + yard + "/stamps.txt");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_EQ(text.err.find("warning"), std::string::npos) << text.err;
  EXPECT_EQ(text.out.find('{'), std::string::npos) << text.out;
  for (const char* label : {"input ", "frames ", "found ", "ms per frame ", "warnings ", "outputs "})
    EXPECT_NE(text.out.find(label), std::string::npos) << label << "\n" << text.out;
  const AppRun json = run("roadslam-bounds", args + " --json");
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["frames"].get<int>(), 3);
  EXPECT_EQ(nlohmann::json::parse(json.out), nlohmann::json::parse(slurp(yard + "/out/summary.json")));
}

namespace {
/// A curving drive of \p n poses T_velo0_velo, 0.1 s apart from \p t0.
datasets::Trajectory drive(size_t n, double t0) {
  datasets::Trajectory d;
  for (size_t i = 0; i < n; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.03 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(1.0 * i, 0.02 * i * i, 0.01 * i);
    d.poses.push_back(T);
    d.stamps_s.push_back(t0 + 0.1 * i);
  }
  return d;
}
}  // namespace

TEST(AppsCli, EvalWarnsWhenFewPosesPair) {
  if (!built("roadslam-eval")) GTEST_SKIP() << "roadslam-eval not built";
  const fs::path dir = fs::path(::testing::TempDir()) / "apps_cli_eval_pairing";
  fs::create_directories(dir);
  auto gt = drive(16, 1700000000.0);
  auto est = gt;
  for (size_t i = 6; i < est.stamps_s.size(); ++i) est.stamps_s[i] += 0.05;  // 10 of 16 beyond max dt
  datasets::writeTum((dir / "gt.tum").string(), gt);
  datasets::writeTum((dir / "est.tum").string(), est);
  const std::string args = "--gt " + (dir / "gt.tum").string() + " --est " + (dir / "est.tum").string();
  const AppRun r = run("roadslam-eval", args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("roadslam-eval: warning: only 6 of the estimate's 16 poses"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("max dt 0.02 s"), std::string::npos) << r.err;
  const AppRun j = run("roadslam-eval", args + " --json");
  ASSERT_EQ(j.code, 0) << j.err;
  const auto js = nlohmann::json::parse(j.out);
  ASSERT_EQ(js["warnings"].size(), 1u);
  EXPECT_EQ(js["matched_poses"].get<int>(), 6);
  EXPECT_EQ(js["est_poses"].get<int>(), 16);

  const AppRun ok = run("roadslam-eval", args + " --max-dt 0.06 --json");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ok.err, "");
  EXPECT_TRUE(nlohmann::json::parse(ok.out)["warnings"].empty());
}

// A KITTI estimate without its times against a timed ground truth would pair unrelated poses by
// index; a ground truth that does not move leaves nothing to score per distance: both refused.
TEST(AppsCli, EvalRefusesAnUntimedSideAndAStandingGroundTruth) {
  if (!built("roadslam-eval")) GTEST_SKIP() << "roadslam-eval not built";
  const fs::path dir = fs::path(::testing::TempDir()) / "apps_cli_eval_refusals";
  fs::create_directories(dir);
  const auto gt = drive(16, 1700000000.0);
  datasets::writeTum((dir / "gt.tum").string(), gt);
  datasets::writeKittiPoses((dir / "est_kitti.txt").string(), gt.poses);
  const AppRun untimed = run("roadslam-eval", "--gt " + (dir / "gt.tum").string() + " --est " + (dir / "est_kitti.txt").string());
  EXPECT_EQ(untimed.code, 1) << untimed.out;
  EXPECT_NE(untimed.err.find("est_kitti.txt' is a KITTI 3x4 file without times"), std::string::npos) << untimed.err;
  EXPECT_NE(untimed.err.find("--est-times"), std::string::npos) << untimed.err;
  auto standing = gt;
  for (auto& T : standing.poses) T = gt.poses.front();
  datasets::writeTum((dir / "standing.tum").string(), standing);
  const AppRun still = run("roadslam-eval", "--gt " + (dir / "standing.tum").string() + " --est " + (dir / "standing.tum").string());
  EXPECT_EQ(still.code, 1) << still.out;
  EXPECT_NE(still.err.find("the 16 matched ground-truth poses span 0.000 m"), std::string::npos) << still.err;
}

TEST(AppsCli, EvalCalibTurnsCameraGroundTruthIntoLidarFrame) {
  if (!built("roadslam-eval")) GTEST_SKIP() << "roadslam-eval not built";
  const fs::path dir = fs::path(::testing::TempDir()) / "apps_cli_eval_calib";
  fs::create_directories(dir);
  // KITTI's Tr: velodyne (x fwd, y left, z up) to camera (x right, y down, z fwd), with an offset.
  Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
  Tr.linear() << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  Tr.translation() = Eigen::Vector3d(-0.004, -0.076, -0.27);
  {
    std::ofstream c(dir / "calib.txt");
    c << std::setprecision(12);
    for (const char* p : {"P0:", "P1:", "P2:", "P3:"}) c << p << " 1 0 0 0 0 1 0 0 0 0 1 0\n";
    c << "Tr:";
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 4; ++k) c << ' ' << Tr.matrix()(r, k);
    c << "\n";
  }
  const auto velo = drive(40, 0.0);
  datasets::PoseList cam;  // T_cam0_cami = Tr T_velo0_veloi Tr^-1
  for (const auto& T : velo.poses) cam.push_back(Tr * T * Tr.inverse());
  datasets::writeKittiPoses((dir / "gt_cam.txt").string(), cam);
  datasets::writeTimes((dir / "times.txt").string(), velo.stamps_s);
  datasets::writeTum((dir / "est_velo.tum").string(), velo);
  const std::string args = "--gt " + (dir / "gt_cam.txt").string() + " --gt-times " + (dir / "times.txt").string() +
                           " --est " + (dir / "est_velo.tum").string() + " --json";
  const AppRun with = run("roadslam-eval", args + " --calib " + (dir / "calib.txt").string());
  ASSERT_EQ(with.code, 0) << with.err;
  const auto jw = nlohmann::json::parse(with.out);
  EXPECT_LT(jw["rpe_trans_rmse_m"].get<double>(), 1e-6);
  EXPECT_LT(jw["ate_rmse_origin_aligned_m"].get<double>(), 1e-6);
  // Without --calib the camera-frame ground truth is refused: its figures would be meaningless.
  const AppRun without = run("roadslam-eval", args);
  EXPECT_EQ(without.code, 1) << without.out;
  EXPECT_NE(without.err.find("moves along its z axis"), std::string::npos) << without.err;
  EXPECT_NE(without.err.find("--calib"), std::string::npos) << without.err;
  const AppRun bad = run("roadslam-eval", args + " --calib " + (dir / "times.txt").string());
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("no 'Tr:' line"), std::string::npos) << bad.err;
}
