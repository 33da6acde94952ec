// The orchestrator's own contract: sweeps through the stages in order, a first sweep read ahead and
// handed out again, poses from a trajectory (exact where it is linear), deskewing into the reference
// pose (a static wall seen from a moving sensor lands in one place), a two-pass replay that notices a
// changed recording, the stage wiring errors, and the factory's stage lists (a stage of one's own
// plugs in beside them).
#include <gtest/gtest.h>
#include <unistd.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>

#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/mapping/mapper.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/pipeline/stage_factory.h"
#include "roadslam/pipeline/stages/dynamic_removal.h"
#include "roadslam/pipeline/stages/maps.h"
#include "roadslam/pipeline/stages/objects.h"
#include "roadslam/pipeline/stages/sweep_export.h"

using namespace roadslam;
namespace fs = std::filesystem;

namespace {

/// Sweeps from memory, a real ScanSource: the pipeline cannot tell it from a recording.
class MemorySource : public sources::ScanSource {
 public:
  explicit MemorySource(std::deque<Scan> scans) : scans_(std::move(scans)) {}
  std::optional<Scan> next() override {
    if (scans_.empty()) return std::nullopt;
    Scan s = std::move(scans_.front());
    scans_.pop_front();
    ++stats_.sweeps;
    return s;
  }
  bool finished() const override { return scans_.empty(); }
  std::string describe() const override { return "memory"; }
  sources::ScanSourceStats stats() const override { return stats_; }

 private:
  std::deque<Scan> scans_;
  sources::ScanSourceStats stats_;
};

constexpr double kSpeed = 10.0;   // [m/s] along x
constexpr double kPeriod = 0.1;   // [s] per sweep
constexpr double kWallX = 20.0;   // a wall across the road at x = 20 m (map frame)

/// A sensor moving at kSpeed along x from t = 0 sees the wall: each point fired at time t lies at
/// x = kWallX - kSpeed * (stamp + t) in the lidar frame of its own firing.
Scan wallSweep(double stamp_s) {
  Scan s;
  s.stamp_s = stamp_s;
  s.has_point_times = true;
  for (int i = 0; i <= 100; ++i) {
    ScanPoint p;
    p.t = static_cast<float>(kPeriod * i / 100.0);
    p.x = static_cast<float>(kWallX - kSpeed * (stamp_s + p.t));
    p.y = static_cast<float>(-5.0 + 0.1 * i);
    s.points.push_back(p);
  }
  return s;
}

std::string writeLinearTrajectory(double t_end_s) {
  datasets::Trajectory traj;
  for (double t = 0; t <= t_end_s + 1e-9; t += 0.05) {
    traj.stamps_s.push_back(t);
    traj.poses.push_back(Eigen::Isometry3d(Eigen::Translation3d(kSpeed * t, 0, 0)));
  }
  // One file per process: ctest runs each TEST as its own process, two of them at once with -j2.
  const std::string path =
      (fs::temp_directory_path() / ("roadslam_test_pipeline_linear_" + std::to_string(::getpid()) + ".tum")).string();
  datasets::writeTum(path, traj);
  return path;
}

std::deque<Scan> wallSweeps(int n, double t0 = 0.0) {
  std::deque<Scan> out;
  for (int k = 0; k < n; ++k) out.push_back(wallSweep(t0 + k * kPeriod));
  return out;
}

}  // namespace

