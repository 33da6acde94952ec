// End-to-end: the roadslam-view binary on the bundled box room (as a rawlog) with a small map folder:
// headless renders (deterministic, a sequence), bad inputs (one line, exit 1), and the real window
// under Xvfb driven by a --script, asserting on its screenshots.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/img/CImage.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "roadslam/runfolder/run_folder.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/rawlog/rawlog_index.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/sources/recording.h"
#include "roadslam/viewer/recording_cache.h"

namespace fs = std::filesystem;

namespace {

// The trajectory's magenta (SceneColors::trajectory), also where lines are blended with the
// background: red and blue alike, no green. The jet colour map of the sweep never gives that hue.
bool isTrajectoryHue(int r, int g, int b) { return r > 100 && b > 100 && g < 40 && std::abs(r - b) < 30; }
const std::string kBin = ROADSLAM_VIEW_BIN;

// The viewer keeps its conversions and indexes in the user's cache folder: this run's own.
const fs::path kCache = [] {
  const fs::path c = fs::temp_directory_path() / ("roadslam_view_app_" + std::to_string(getpid())) / "xdg-cache";
  setenv("XDG_CACHE_HOME", c.c_str(), 1);
  return c;
}();

struct AppRun {
  int status = -1;
  std::string out;
};
AppRun run(const std::string& args, const std::string& prefix = "") {
  const std::string cmd = prefix + kBin + " " + args + " 2>&1 </dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), p)) > 0) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

/// The names in \p dir, sorted: what a run wrote beside its input shows as a difference.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// N from the summary line "...: N observations over ...".
std::string observationsIn(const std::string& out) {
  const auto end = out.find(" observations over");
  if (end == std::string::npos) return "?";
  const auto start = out.rfind(' ', end - 1) + 1;
  return out.substr(start, end - start);
}

/// The first whole records of the pcap \p bytes that fit in \p n bytes (pcap-savefile(5): a 24-byte
/// file header, 16-byte record headers with the captured length at byte 8): a shorter, whole capture.
std::string wholeRecordsUpTo(const std::string& bytes, std::size_t n) {
  std::size_t end = 24;
  for (uint32_t incl = 0; end + 16 <= bytes.size(); end += 16 + incl) {
    std::memcpy(&incl, bytes.data() + end + 8, 4);
    if (end + 16 + incl > n) break;
  }
  return bytes.substr(0, end);
}

// The box room as a rawlog and a map folder whose trajectory drove 10 m along +x up to it.
struct Fixture {
  fs::path dir, rawlog, map;
  Fixture() {
    dir = fs::temp_directory_path() / ("roadslam_view_app_" + std::to_string(getpid()));
    fs::create_directories(dir / "map");
    rawlog = dir / "boxroom.rawlog";
    map = dir / "map";
    roadslam::sources::convertToRawlog(std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap",
                                       rawlog.string());
    roadslam::rawlog::RawlogIndexOptions no_sidecar;  // the viewer must find none beside it
    no_sidecar.use_cache = no_sidecar.write_cache = false;
    const double t0 = roadslam::rawlog::RawlogIndex::open(rawlog.string(), no_sidecar)->firstStamp();
    roadslam::datasets::Trajectory poses;
    for (int k = 0; k <= 20; ++k) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation().x() = -10.0 + 0.5 * k;
      poses.stamps_s.push_back(t0 - 2.0 + 0.1 * k);
      poses.poses.push_back(T);
    }
    roadslam::runfolder::writeMapRun(map.string(), roadslam::runfolder::mapRunOfTrajectory(poses, "boxroom"));
  }
};
const Fixture& fixture() {
  static const Fixture f;
  return f;
}

// Green pixels (PlotColors::speed) in the bottom fifth of a picture: the CAN speed curve.
int speedCurvePixels(const fs::path& png) {
  mrpt::img::CImage img;
  EXPECT_TRUE(img.loadFromFile(png.string()));
  int green = 0;
  for (int y = static_cast<int>(img.getHeight()) * 4 / 5; y < static_cast<int>(img.getHeight()); ++y)
    for (int x = 0; x < static_cast<int>(img.getWidth()); ++x) {
      const auto* p = img.ptr<uint8_t>(x, y);  // BGR
      green += p[1] > 150 && p[0] < 120 && p[2] < 120;
    }
  return green;
}

struct Pixels {
  int magenta = 0, coloured = 0, bright = 0;
};
// Counts in the rectangle [x0, x1) x [y0, y1): trajectory magenta, jet-coloured (sweep) and bright
// grey (text) pixels.
Pixels count(const mrpt::img::CImage& img, int x0, int y0, int x1, int y1) {
  Pixels c;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const auto* px = img.ptr<uint8_t>(x, y);
      const int b = px[0], g = px[1], r = px[2];
      if (isTrajectoryHue(r, g, b)) ++c.magenta;
      const int mx = std::max({r, g, b}), mn = std::min({r, g, b});
      if (mx - mn > 60 && !isTrajectoryHue(r, g, b)) ++c.coloured;
      if (mn > 170 && mx - mn < 20) ++c.bright;
    }
  return c;
}
}  // namespace

