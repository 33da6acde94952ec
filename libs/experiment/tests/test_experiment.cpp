// roadslam-experiment end to end on a short simulated drive: jobs run as processes of the real app,
// their trajectories equal roadslam-map's on the same config (the oracle: the job runner adds
// nothing), reruns skip finished jobs, a failing or hanging job is recorded and the others go on,
// GNU parallel running the emitted list gives the in-process results, bad experiments stop before
// any job with file and line, and the report renders in headless Chromium.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/img/CImage.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "roadslam/common/config.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/experiment/experiment.h"
#include "roadslam/experiment/jobs.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/sim/simulator.h"

namespace fs = std::filesystem;
using namespace roadslam;
using namespace roadslam::experiment;

namespace {

const std::string kBin = std::string(ROADSLAM_BINARY_DIR) + "/bin";
const std::string kSrc = ROADSLAM_SOURCE_DIR;

std::string readText(const std::string& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// 3 s of the urban loop, simulated once per build tree (30 sweeps, GT beside).
const std::string& drive() {
  static const std::string dir = [] {
    auto p = sim::ScenarioParams::fromFile(kSrc + "/ini/sim/urban-loop.ini");
    p.duration_s = 3.0;
    return sim::simulateCached(p, ROADSLAM_SIM_CACHE);
  }();
  return dir;
}

std::string freshDir(const std::string& name) {
  const std::string d = std::string(ROADSLAM_BINARY_DIR) + "/test_data/experiment_" + name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// An experiment file in \p dir: the default config, the 3 s drive, \p body appended.
std::string writeExp(const std::string& dir, const std::string& body, const std::string& stages = "odometry, eval") {
  const std::string path = dir + "/exp.ini";
  std::ofstream(path) << "[experiment]\nname = test\nbase_config = " << kSrc << "/ini/default.ini\nstages = " << stages
                      << "\n\n[dataset.urban]\ninput = " << drive() << "/velodyne.pcap\ngt = " << drive()
                      << "/gt_trajectory.tum\n\n" << body;
  return path;
}

ExperimentRequest request(const std::string& exp, const std::string& out) {
  ExperimentRequest r;
  r.config_path = exp, r.out_dir = out;
  r.pool.program = kBin + "/roadslam-experiment";
  r.pool.jobs = 2;
  r.pool.progress = false;
  return r;
}

std::string errorOf(const ExperimentRequest& r) {
  try {
    runExperiment(r);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

/// The 2-configuration experiment run here and emitted for \p engine ("parallel", "slurm"), the
/// emitted file run by \p run_emitted, collected: the metrics must equal the local pool's.
void expectEmittedEqualsLocal(const std::string& name, const std::string& engine,
                              const std::function<int(const std::string&)>& run_emitted) {
  const std::string dir = freshDir(name);
  const std::string exp = writeExp(dir, "[sweep]\nodometry.registration_voxel_m = 0.75, 1.0\n");
  const auto local = runExperiment(request(exp, dir + "/local"));
  auto emit = request(exp, dir + "/emitted");
  emit.emit = engine;
  const auto e = runExperiment(emit);
  ASSERT_EQ(e.emitted, dir + (engine == "slurm" ? "/emitted/slurm.sbatch" : "/emitted/jobs.txt"));
  ASSERT_EQ(run_emitted(e.emitted), 0);
  const auto c = collect(dir + "/emitted");
  ASSERT_EQ(c.ok, 2u);
  for (size_t i = 0; i < 2; ++i) {
    const auto& a = local.collected.results["jobs"][i];
    const auto& b = c.results["jobs"][i];
    EXPECT_EQ(a["params"], b["params"]);
    for (const char* m : {"rte_percent", "ate_m", "rre_deg_per_100m", "frames", "failed_frames"}) {
      EXPECT_EQ(a["metrics"][m], b["metrics"][m]) << m;
    }
  }
}

}  // namespace

TEST(Experiment, JobsEqualTheMapJobRunAloneAndRerunsSkipThem) {
  const std::string dir = freshDir("grid");
  const std::string exp = writeExp(dir, "[sweep]\nodometry.registration_voxel_m = 0.75, 1.0\n");
  const auto out = runExperiment(request(exp, dir + "/out"));
  ASSERT_EQ(out.planned, 2u);
  EXPECT_EQ(out.pool.ok, 2u);
  ASSERT_EQ(out.collected.ok, 2u) << readText(dir + "/out/results.csv");
  for (const auto& row : out.collected.results["jobs"]) {
    const std::string job = dir + "/out/" + row["dir"].get<std::string>();
    const std::string voxel = row["params"]["odometry.registration_voxel_m"];
    // the job's config is the base with the swept value
    mrpt::config::CConfigFileMemory cfg(readText(job + "/config_used.ini"));
    EXPECT_EQ(cfg.read_string("odometry", "registration_voxel_m", ""), voxel);
    // oracle: roadslam-map alone on the job's config gives the same odometry, byte for byte
    const std::string alone = dir + "/alone-" + voxel;
    ASSERT_EQ(std::system((kBin + "/roadslam-map --quiet --config " + job + "/config_used.ini --input " + drive() +
                           "/velodyne.pcap --out " + alone).c_str()), 0);
    EXPECT_EQ(readText(job + "/map/trajectory.tum"), readText(alone + "/trajectory_odometry.tum"));
    EXPECT_GT(row["metrics"]["rte_percent"].get<double>(), 0.0);
    EXPECT_LT(row["metrics"]["rte_percent"].get<double>(), 5.0);
    EXPECT_EQ(row["metrics"]["frames"].get<int>(), 30);
  }
  const auto csv = readText(dir + "/out/results.csv");
  EXPECT_NE(csv.find("odometry.registration_voxel_m"), std::string::npos);
  EXPECT_TRUE(out.collected.results["best"].contains("rte_percent"));

  const auto m0 = fs::last_write_time(dir + "/out/" + out.collected.results["jobs"][0]["dir"].get<std::string>() + "/metrics.json");
  const auto again = runExperiment(request(exp, dir + "/out"));
  EXPECT_EQ(again.skipped, 2u);
  EXPECT_EQ(again.pool.ran, 0u);
  EXPECT_EQ(again.collected.ok, 2u);
  EXPECT_EQ(fs::last_write_time(dir + "/out/" + out.collected.results["jobs"][0]["dir"].get<std::string>() + "/metrics.json"), m0);
  auto forced = request(exp, dir + "/out");
  forced.force = true;
  EXPECT_EQ(runExperiment(forced).pool.ran, 2u);
}

TEST(Experiment, AFailingJobAndAHangingJobAreRecordedAndTheOthersGoOn) {
  const std::string dir = freshDir("failures");
  std::ofstream(dir + "/garbage.pcap") << "this is no capture";
  const std::string exp = writeExp(dir, "[dataset.broken]\ninput = " + dir + "/garbage.pcap\n", "odometry");
  const auto out = runExperiment(request(exp, dir + "/out"));
  EXPECT_EQ(out.collected.ok, 1u);
  EXPECT_EQ(out.collected.failed, 1u);
  for (const auto& row : out.collected.results["jobs"]) {
    if (row["dataset"] != "broken") continue;
    EXPECT_EQ(row["status"], "failed");
    EXPECT_NE(row["reason"].get<std::string>().find("garbage.pcap"), std::string::npos) << row["reason"];
    EXPECT_NE(readText(dir + "/out/" + row["dir"].get<std::string>() + "/log.txt").find("garbage.pcap"), std::string::npos);
  }
  EXPECT_NE(readText(dir + "/out/report.html").find("Failed jobs"), std::string::npos);

  auto hang = request(writeExp(dir, "", "odometry"), dir + "/out-timeout");
  hang.pool.job_timeout_s = 0.05;
  const auto t = runExperiment(hang);
  EXPECT_EQ(t.pool.timed_out, 1u);
  EXPECT_EQ(t.collected.failed, 1u);
  EXPECT_NE(t.collected.results["jobs"][0].value("reason", "").find("timeout"), std::string::npos);
}

TEST(Experiment, GnuParallelOnTheEmittedListGivesTheInProcessResults) {
  if (std::system("command -v parallel > /dev/null 2>&1") != 0) GTEST_SKIP() << "GNU parallel is not installed (Debian: parallel)";
  expectEmittedEqualsLocal("parallel", "parallel",
                           [](const std::string& list) { return std::system(("parallel --will-cite -j 2 < " + list).c_str()); });
}

TEST(Experiment, BadExperimentsStopBeforeAnyJobNamingFileAndLine) {
  const std::string dir = freshDir("bad");
  // line 11 of the file: the sweep key
  const std::string typo = writeExp(dir, "[sweep]\nodometry.registration_voxel_size_m = 0.5, 1.0\n");
  const std::string e1 = errorOf(request(typo, dir + "/out1"));
  EXPECT_NE(e1.find(typo + ":11: unknown key 'odometry.registration_voxel_size_m'"), std::string::npos) << e1;
  EXPECT_NE(e1.find("nearest known: odometry.registration_voxel_m"), std::string::npos) << e1;
  EXPECT_FALSE(fs::exists(dir + "/out1/plan.json"));

  const std::string missing = dir + "/missing.ini";
  std::ofstream(missing) << "[experiment]\nbase_config = " << kSrc << "/ini/default.ini\n[dataset.x]\ninput = /nonexistent.pcap\n";
  const std::string e2 = errorOf(request(missing, dir + "/out2"));
  EXPECT_NE(e2.find(missing + ":4: [dataset.x] input '/nonexistent.pcap' does not exist"), std::string::npos) << e2;

  // a GT of another clock: the drive's GT moved a day later
  auto gt = datasets::readTum(drive() + "/gt_trajectory.tum");
  for (auto& t : gt.stamps_s) t += 86400.0;
  datasets::writeTum(dir + "/late.tum", gt);
  const std::string late = dir + "/late.ini";
  std::ofstream(late) << "[experiment]\nbase_config = " << kSrc << "/ini/default.ini\n[dataset.late]\ninput = " << drive()
                      << "/velodyne.pcap\ngt = " << dir << "/late.tum\n";
  const std::string e3 = errorOf(request(late, dir + "/out3"));
  EXPECT_NE(e3.find(late + ":4: [dataset.late] gt"), std::string::npos) << e3;
  EXPECT_NE(e3.find("do not overlap"), std::string::npos) << e3;
  EXPECT_FALSE(fs::exists(dir + "/out3/jobs"));

  const std::string cut = dir + "/cut.ini";  // duration_s on a recording: an error, not ignored
  std::ofstream(cut) << "[experiment]\nbase_config = " << kSrc << "/ini/default.ini\n[dataset.rec]\ninput = " << drive()
                     << "/velodyne.pcap\nduration_s = 5\n";
  EXPECT_NE(errorOf(request(cut, dir + "/out5")).find(cut + ":5: [dataset.rec] duration_s cuts a simulated drive"),
            std::string::npos);

  const std::string zip = writeExp(dir, "[sweep]\nmode = zip\nodometry.registration_voxel_m = 0.5, 1.0\nodometry.map_voxel_m = 1.0\n");
  EXPECT_NE(errorOf(request(zip, dir + "/out4")).find("mode = zip"), std::string::npos);
}

TEST(Experiment, RandomSearchIsSeededAndStaysInItsRanges) {
  const std::string dir = freshDir("random");
  const std::string exp = writeExp(dir, "[sweep]\nmode = random\nsamples = 20\nseed = 7\n"
                                        "odometry.registration_voxel_m = uniform(0.5, 1.5)\nodometry.map_points_per_voxel = randint(10, 20)\n"
                                        "odometry.deskew = true, false\n");
  const auto spec = loadExperiment(exp);
  const auto a = expandSweep(spec), b = expandSweep(spec);
  ASSERT_EQ(a.size(), 20u);
  EXPECT_EQ(a, b);
  std::set<std::string> deskew;
  for (const auto& c : a) {
    const double v = std::stod(c.at("odometry.registration_voxel_m"));
    const int n = std::stoi(c.at("odometry.map_points_per_voxel"));
    EXPECT_GE(v, 0.5);
    EXPECT_LT(v, 1.5);
    EXPECT_GE(n, 10);
    EXPECT_LE(n, 20);
    deskew.insert(c.at("odometry.deskew"));
  }
  EXPECT_EQ(deskew.size(), 2u) << "20 draws from two values";
}

TEST(Experiment, ReportRendersInHeadlessChromium) {
  const char* chromium = std::system("command -v chromium > /dev/null 2>&1") == 0 ? "chromium" : nullptr;
  if (!chromium) GTEST_SKIP() << "chromium is not installed (Debian: chromium)";
  const std::string dir = freshDir("report");
  const auto out = runExperiment(request(writeExp(dir, "[sweep]\nodometry.registration_voxel_m = 0.75, 1.0\n"), dir + "/out"));
  ASSERT_EQ(out.collected.ok, 2u);
  const std::string png = dir + "/report.png";
  const std::string cmd = std::string(chromium) + " --headless --no-sandbox --disable-gpu --window-size=1200,1600 --screenshot=" +
                          png + " file://" + dir + "/out/report.html > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(png));
  int series = 0, ink = 0;
  for (int y = 0; y < int(img.getHeight()); ++y)
    for (int x = 0; x < int(img.getWidth()); ++x) {
      const auto* p = img.ptr<uint8_t>(x, y);  // BGR
      series += std::abs(p[2] - 0x1f) < 12 && std::abs(p[1] - 0x77) < 12 && std::abs(p[0] - 0xb4) < 12;
      ink += p[0] < 90 && p[1] < 90 && p[2] < 90;
    }
  EXPECT_GT(series, 40) << "the plots' first series (#1f77b4: metric against the swept key) drawn";
  EXPECT_GT(ink, 3000) << "the tables' text";
}

TEST(Experiment, SlurmArrayOnAOneNodeClusterGivesTheInProcessResults) {
  const std::string state = std::string(ROADSLAM_BINARY_DIR) + "/test_data/experiment_slurm_cluster";
  const std::string conf = state + "/slurm.conf";
  const std::string start = kSrc + "/scripts/slurm_localhost.sh start " + state + " > " + state + ".out 2>&1";
  if (std::system(start.c_str()) != 0) {
    GTEST_SKIP() << "a one-node Slurm could not start here (" << readText(state + ".out") << ")";
  }
  struct Stop {
    std::string cmd;
    ~Stop() { (void)std::system(cmd.c_str()); }
  } stop{kSrc + "/scripts/slurm_localhost.sh stop " + state};
  expectEmittedEqualsLocal("slurm", "slurm", [&conf](const std::string& script) {
    return std::system(("SLURM_CONF=" + conf + " sbatch --wait --quiet " + script).c_str());
  });
}