TEST(Pipeline, TrajectoryPosesAreExactOnALinearDriveAndDeskewPutsTheWallInOnePlace) {
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(1.0);
  r.boundaries = std::make_shared<boundary::BoundaryDetector>(boundary::Params{});
  pipeline::Pipeline pipe(std::make_unique<MemorySource>(wallSweeps(5)), pipeline::buildStages({}, std::move(r)));
  size_t n = 0;
  while (auto f = pipe.next()) {
    EXPECT_EQ(f->index, n++);
    ASSERT_TRUE(f->pose.ok) << f->pose.why;
    // mid-sweep pose: x = v * (stamp + T/2)
    EXPECT_NEAR(f->pose.t_ref, f->pose.stamp_s + 0.5 * kPeriod, 1e-6);
    EXPECT_NEAR(f->pose.ref.translation().x(), kSpeed * f->pose.t_ref, 1e-6);
    ASSERT_TRUE(f->scan);
    // Deskewed into the mid-sweep frame, every wall point sits at kWallX - x_ref.
    const double x_expected = kWallX - f->pose.ref.translation().x();
    double worst = 0;
    for (const auto& p : f->scan->points) worst = std::max(worst, std::abs(p.x - x_expected));
    EXPECT_LT(worst, kSpeed * kPeriod / 200 + 1e-4) << "one 0.5 ms deskew bucket of motion at most";
    ASSERT_TRUE(f->boundary);
    EXPECT_EQ(f->ms.by_stage.count("boundaries"), 1u);
    EXPECT_GE(f->ms.of("boundaries"), 0.0);
  }
  EXPECT_EQ(n, 5u);
  EXPECT_EQ(pipe.frames(), 5u);
  EXPECT_GE(pipe.totals().of("boundaries"), 0.0);
}

TEST(Pipeline, ASweepOutsideTheTrajectoryHasNoPoseAndReachesNoStage) {
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(0.3);
  r.boundaries = std::make_shared<boundary::BoundaryDetector>(boundary::Params{});
  pipeline::Pipeline pipe(std::make_unique<MemorySource>(wallSweeps(1, 5.0)), pipeline::buildStages({}, std::move(r)));
  const auto f = pipe.next();
  ASSERT_TRUE(f);
  EXPECT_FALSE(f->pose.ok);
  EXPECT_EQ(f->pose.why, "no pose in the trajectory at this sweep");
  EXPECT_FALSE(f->boundary);
  EXPECT_FALSE(pipe.next());
}

TEST(Pipeline, RecordedPosesReplayInOrderAndNoticeAChangedRecording) {
  std::vector<pipeline::SweepPose> rec(2);
  rec[0].stamp_s = 0.0, rec[1].stamp_s = 0.1;
  rec[0].ok = rec[1].ok = true;
  pipeline::RecordedPoses poses(rec, "in.pcap", "odometry");
  Scan a = wallSweep(0.0), b = wallSweep(0.2);
  EXPECT_TRUE(poses.pose(a).ok);
  try {
    poses.pose(b);
    FAIL() << "a sweep stamped 0.2 s where 0.1 s was recorded must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'in.pcap' gave other sweeps on its second reading (sweep 1)"), std::string::npos) << e.what();
  }
}

TEST(Pipeline, StageWiringErrors) {
  EXPECT_THROW(pipeline::Pipeline(std::make_unique<MemorySource>(wallSweeps(1)), pipeline::StageList{}), std::invalid_argument);
  pipeline::StageList no_pose_first;
  no_pose_first.push_back(std::make_unique<pipeline::MapsStage>(mapping::MapperParams{}, nullptr, pipeline::MapsStageParams{}));
  EXPECT_THROW(pipeline::Pipeline(std::make_unique<MemorySource>(wallSweeps(1)), std::move(no_pose_first)),
               std::invalid_argument);
  // The maps stage needs the odometry's results and points; a trajectory has neither.
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(1.0);
  r.maps = true;
  pipeline::Pipeline pipe(std::make_unique<MemorySource>(wallSweeps(1)), pipeline::buildStages({}, std::move(r)));
  EXPECT_THROW(pipe.next(), std::logic_error);
}

TEST(Pipeline, OpenNonEmptySourceHandsOutTheFirstSweepAgain) {
  const std::string pcap = std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap";
  mrpt::config::CConfigFileMemory cfg;
  auto plain = sources::openScanSource(pcap, cfg);
  auto peeked = pipeline::openNonEmptySource(pcap, cfg);
  size_t n = 0;
  while (true) {
    const auto a = plain->next();
    const auto b = peeked->next();
    ASSERT_EQ(a.has_value(), b.has_value()) << "at sweep " << n;
    if (!a) break;
    EXPECT_EQ(a->stamp_s, b->stamp_s);
    EXPECT_EQ(a->points.size(), b->points.size());
    ++n;
  }
  EXPECT_GT(n, 1u);
  EXPECT_EQ(plain->stats().sweeps, peeked->stats().sweeps);
  EXPECT_EQ(peeked->describe(), plain->describe());
}