TEST(RoadslamViewApp, HeadlessRenderIsDeterministicAndSequenceWritesPictures) {
  const auto& f = fixture();
  const fs::path a = f.dir / "a.png", b = f.dir / "b.png";
  const std::string common = f.rawlog.string() + " --map " + f.map.string() + " --size 320x240 --camera top";
  const AppRun ra = run(common + " --render " + a.string() + " --at 0.2");
  ASSERT_EQ(ra.status, 0) << ra.out;
  const AppRun rb = run(common + " --render " + b.string() + " --at 0.2");
  ASSERT_EQ(rb.status, 0) << rb.out;
  EXPECT_EQ(slurp(a), slurp(b));
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(a.string()));
  EXPECT_EQ(img.getWidth(), 320u);
  EXPECT_GT(count(img, 0, 30, 150, 240).magenta, 20) << "the path comes from the left in the top view";
  const AppRun rs = run(common + " --render-sequence " + (f.dir / "seq").string() + " --every 2");
  ASSERT_EQ(rs.status, 0) << rs.out;
  EXPECT_NE(rs.out.find(": 3 pictures"), std::string::npos) << rs.out;  // 6 sweeps, every 2nd
  EXPECT_EQ(std::distance(fs::directory_iterator(f.dir / "seq"), fs::directory_iterator{}), 3);
  EXPECT_FALSE(fs::exists(f.rawlog.string() + ".idx")) << "the index is kept in the cache, not beside the rawlog";
  EXPECT_TRUE(fs::exists(kCache / "roadslam" / roadslam::viewer::cacheFileName(f.rawlog.string(), ".idx")));
}

// The real outputs of roadslam-map and roadslam-bounds on the same recording load (their formats are
// what the viewer parses: a change on either side fails here) and cover the recording's times.
TEST(RoadslamViewApp, OpensRealMapAndBoundsFolders) {
  const auto& f = fixture();
  const std::string bin = fs::path(kBin).parent_path().string();
  const fs::path map = f.dir / "real_map", bounds = f.dir / "real_bounds";
  const std::string src = ROADSLAM_SOURCE_DIR;
  ASSERT_EQ(std::system((bin + "/roadslam-map --config " + src + "/ini/default.ini --input " + f.rawlog.string() +
                         " --out " + map.string() + " --quiet").c_str()), 0);
  ASSERT_EQ(std::system((bin + "/roadslam-bounds --config " + src + "/ini/bounds.ini --input " + f.rawlog.string() +
                         " --trajectory " + (map / "trajectory.tum").string() + " --out " + bounds.string() +
                         " --png-every 0 --quiet").c_str()), 0);
  const AppRun r = run(f.rawlog.string() + " --map " + map.string() + " --bounds " + bounds.string() + " --gt " +
                       (map / "trajectory_odometry.tum").string() + " --size 320x240 --render " +
                       (f.dir / "real.png").string() + " --at 0.3");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 6 frames, 0 loops, "), std::string::npos) << r.out;  // the box room's 6 sweeps
  EXPECT_NE(r.out.find(" 6 boundary sweeps, 6 ground-truth poses"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(f.dir / "real.png"));
  // --octomap: the map folder's map.bt occupied leaves instead of its point map
  const AppRun o = run(f.rawlog.string() + " --map " + map.string() + " --octomap --size 320x240 --render " +
                       (f.dir / "octo.png").string() + " --at 0.3");
  EXPECT_EQ(o.status, 0) << o.out;
  EXPECT_NE(o.out.find(" 0 map points, "), std::string::npos) << o.out;
  EXPECT_EQ(o.out.find(" 0 OctoMap voxels"), std::string::npos) << "the box room's walls are occupied: " << o.out;
  // --grid: the occupancy grid on the ground; its occupied cells as roadslam-map counted them
  const AppRun g = run(f.rawlog.string() + " --map " + map.string() + " --grid --camera top --size 320x240 --render " +
                       (f.dir / "grid.png").string() + " --at 0.3");
  ASSERT_EQ(g.status, 0) << g.out;
  const std::string summary = slurp(map / "summary.json");
  const auto key = summary.find("\"grid_occupied_cells\":");
  ASSERT_NE(key, std::string::npos) << summary;
  const std::size_t occupied = std::stoul(summary.substr(summary.find(':', key) + 1));
  ASSERT_GT(occupied, 0u);
  EXPECT_NE(g.out.find(" " + std::to_string(occupied) + " grid cells occupied"), std::string::npos) << g.out;
  const AppRun ng = run(f.rawlog.string() + " --map " + map.string() + " --camera top --size 320x240 --render " +
                        (f.dir / "nogrid.png").string() + " --at 0.3");
  ASSERT_EQ(ng.status, 0) << ng.out;
  const auto amber = [](const fs::path& png) {  // SceneColors::grid_occupied, exactly
    mrpt::img::CImage img;
    EXPECT_TRUE(img.loadFromFile(png.string()));
    int n = 0;
    for (int y = 30; y < 240; ++y)
      for (int x = 0; x < 320; ++x) {
        const auto* p = img.ptr<uint8_t>(x, y);  // BGR
        n += p[2] == 255 && p[1] == 200 && p[0] == 0;
      }
    return n;
  };
  EXPECT_GT(amber(f.dir / "grid.png"), amber(f.dir / "nogrid.png") + 20) << "occupied cells (the walls) seen from above";
}

// --run-slam: the pipeline's odometry over the replayed recording posts one frame per sweep, as many
// as roadslam-map gives on the same recording and config; a config with a typo stops before it runs.
TEST(RoadslamViewApp, RunSlamPostsTheOdometrysFrames) {
  const auto& f = fixture();
  const std::string src = ROADSLAM_SOURCE_DIR;
  const AppRun r = run(f.rawlog.string() + " --run-slam " + src + "/ini/default.ini --size 320x240 --render-sequence " +
                       (f.dir / "slam_seq").string() + " --every 3");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("odometry (--run-slam): 6 sweeps, 6 frames posted"), std::string::npos) << r.out;
  // the strip of the odometry's figures under the view: its ms-per-frame yellow, only with frames
  const auto yellow = [](const fs::path& png) {
    mrpt::img::CImage img;
    if (!img.loadFromFile(png.string())) return -1;
    int n = 0;
    for (int y = static_cast<int>(img.getHeight()) * 4 / 5; y < static_cast<int>(img.getHeight()); ++y)
      for (int x = 0; x < static_cast<int>(img.getWidth()); ++x) {
        const auto* p = img.ptr<uint8_t>(x, y);  // BGR
        n += p[2] > 120 && p[1] > 90 && p[0] < 60 && p[2] > p[1];  // yellow, scaled and blended
      }
    return n;
  };
  const fs::path with = f.dir / "slam_at.png", without = f.dir / "no_slam_at.png";
  ASSERT_EQ(run(f.rawlog.string() + " --run-slam " + src + "/ini/default.ini --size 640x360 --render " + with.string() +
                " --at 0.3").status, 0);
  ASSERT_EQ(run(f.rawlog.string() + " --size 640x360 --render " + without.string() + " --at 0.3").status, 0);
  EXPECT_GT(yellow(with), 5) << "ms per frame plotted";
  EXPECT_EQ(yellow(without), 0) << "no frames, no strip";
  const fs::path typo = f.dir / "typo.ini";
  std::ofstream(typo) << "[odometry]\nregistration_voxel_sise_m = 1\n";
  const AppRun bad = run(f.rawlog.string() + " --run-slam " + typo.string() + " --render " + (f.dir / "x.png").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.out.find(typo.string() + ":2: unknown key 'registration_voxel_sise_m' in [odometry]"), std::string::npos) << bad.out;
}