TEST(Pipeline, AnInputWithNoSweepIsAnErrorNamingIt) {
  const fs::path empty = fs::temp_directory_path() / "roadslam_test_pipeline_empty.pcap";
  {
    std::ofstream f(empty, std::ios::binary);
    // a valid pcap global header (LINKTYPE_ETHERNET) and no packet
    const unsigned char hdr[24] = {0xd4, 0xc3, 0xb2, 0xa1, 2, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 0, 0, 1, 0, 0, 0};
    f.write(reinterpret_cast<const char*>(hdr), sizeof hdr);
  }
  mrpt::config::CConfigFileMemory cfg;
  try {
    pipeline::openNonEmptySource(empty.string(), cfg);
    FAIL() << "an empty capture gives no sweep";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("input '" + empty.string() + "' gives no sweep"), std::string::npos) << e.what();
  }
}

TEST(Pipeline, TheObjectsStageTracksTheWallAndCoastsWithoutAPose) {
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(0.3);  // poses for the first 3 sweeps only
  pipeline::ChainParams chain;
  chain.objects.enabled = true;
  const objects::TrackerParams tp = chain.tracking;
  pipeline::Pipeline pipe(std::make_unique<MemorySource>(wallSweeps(4 + tp.max_misses + 1)),
                          pipeline::buildStages(chain, std::move(r)));
  objects::ObjectsStage& stage = pipe.find<pipeline::ObjectTrackingStage>()->objects();
  size_t posed = 0;
  while (auto f = pipe.next()) {
    ASSERT_TRUE(f->objects) << "every sweep has an objects frame, posed or not";
    if (f->pose.ok) {
      ++posed;
      EXPECT_EQ(f->objects->objects.size(), 1u) << "the wall, clustered without rings (Euclidean)";
      if (f->index == 2) {  // the third sweep confirms the wall's track, where the wall stands in the map
        ASSERT_EQ(f->objects->tracks.size(), 1u);
        EXPECT_NEAR(f->objects->tracks[0].x(0), kWallX, 0.05);
        EXPECT_NEAR(f->objects->tracks[0].speed(), 0.0, 0.05);
      }
      ASSERT_TRUE(f->scan);
    }
    for (const auto& t : f->objects->tracks) EXPECT_TRUE(t.x.allFinite());
  }
  EXPECT_GE(posed, 3u);  // the sweep at the trajectory's end may still get one
  EXPECT_GE(pipe.totals().of("objects"), 0.0);
  EXPECT_TRUE(stage.tracker().tracks().empty());
  const auto ended = stage.tracker().takeEnded();
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].reason, "pose");
  EXPECT_EQ(ended[0].track.state, objects::TrackState::Confirmed);
  EXPECT_TRUE(ended[0].track.x.allFinite());
}

// The objects stage's moving tracks as boxes for the odometry's map: car-sized at least, lengthened by
// one sweep's drive, grown by the margin; static tracks give none.
TEST(Pipeline, MovingTracksBecomeOdometryExclusions) {
  objects::ObjectsFrame f;
  objects::Track moving, parked;
  moving.id = 1, moving.moving = true, moving.heading = 0, moving.length = 3.0, moving.width = 2.0;
  moving.x << 10, 2, 5, 0;
  moving.z_min = -1.5, moving.z_max = 0.0;
  parked = moving;
  parked.id = 2, parked.moving = false;
  f.tracks = {moving, parked};
  objects::TrackerParams tp;  // car 4.5 x 1.8 m
  const auto boxes = pipeline::movingExclusions(f, 7.0, tp, 0.3, 0.1);
  ASSERT_EQ(boxes.size(), 1u);
  const auto& b = boxes[0];
  EXPECT_DOUBLE_EQ(b.stamp_s, 7.0);
  EXPECT_NEAR(b.box.length_m, 4.5 + 2 * 5 * 0.1 + 2 * 0.3, 1e-12);  // the car's length, not the 3 m seen
  EXPECT_NEAR(b.box.width_m, 2.0 + 2 * 0.3, 1e-12);                // the 2 m seen, wider than a car
  EXPECT_NEAR(b.box.z_min_m, -1.8, 1e-12);
  EXPECT_NEAR(b.box.z_max_m, 0.3, 1e-12);
  // one sweep later the box has driven 0.5 m
  EXPECT_TRUE(b.contains({10.5 + 3.0, 2, -1}, 7.1));
  EXPECT_FALSE(b.contains({10.5 + 3.1, 2, -1}, 7.1));
  EXPECT_FALSE(b.contains({10.5 - 3.1, 2, -1}, 7.1));
}