// The objects layer live and recorded: --run-slam with [objects] enabled draws the boxes the objects
// stage gives as it runs; roadslam-map with the same ini writes them to tracks.csv / objects.csv. Oracle:
// the box room's objects (khaki: no confirmed track) cover the same pixels either way, and none is drawn
// without the stage.
TEST(RoadslamViewApp, RunSlamDrawsTheObjectsRoadslamMapWrites) {
  const auto& f = fixture();
  const std::string bin = fs::path(kBin).parent_path().string(), src = ROADSLAM_SOURCE_DIR;
  std::stringstream ini;
  ini << std::ifstream(src + "/ini/default.ini").rdbuf();
  mrpt::config::CConfigFileMemory cfg(ini.str());  // set by section and key: comments stay as they are
  ASSERT_EQ(cfg.read_string("objects", "enabled", ""), "false");
  cfg.write("objects", "enabled", std::string("true"));
  const fs::path on = f.dir / "objects_on.ini", map = f.dir / "objects_map";
  std::ofstream(on) << cfg.getContent();
  ASSERT_EQ(std::system((bin + "/roadslam-map --config " + on.string() + " --input " + f.rawlog.string() + " --out " +
                         map.string() + " --quiet").c_str()), 0);
  // khaki (SceneColors::object_untracked, 200 200 120) by hue: lines are shaded at their edges
  const auto khaki = [](const fs::path& png) {
    mrpt::img::CImage img;
    std::vector<int> at;
    if (!img.loadFromFile(png.string())) return at;
    for (int y = 30; y < static_cast<int>(img.getHeight()) * 4 / 5; ++y)  // below the HUD, above the plots
      for (int x = 0; x < static_cast<int>(img.getWidth()); ++x) {
        const auto* p = img.ptr<uint8_t>(x, y);  // BGR
        const double m = std::max({p[0], p[1], p[2]});
        if (m > 70 && std::abs(p[2] / m - 1.0) < 0.12 && std::abs(p[1] / m - 1.0) < 0.12 && std::abs(p[0] / m - 0.6) < 0.12)
          at.push_back(y * 10000 + x);
      }
    return at;
  };
  const std::string common = f.rawlog.string() + " --size 480x360 --camera top --at 0.5 --render ";
  const fs::path live = f.dir / "objects_live.png", recorded = f.dir / "objects_recorded.png", none = f.dir / "objects_none.png";
  const AppRun lr = run(common + live.string() + " --run-slam " + on.string());
  ASSERT_EQ(lr.status, 0) << lr.out;
  ASSERT_EQ(run(common + recorded.string() + " --run-slam " + src + "/ini/default.ini --map " + map.string()).status, 0);
  ASSERT_EQ(run(common + none.string() + " --run-slam " + src + "/ini/default.ini").status, 0);
  const auto a = khaki(live), b = khaki(recorded);
  EXPECT_GT(a.size(), 20u) << "the box room's objects";
  // every pixel of one within a pixel of the other (objects.csv keeps millimetres, live has doubles)
  const auto near = [](const std::vector<int>& from, const std::vector<int>& to) {
    int far = 0;
    for (int q : from) {
      bool hit = false;
      for (int dy = -1; dy <= 1 && !hit; ++dy)
        for (int dx = -1; dx <= 1 && !hit; ++dx) hit = std::binary_search(to.begin(), to.end(), q + dy * 10000 + dx);
      far += !hit;
    }
    return far;
  };
  EXPECT_EQ(near(a, b), 0) << "live objects where roadslam-map wrote none";
  EXPECT_EQ(near(b, a), 0) << "roadslam-map's objects missing live";
  EXPECT_TRUE(khaki(none).empty());
}

// A pcap opens directly: converted once into the cache (the same observations as roadslam-rawlog's
// conversion), reused while unchanged. --video encodes the sequence through ffmpeg.
TEST(RoadslamViewApp, OpensAPcapAndWritesAVideo) {
  const auto& f = fixture();
  const fs::path pcap = f.dir / "boxroom.pcap";
  fs::copy_file(std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap", pcap, fs::copy_options::overwrite_existing);
  const AppRun first = run(pcap.string() + " --size 320x240 --render " + (f.dir / "pcap.png").string());
  ASSERT_EQ(first.status, 0) << first.out;
  EXPECT_NE(first.out.find("converting " + pcap.string() + " into " + (kCache / "roadslam" / "boxroom-").string()),
            std::string::npos) << first.out;
  EXPECT_FALSE(fs::exists(pcap.string() + ".rawlog"));
  const AppRun viaRawlog = run(f.rawlog.string() + " --size 320x240 --render " + (f.dir / "rawlog.png").string());
  EXPECT_EQ(observationsIn(first.out), observationsIn(viaRawlog.out)) << first.out << viaRawlog.out;
  const AppRun second = run(pcap.string() + " --size 320x240 --render " + (f.dir / "pcap.png").string());
  EXPECT_EQ(second.out.find("converting"), std::string::npos) << "the conversion is kept: " << second.out;

  const fs::path mp4 = f.dir / "boxroom.mp4";
  const AppRun v = run(f.rawlog.string() + " --size 320x240 --video " + mp4.string() + " --every 2");
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
    EXPECT_EQ(v.status, 1);
    EXPECT_NE(v.out.find("--video needs ffmpeg"), std::string::npos) << v.out;
    return;
  }
  ASSERT_EQ(v.status, 0) << v.out;
  EXPECT_NE(v.out.find(": 3 frames at 10 per second"), std::string::npos) << v.out;
  const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                            "-of csv=p=0 " + mp4.string();
  FILE* p = popen(probe.c_str(), "r");
  int frames = 0;
  ASSERT_EQ(std::fscanf(p, "%d", &frames), 1);
  pclose(p);
  EXPECT_EQ(frames, 3) << "ffprobe counts the encoded frames";
}