namespace {

/// The names of \p stages, in order.
std::vector<std::string> names(const pipeline::StageList& stages) {
  std::vector<std::string> out;
  for (const auto& s : stages) out.push_back(s->name());
  return out;
}

}  // namespace

// The factory's lists: what a job asks for, in the order a frame visits the stages; the odometry
// leaves the sweep in place only when a later stage reads it.
TEST(StageFactory, TheJobsListsInTheirOrder) {
  using V = std::vector<std::string>;
  pipeline::ChainParams chain;
  EXPECT_EQ(names(pipeline::buildStages(chain, {})), V({"poses"}));
  {
    pipeline::StageRequest r;
    r.maps = true;
    EXPECT_EQ(names(pipeline::buildStages(chain, std::move(r))), V({"poses", "maps"}));
  }
  chain.objects.enabled = true;
  chain.objects.remove_moving_from_maps = true;
  {
    pipeline::StageRequest r;
    r.maps = true;
    r.boundaries = std::make_shared<boundary::BoundaryDetector>(boundary::Params{});
    EXPECT_EQ(names(pipeline::buildStages(chain, std::move(r))),
              V({"poses", "deskew", "objects", "dynamic_removal", "maps", "boundaries"}));
  }
  {
    pipeline::StageRequest r;  // no maps: nothing to remove the moving points from
    EXPECT_EQ(names(pipeline::buildStages(chain, std::move(r))), V({"poses", "deskew", "objects"}));
  }
  {
    pipeline::StageRequest r;
    r.objects = false;  // a job that runs no objects, whatever the ini says
    r.maps = true;
    EXPECT_EQ(names(pipeline::buildStages(chain, std::move(r))), V({"poses", "maps"}));
  }
  {
    pipeline::StageRequest r;
    r.live_gnss = std::make_shared<pipeline::LiveGnss>(gnss_fusion::GnssFusionParams{});
    chain.objects.enabled = false;
    EXPECT_EQ(names(pipeline::buildStages(chain, std::move(r))), V({"poses", "gnss"}));
  }
}

namespace {

/// A stage of a test's own: it sees every frame after the stages before it, with their results.
class CountingStage : public pipeline::Stage {
 public:
  std::string name() const override { return "counting"; }
  void process(pipeline::PipelineFrame& f) override {
    ++frames;
    posed += f.pose.ok;
    with_boundary += f.boundary.has_value();
  }
  void finish() override { ++finished; }
  int frames = 0, posed = 0, with_boundary = 0, finished = 0;
};

}  // namespace

TEST(StageFactory, AStageOfOnesOwnPlugsInAfterTheFactorysStages) {
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(0.3);  // poses for the first 3 sweeps only
  r.boundaries = std::make_shared<boundary::BoundaryDetector>(boundary::Params{});
  pipeline::StageList stages = pipeline::buildStages({}, std::move(r));
  auto counting = std::make_unique<CountingStage>();
  CountingStage& c = *counting;
  stages.push_back(std::move(counting));
  pipeline::Pipeline pipe(std::make_unique<MemorySource>(wallSweeps(6)), std::move(stages));
  while (pipe.next()) {
  }
  EXPECT_EQ(c.frames, 6);
  EXPECT_GE(c.posed, 3);
  EXPECT_LE(c.posed, 4);  // the sweep at the trajectory's end may still get one
  EXPECT_EQ(c.with_boundary, c.posed) << "the boundary stage ran before it on every posed sweep";
  EXPECT_GE(c.finished, 1) << "the end of the source finishes every stage";
  EXPECT_GE(pipe.totals().of("counting"), 0.0);
  EXPECT_EQ(pipe.totals().by_stage.count("counting"), 1u);
}