// A KITTI folder opens directly: its .bin sweeps as point-cloud observations, one per file, stamped
// from its times.txt.
TEST(RoadslamViewApp, OpensAKittiFolder) {
  const auto& f = fixture();
  const fs::path kitti = f.dir / "kitti" / "velodyne_points" / "data";
  fs::create_directories(kitti);
  std::ofstream times(f.dir / "kitti" / "velodyne_points" / "times.txt");
  for (int k = 0; k < 3; ++k) {
    roadslam::Scan s;
    for (int i = 0; i < 2000; ++i) {
      roadslam::ScanPoint p;
      const double a = i * 0.00314;
      p.x = static_cast<float>(10 * std::cos(a)), p.y = static_cast<float>(10 * std::sin(a)), p.z = -1.7f;
      p.intensity = 0.5f;
      s.points.push_back(p);
    }
    char name[32];
    std::snprintf(name, sizeof name, "%010d.bin", k);
    roadslam::datasets::writeKittiBin((kitti / name).string(), s);
    times << 100.0 + k << "\n";
  }
  times.close();
  const auto beside = listing(kitti.parent_path());
  const AppRun r = run(kitti.string() + " --size 320x240 --render " + (f.dir / "kitti.png").string() + " --at 1");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(listing(kitti.parent_path()), beside) << "nothing written beside the folder";
  EXPECT_NE(r.out.find("converting the KITTI folder"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(": 3 observations over 2.0 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("observation 1"), std::string::npos) << r.out;
}

// --can with the car's vehicle ini: the simulator's CAN log decoded with its DBC, speed and yaw rate
// plotted under the view; the top speed against the simulator's own vehicle ground truth.
TEST(RoadslamViewApp, CanSignalsOfTheDriveArePlotted) {
  const auto& f = fixture();
  const std::string bin = fs::path(kBin).parent_path().string(), src = ROADSLAM_SOURCE_DIR;
  const fs::path sim = f.dir / "sim4";
  ASSERT_EQ(std::system((bin + "/roadslam-sim --config " + src + "/ini/sim/urban-loop.ini --duration 4 --out " +
                         sim.string() + " > /dev/null 2>&1").c_str()), 0);
  double v_gt = 0;
  {
    std::ifstream csv(sim / "gt_vehicle.csv");
    std::string line;
    std::getline(csv, line);  // t,x,y,z,yaw_rad,pitch_rad,roll_rad,speed_mps,...
    while (std::getline(csv, line)) {
      std::stringstream ss(line);
      std::string cell;
      for (int c = 0; c <= 7 && std::getline(ss, cell, ','); ++c)
        if (c == 7) v_gt = std::max(v_gt, std::stod(cell));
    }
  }
  const fs::path png = f.dir / "can.png";
  const AppRun r = run((sim / "velodyne.pcap").string() + " --can " + (sim / "can.log").string() + " --vehicle " + src +
                       "/ini/vehicles/roadslam-sim.ini --size 640x360 --render " + png.string() + " --at 3");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto at = r.out.find("CAN: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  std::size_t samples = 0;
  double span = 0, v = 0;
  ASSERT_EQ(std::sscanf(r.out.c_str() + at, "CAN: %zu samples over %lf s, speed up to %lf m/s", &samples, &span, &v), 3) << r.out;
  EXPECT_NEAR(static_cast<double>(samples), 80.0, 5.0) << "4 s at 20 Hz";
  EXPECT_NEAR(v, v_gt, 0.05 * v_gt + 0.2) << "the simulator writes a wheel-speed scale error of a few per cent";
  const int green = speedCurvePixels(png);
  EXPECT_GT(green, 10) << "the speed curve";
}

// Two different drives of the same name, velodyne.pcap (as the simulator names every capture), in two
// folders: each shows its own observations (the oracle: roadslam-rawlog's conversion of each), and
// nothing is written beside either; reopened, both conversions are reused; a pcap changed in place
// is converted again.
TEST(RoadslamViewApp, TwoPcapsOfTheSameNameShowTheirOwnDrive) {
  const auto& f = fixture();
  const fs::path a = f.dir / "driveA", b = f.dir / "driveB", oracle = f.dir / "oracle";
  for (const auto& d : {a, b, oracle}) fs::create_directories(d);
  const std::string box = slurp(std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap");
  const std::string shorter = wholeRecordsUpTo(box, box.size() * 6 / 10);
  std::ofstream(a / "velodyne.pcap", std::ios::binary) << box;
  std::ofstream(b / "velodyne.pcap", std::ios::binary) << shorter;
  const auto expected = [&oracle](const fs::path& pcap, const std::string& name) {
    const auto s = roadslam::sources::convertToRawlog(pcap.string(), (oracle / name).string());
    return std::to_string(s.observations + s.gps);
  };
  const std::string n_a = expected(a / "velodyne.pcap", "a.rawlog"), n_b = expected(b / "velodyne.pcap", "b.rawlog");
  ASSERT_NE(n_a, n_b);
  const auto before_a = listing(a), before_b = listing(b);
  const auto view = [&f](const fs::path& pcap) { return run(pcap.string() + " --size 160x120 --render " + (f.dir / "same-name.png").string()); };

  const AppRun ra = view(a / "velodyne.pcap"), rb = view(b / "velodyne.pcap");
  ASSERT_EQ(ra.status, 0) << ra.out;
  ASSERT_EQ(rb.status, 0) << rb.out;
  EXPECT_EQ(observationsIn(ra.out), n_a) << ra.out;
  EXPECT_EQ(observationsIn(rb.out), n_b) << "the second drive, not the first one's conversion: " << rb.out;
  EXPECT_NE(rb.out.find("converting " + (b / "velodyne.pcap").string()), std::string::npos) << rb.out;
  EXPECT_EQ(listing(a), before_a);
  EXPECT_EQ(listing(b), before_b);

  const AppRun again = view(a / "velodyne.pcap");
  EXPECT_EQ(again.out.find("converting"), std::string::npos) << again.out;
  EXPECT_EQ(observationsIn(again.out), n_a) << again.out;

  std::ofstream(a / "velodyne.pcap", std::ios::binary | std::ios::trunc) << shorter;  // drive A replaced
  const AppRun changed = view(a / "velodyne.pcap");
  EXPECT_NE(changed.out.find("converting " + (a / "velodyne.pcap").string()), std::string::npos) << changed.out;
  EXPECT_EQ(observationsIn(changed.out), n_b) << changed.out;
  EXPECT_EQ(listing(a), before_a);
}

// --no-index-cache, or a cache folder that cannot be made: the conversion goes into a private
// temporary folder that is gone when the viewer exits; nothing is kept, nothing written beside the input.
TEST(RoadslamViewApp, WithoutACacheNothingIsKept) {
  const auto& f = fixture();
  const fs::path in = f.dir / "nocache", xdg = f.dir / "nocache-xdg";
  fs::create_directories(in);
  fs::create_directories(xdg);
  fs::copy_file(std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap", in / "velodyne.pcap",
                fs::copy_options::overwrite_existing);
  std::ofstream(f.dir / "a-file") << "x";
  const auto before = listing(in);
  const std::string args = (in / "velodyne.pcap").string() + " --size 160x120 --render " + (f.dir / "nocache.png").string();
  const struct {
    std::string prefix, args, note;
  } cases[] = {
      {"env XDG_CACHE_HOME=" + xdg.string() + " ", args + " --no-index-cache", ""},
      {"env XDG_CACHE_HOME=" + (f.dir / "a-file").string() + " ", args, "warning: cannot create the cache folder '" +
                                                                            (f.dir / "a-file" / "roadslam").string() + "'"},
  };
  for (const auto& c : cases) {
    const AppRun r = run(c.args, c.prefix);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NE(r.out.find(c.note), std::string::npos) << r.out;
    const auto at = r.out.find(" into "), end = r.out.find(" (removed at exit)");
    ASSERT_TRUE(at != std::string::npos && end != std::string::npos) << r.out;
    const fs::path conversion = r.out.substr(at + 6, end - at - 6);
    EXPECT_FALSE(fs::exists(conversion.parent_path())) << conversion << " is left";
    EXPECT_EQ(r.out.find("kept in"), std::string::npos) << r.out;
    EXPECT_EQ(listing(in), before);
  }
  EXPECT_FALSE(fs::exists(xdg / "roadslam")) << "--no-index-cache keeps nothing in the cache folder";  // (Mesa keeps its own)
}

TEST(RoadslamViewApp, BadInputsExitWithOneLineNamingTheProblem) {
  const auto& f = fixture();
  const fs::path script = f.dir / "bad_script.txt";
  std::ofstream(script) << "wait 0.1\njump 3\n";
  const fs::path noise = f.dir / "noise.rawlog";
  {
    std::ofstream n(noise, std::ios::binary);
    for (int i = 0; i < 20000; ++i) n.put(char((i * 7919) % 251));
  }
  const struct {
    std::string args, prefix, message;
  } cases[] = {
      {f.rawlog.string() + " --script " + script.string(), "", script.string() + ":2: unknown command 'jump'"},
      {f.rawlog.string() + " --color purple --render x.png", "", "colour mode 'purple'"},
      {f.rawlog.string(), "env -u DISPLAY -u WAYLAND_DISPLAY ", "no display"},
      {noise.string() + " --render " + (f.dir / "n.png").string(), "", "holds no readable observation"},
  };
  for (const auto& c : cases) {
    const AppRun r = run(c.args, c.prefix);
    EXPECT_EQ(r.status, 1) << c.args << ": " << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << ": " << r.out;
    EXPECT_EQ(r.out.rfind("roadslam-view: ", 0), 0u) << r.out;
  }
  EXPECT_FALSE(fs::exists(f.dir / "n.png"));
}

TEST(RoadslamViewWindow, ScriptDrivesTheRealWindowUnderXvfb) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb; scripts/setup.sh installs it)";
  const auto& f = fixture();
  const fs::path s0 = f.dir / "win0.png", s1 = f.dir / "win1.png", script = f.dir / "script.txt";
  std::ofstream(script) << "# start, step to the next sweep, top view, select observation 3\n"
                        << "wait 0.3\nscreenshot " << s0.string() << "\n"
                        << "key right\nkey v\nkey h\nselect 3\nwait 0.2\nscreenshot " << s1.string() << "\n"
                        << "# play at 1/8 speed for 0.8 s: about 0.1 s of the recording\n"
                        << "key home\nkey -\nkey -\nkey -\nkey space\nwait 0.8\nscreenshot " << (f.dir / "win2.png").string()
                        << "\nquit\n";
  const AppRun r = run(f.rawlog.string() + " --map " + f.map.string() + " --size 960x540 --script " + script.string(),
                       "timeout 60 xvfb-run -a -s '-screen 0 1024x600x24' ");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("screenshot " + s0.string() + " t=0.000 obs=0"), std::string::npos) << r.out;
  // observation 3 is a GPS record at 0.101 s: the scene shows the sweep before it, observation 2
  EXPECT_NE(r.out.find("screenshot " + s1.string() + " t=0.101 obs=2"), std::string::npos) << r.out;
  const auto at = r.out.find("win2.png t=");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double played = std::stod(r.out.substr(at + 11));
  EXPECT_GT(played, 0.05) << "playing moved the time";
  EXPECT_LT(played, 0.44) << "at 1/8 speed, not at the end (0.45 s) as at 1x";
  mrpt::img::CImage a, b;
  ASSERT_TRUE(a.loadFromFile(s0.string()));
  ASSERT_TRUE(b.loadFromFile(s1.string()));
  ASSERT_EQ(a.getWidth(), 960u);
  ASSERT_EQ(a.getHeight(), 540u);
  // the scene between the timeline (bottom left) and the list (right): the sweep's points
  EXPECT_GT(count(a, 300, 40, 480, 350).coloured, 300) << "sweep points in the 3D view";
  // the trajectory's colour in the window (the map folder's path up to the box room)
  EXPECT_GT(count(a, 0, 0, 490, 540).magenta + count(b, 0, 0, 490, 540).magenta, 10);
  // the observation list (right panel) filled with rows of text
  EXPECT_GT(count(b, 500, 60, 960, 480).bright, 1500) << "observation rows";
  // "select 3" shows observation 3's details: a GPS record (the box room has one after every sweep)
  EXPECT_NE(count(b, 490, 420, 960, 540).bright, count(a, 490, 420, 960, 540).bright) << "details changed";
  // top view after "key v" changes the picture
  EXPECT_NE(slurp(s0), slurp(s1));
}

// ---- live views: the simulator streams real VLP-16 packets over loopback UDP ----
namespace {

// A loopback UDP port free now (the kernel's choice; released for the viewer to bind).
int freeUdpPort() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}

// Runs the viewer with \p args on a thread while the simulator streams \p duration_s of the urban
// loop to \p port after \p delay_s (the viewer binds first); returns the viewer's run and the
// simulator's packets_sent.
std::pair<AppRun, std::size_t> viewWhileStreaming(const std::string& args, const std::string& prefix, int port,
                                                  const fs::path& sim_dir, double delay_s, double duration_s) {
  AppRun view;
  std::thread viewer([&] { view = run(args, prefix); });
  std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
  const std::string bin = fs::path(kBin).parent_path().string(), src = ROADSLAM_SOURCE_DIR;
  const int sim = std::system((bin + "/roadslam-sim --config " + src + "/ini/sim/urban-loop.ini --duration " +
                               std::to_string(duration_s) + " --out " + sim_dir.string() + " --udp 127.0.0.1:" +
                               std::to_string(port) + " > /dev/null 2>&1").c_str());
  viewer.join();
  EXPECT_EQ(sim, 0);
  const std::string summary = slurp(sim_dir / "summary.json");
  const auto at = summary.find("\"packets_sent\":");
  std::size_t sent = 0;
  if (at != std::string::npos) sent = std::stoul(summary.substr(summary.find(':', at) + 1));
  return {view, sent};
}

// "... VELODYNE: 0 pkt/s 785 pkt, ..." -> 785
std::size_t packetsReceived(const std::string& out, const std::string& label) {
  const auto at = out.find(label + ": ");
  if (at == std::string::npos) return 0;
  const auto pkt = out.find("pkt/s ", at);
  return pkt == std::string::npos ? 0 : std::stoul(out.substr(pkt + 6));
}

// "udp:PORT: 19 observations over ..." -> 19
std::size_t liveObservations(const std::string& out, const std::string& name) {
  const auto at = out.find(name + ": ");
  return at == std::string::npos ? 0 : std::stoul(out.substr(at + name.size() + 2));
}

}  // namespace

// --udp PORT headless: every packet the simulator sent is received, the sweeps are listed as they
// came, the newest is drawn, and nothing is written (monitoring).
TEST(RoadslamViewLive, UdpShowsWhatTheSimulatorSends) {
  const auto& f = fixture();
  const fs::path dir = f.dir / "live_udp";
  fs::create_directories(dir);
  const int port = freeUdpPort();
  const auto [view, sent] = viewWhileStreaming(
      "--udp " + std::to_string(port) + " --render live.png --size 640x360 --sweeps 1000 --timeout 4", "cd " + dir.string() + " && ",
      port, f.dir / "live_udp_sim", 0.7, 2.0);
  ASSERT_EQ(view.status, 0) << view.out;
  ASSERT_GT(sent, 1000u);
  EXPECT_EQ(packetsReceived(view.out, "VELODYNE"), sent) << view.out;
  const std::size_t n = liveObservations(view.out, "udp:" + std::to_string(port));
  EXPECT_GE(n, 18u) << "2 s at 10 Hz, less the sweep in progress: " << view.out;
  EXPECT_LE(n, 21u) << view.out;
  EXPECT_NE(view.out.find("of 1000 sweeps within 4 s"), std::string::npos) << view.out;
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile((dir / "live.png").string()));
  EXPECT_GT(count(img, 0, 30, 640, 360).coloured, 500) << "the newest sweep's points";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "monitoring writes only the PNG";
}

// --grab INI --record DIR: the grab ini's LiDAR and its CAN source (the simulator's CAN log
// replayed at its pace), shown live and recorded; the recording holds what was shown, and its
// session folder (segments cut every second) replays as one recording.
TEST(RoadslamViewLive, GrabIniWithCanShowsAndRecords) {
  const auto& f = fixture();
  const std::string bin = fs::path(kBin).parent_path().string(), src = ROADSLAM_SOURCE_DIR;
  const fs::path dir = f.dir / "live_grab", can_sim = dir / "can_sim", rec = dir / "rec";
  fs::create_directories(dir);
  ASSERT_EQ(std::system((bin + "/roadslam-sim --config " + src + "/ini/sim/urban-loop.ini --duration 3 --out " +
                         can_sim.string() + " > /dev/null 2>&1").c_str()), 0);
  const int port = freeUdpPort();
  const fs::path ini = dir / "grab.ini";
  std::ofstream(ini) << "[grab]\nsensors = lidar\ncan = can\nflush_period_ms = 200\nrotate_period_s = 1\n"
                     << "[lidar]\ndata_port = " << port << "\nposition_port = 0\nbind_address = 127.0.0.1\n"
                     << "model = vlp16\nsensor_label = VELODYNE\n"
                     << "[can]\nsource = candump\ncandump_file = " << (can_sim / "can.log").string()
                     << "\ncandump_realtime = true\nrestamp = true\nvehicle_ini = " << src << "/ini/vehicles/roadslam-sim.ini\n";
  const fs::path png = dir / "grab.png";
  const auto [view, sent] = viewWhileStreaming("--grab " + ini.string() + " --record " + rec.string() + " --render " +
                                                   png.string() + " --size 640x360 --sweeps 1000 --timeout 4",
                                               "", port, dir / "udp_sim", 0.7, 2.0);
  ASSERT_EQ(view.status, 0) << view.out;
  EXPECT_EQ(packetsReceived(view.out, "VELODYNE"), sent) << view.out;
  const auto at = view.out.find(" CAN samples");
  ASSERT_NE(at, std::string::npos) << view.out;
  const std::size_t can_samples = std::stoul(view.out.substr(view.out.rfind(", ", at) + 2));
  EXPECT_GT(can_samples, 40u) << "the car's odometry at 20 Hz for 3 s: " << view.out;
  const std::size_t shown = liveObservations(view.out, ini.string());
  ASSERT_GT(shown, 50u) << view.out;
  std::size_t observations = 0, odometry = 0, sweeps = 0, segments = 0;
  for (const auto& seg : roadslam::rawlog::RawlogSession::segmentsOf(rec.string())) {  // cut every second
    auto recorded = roadslam::rawlog::RawlogIndex::open(seg);
    ++segments;
    observations += recorded->size();
    for (std::size_t i = 0; i < recorded->size(); ++i) {
      odometry += recorded->className(i) == "CObservationOdometry";
      sweeps += recorded->className(i) == "CObservationVelodyneScan";
    }
  }
  EXPECT_GE(segments, 3u);
  EXPECT_GE(observations, shown) << "the recording holds what was shown, and what came until it stopped";
  EXPECT_GT(odometry, 0u);
  EXPECT_GE(sweeps, 19u);
  // the session folder replays as one recording, its segments in order, and the odometry runs on it
  // (a sequence waits for the odometry to finish the whole recording)
  const AppRun replay = run(rec.string() + " --render-sequence " + (dir / "session").string() + " --every 50 --size 320x240" +
                            " --run-slam " + src + "/ini/default.ini");
  ASSERT_EQ(replay.status, 0) << replay.out;
  EXPECT_EQ(liveObservations(replay.out, rec.string()), observations) << replay.out;
  EXPECT_NE(replay.out.find("(" + std::to_string(segments) + " segments)"), std::string::npos) << replay.out;
  const auto slam = replay.out.find("odometry (--run-slam): ");
  ASSERT_NE(slam, std::string::npos) << replay.out;
  EXPECT_GE(std::stoul(replay.out.substr(slam + 23)), sweeps - 1) << "every sweep of every segment: " << replay.out;
  EXPECT_TRUE(fs::exists(rec / "summary.json")) << "recorded as roadslam-grab records";
  const int green = speedCurvePixels(png);
  EXPECT_GT(green, 10) << "the speed curve under the view";
}