// Timing by name: a stage that did not run is 0, sums add stage by stage.
TEST(StageTimes, SumsByStageName) {
  pipeline::StageTimes a, b;
  a.source = 1, a.by_stage["poses"] = 2;
  b.source = 3, b.by_stage["poses"] = 4, b.by_stage["maps"] = 5;
  a += b;
  EXPECT_DOUBLE_EQ(a.source, 4);
  EXPECT_DOUBLE_EQ(a.of("poses"), 6);
  EXPECT_DOUBLE_EQ(a.of("maps"), 5);
  EXPECT_DOUBLE_EQ(a.of("boundaries"), 0);
}

namespace {

/// A binary PCD's header lines up to DATA, and its data.
std::pair<std::vector<std::string>, std::string> readPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    header.push_back(line);
    if (line.rfind("DATA", 0) == 0) break;
  }
  return {header, std::string(std::istreambuf_iterator<char>(in), {})};
}

}  // namespace

// The sweep exporter: one PCD per posed sweep, the deskewed points exactly as the later stages saw
// them (x y z intensity ring t, packed as the header says); unposed sweeps write nothing.
TEST(SweepExport, EachPosedSweepAsTheStagesSawIt) {
  const fs::path dir = fs::temp_directory_path() / "roadslam_test_sweep_export";
  fs::remove_all(dir);
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(1.0);
  r.sweep_export_dir = dir.string();
  std::deque<Scan> sweeps = wallSweeps(4), late = wallSweeps(2, 5.0);  // the last two outside the trajectory
  sweeps.insert(sweeps.end(), late.begin(), late.end());
  pipeline::Pipeline pipe(std::make_unique<MemorySource>(std::move(sweeps)), pipeline::buildStages({}, std::move(r)));
  size_t posed = 0;
  while (auto f = pipe.next()) {
    char name[32];
    std::snprintf(name, sizeof name, "%06zu.pcd", f->index);
    const fs::path file = dir / name;
    ASSERT_EQ(fs::exists(file), f->pose.ok) << file;
    if (!f->pose.ok) continue;
    ++posed;
    ASSERT_TRUE(f->scan);
    const auto [header, data] = readPcd(file.string());
    ASSERT_GE(header.size(), 10u);
    EXPECT_EQ(header[2], "FIELDS x y z intensity ring t");
    EXPECT_EQ(header[3], "SIZE 4 4 4 4 2 4");
    EXPECT_EQ(header[4], "TYPE F F F F U F");
    EXPECT_EQ(header[9], "POINTS " + std::to_string(f->scan->points.size()));
    ASSERT_EQ(data.size(), f->scan->points.size() * 22u);
    for (size_t i = 0; i < f->scan->points.size(); ++i) {
      const ScanPoint& p = f->scan->points[i];
      float xyz[3], t;
      uint16_t ring;
      std::memcpy(xyz, data.data() + 22 * i, 12);
      std::memcpy(&ring, data.data() + 22 * i + 16, 2);
      std::memcpy(&t, data.data() + 22 * i + 18, 4);
      EXPECT_EQ(xyz[0], p.x);
      EXPECT_EQ(xyz[1], p.y);
      EXPECT_EQ(xyz[2], p.z);
      EXPECT_EQ(ring, p.ring);
      EXPECT_EQ(t, p.t);
    }
    // deskewed: the wall in one place (as the deskew test above), not spread over the 1 m driven
    // during the sweep
    EXPECT_NEAR(f->scan->points.front().x, f->scan->points.back().x, 1e-3) << "sweep " << f->index;
  }
  EXPECT_EQ(posed, 4u);
  EXPECT_EQ(pipe.find<pipeline::SweepExportStage>()->written(), posed);
  fs::remove_all(dir);
}

TEST(SweepExport, AFolderThatCannotBeMadeIsAnErrorNamingIt) {
  pipeline::StageRequest r;
  r.trajectory_path = writeLinearTrajectory(0.3);
  r.sweep_export_dir = "/proc/roadslam_no_such/sweeps";
  try {
    pipeline::buildStages({}, std::move(r));
    FAIL() << "a folder under /proc cannot be made";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'/proc/roadslam_no_such/sweeps'"), std::string::npos) << e.what();
  }
}