// The live window under Xvfb: the sweeps appear in the view and the list while the simulator sends.
TEST(RoadslamViewWindow, LiveWindowShowsTheSweepsAsTheyArrive) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb; scripts/setup.sh installs it)";
  const auto& f = fixture();
  const fs::path shot = f.dir / "live_win.png", script = f.dir / "live_script.txt";
  std::ofstream(script) << "wait 4\nscreenshot " << shot.string() << "\nquit\n";
  const int port = freeUdpPort();
  const auto [view, sent] = viewWhileStreaming("--udp " + std::to_string(port) + " --size 960x540 --script " + script.string(),
                                               "timeout 60 xvfb-run -a -s '-screen 0 1024x600x24' ", port,
                                               f.dir / "live_win_sim", 1.5, 2.0);
  ASSERT_EQ(view.status, 0) << view.out;
  const auto at = view.out.find("live_win.png t=");
  ASSERT_NE(at, std::string::npos) << view.out;
  const auto obs = view.out.find("obs=", at);
  ASSERT_NE(obs, std::string::npos) << view.out;
  EXPECT_GE(std::stoul(view.out.substr(obs + 4)), 15u) << "the newest of ~20 sweeps is shown: " << view.out;
  mrpt::img::CImage a;
  ASSERT_TRUE(a.loadFromFile(shot.string()));
  EXPECT_GT(count(a, 0, 40, 480, 350).coloured, 300) << "sweep points in the 3D view";
  EXPECT_GT(count(a, 500, 60, 960, 480).bright, 1500) << "observation rows";
}

// --run-slam on a live sensor: the odometry runs on the sweeps as they arrive. Oracle: roadslam-map
// over the simulator's pcap of the same stream; the live frames are the same poses (the packets are
// the same bytes; only their host receive stamps differ from the capture's).
TEST(RoadslamViewLive, OdometryOnTheLiveSensorEqualsTheRecordedRun) {
  const auto& f = fixture();
  const fs::path dir = f.dir / "live_slam";
  fs::create_directories(dir);
  const std::string bin = fs::path(kBin).parent_path().string(), src = ROADSLAM_SOURCE_DIR;
  const int port = freeUdpPort();
  const auto [view, sent] = viewWhileStreaming("--udp " + std::to_string(port) + " --run-slam " + src +
                                                   "/ini/default.ini --render " + (dir / "slam.png").string() +
                                                   " --size 320x240 --sweeps 32 --timeout 10",
                                               "", port, dir / "sim", 0.7, 4.5);
  ASSERT_EQ(view.status, 0) << view.out;
  const auto at = view.out.find("odometry (--run-slam): ");
  ASSERT_NE(at, std::string::npos) << view.out;
  std::size_t sweeps = 0, frames = 0;
  double x = 0, y = 0, z = 0;
  ASSERT_EQ(std::sscanf(view.out.c_str() + at, "odometry (--run-slam): %zu sweeps, %zu frames posted, the last at %lf %lf %lf m",
                        &sweeps, &frames, &x, &y, &z), 5) << view.out;
  EXPECT_GE(frames, 31u) << view.out;
  ASSERT_EQ(std::system((bin + "/roadslam-map --config " + src + "/ini/default.ini --input " + (dir / "sim/velodyne.pcap").string() +
                         " --out " + (dir / "map").string() + " --quiet").c_str()), 0);
  std::ifstream tum(dir / "map/trajectory_odometry.tum");
  std::vector<std::array<double, 3>> poses;
  for (std::string line; std::getline(tum, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double t, px, py, pz;
    ss >> t >> px >> py >> pz;
    poses.push_back({px, py, pz});
  }
  ASSERT_GE(poses.size(), frames);
  const auto& p = poses[frames - 1];
  EXPECT_NEAR(x, p[0], 0.01) << "frame " << frames - 1;
  EXPECT_NEAR(y, p[1], 0.01);
  EXPECT_NEAR(z, p[2], 0.01);
  EXPECT_GT(std::hypot(p[0], p[1]), 0.5) << "the car moved (it starts from standing)";
}
