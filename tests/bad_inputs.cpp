// The bad-input table: every app that reads files, inis or a command line is run on bad
// ones as a user would, as a child process. Each row gives the exit code and a piece of the message
// the user must see (documented in docs/apps/*.md); no row may crash (a signal), hang, or leave a
// temporary or half-written file in its output folder. The same table runs against sanitizer builds
// (ASan + UBSan) with ROADSLAM_BIN_DIR pointing at them (ctest label `sanitize`).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string kSrc = ROADSLAM_SOURCE_DIR;

std::string binDir() {
  const char* env = std::getenv("ROADSLAM_BIN_DIR");
  return env && *env ? env : std::string(ROADSLAM_BINARY_DIR) + "/bin";
}

/// Working folder of the table: bad files are made here once.
const fs::path& work() {
  static const fs::path w = [] {
    const fs::path p = fs::path(ROADSLAM_BINARY_DIR) / "test-out" / ("bad-inputs-" + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::create_directories(p / "out");  // rows' outputs: {O} a folder, or {O}.png beside it
    return p;
  }();
  return w;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

std::string randomBytes(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::string s(n, '\0');
  for (auto& c : s) c = static_cast<char>(rng() & 0xFF);
  return s;
}

std::string fileText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

/// \p pcap (classic pcap, Ethernet/IPv4/UDP records) with the product byte of every Velodyne data
/// packet (1206-byte payload to port 2368, byte 1205) set to \p product.
std::string withProductByte(std::string pcap, unsigned char product) {
  constexpr size_t kGlobalHeader = 24, kRecordHeader = 16, kUdpPayload = 42, kPayload = 1206;
  for (size_t at = kGlobalHeader; at + kRecordHeader <= pcap.size();) {
    uint32_t len = 0;
    std::memcpy(&len, pcap.data() + at + 8, 4);  // incl_len, host (little-endian) byte order
    const size_t rec = at + kRecordHeader;
    const bool data = len == kUdpPayload + kPayload && rec + len <= pcap.size() &&
                      static_cast<unsigned char>(pcap[rec + 36]) == 2368 / 256 &&
                      static_cast<unsigned char>(pcap[rec + 37]) == 2368 % 256;
    if (data) pcap[rec + kUdpPayload + 1205] = static_cast<char>(product);
    at = rec + len;
  }
  return pcap;
}

/// The bad files every row may name as {W}/...
void makeFiles() {
  static bool done = false;
  if (done) return;
  done = true;
  const fs::path w = work();
  // roadslam-view's conversions and indexes go into the user's cache folder: the table's own one
  setenv("XDG_CACHE_HOME", (w / "xdg-cache").c_str(), 1);
  const std::string def = fileText(kSrc + "/ini/default.ini");
  write(w / "random.rawlog", randomBytes(20000, 1));
  write(w / "random.pcap", randomBytes(20000, 2));
  write(w / "empty.pcap", "");
  write(w / "empty.rawlog", "");
  const std::string pcap = fileText(kSrc + "/rawlogs/boxroom-vlp16.pcap");
  write(w / "truncated.pcap", pcap.substr(0, 300000));
  write(w / "vlp16-hdl32-byte.pcap", withProductByte(pcap, 0x21));  // a VLP-16 capture with the HDL-32E byte
  write(w / "notes.txt", "not a recording\n");
  fs::create_directories(w / "empty-dir");
  write(w / "typo-key.ini", def + "\n[odometry]\nvoxel_sise_m = 0.5\n");
  write(w / "typo-section.ini", def + "\n[odometri]\nmap_radius_m = 50\n");
  write(w / "not-a-number.ini", "[preprocess]\nvoxel_size_m = abc\n");
  write(w / "bad-matcher.ini", "[odometry]\nmatcher = kiss\n");
  write(w / "bad-graph-optimizer.ini", "[pose_graph]\noptimizer = g2o\n");
  write(w / "negative-voxel.ini", "[odometry]\nmap_voxel_m = -1\n");
  write(w / "seen-through-zero-tolerance.ini", "[seen_through]\nray_tolerance_m = 0\n");
  write(w / "tracking-negative-reid.ini", "[objects]\nenabled = true\n[tracking]\nreid_gate_m = -1\n");
  write(w / "objects-reach-inside-body.ini", "[objects]\nmax_range_m = 1\n");
  write(w / "objects-negative-free-lag.ini", "[objects]\nenabled = true\nfree_space_lag_s = -1\n");
  write(w / "objects-free-lag-too-long.ini", "[objects]\nenabled = true\nfree_space_lag_s = 60\n");
  write(w / "tracking-free-fraction-above-one.ini", "[objects]\nenabled = true\n[tracking]\nmoving_min_free_fraction = 1.5\n");
  write(w / "bad-spin.ini", "[kitti]\nspin = sideways\n");
  write(w / "bad-stamp-reference.ini", "[kitti]\nstamp_reference = centre\n");
  write(w / "bad-bool.ini", "[odometry]\ndeskew = maybe\n");
  {
    std::string m = def;  // [velodyne] model = auto, its first line of that text, set to hdl32
    m.replace(m.find("model = auto"), 12, "model = hdl32");
    write(w / "model-hdl32.ini", m);
  }
  write(w / "name-and-alias.ini", "[preprocess]\nego_radius_m = 2.5\n; the thesis's name\nrad = 3\n");
  write(w / "bad-motion-model.ini", "; the tracker's filter\n[tracking]\n\nmotion_model = kalman\n");
  write(w / "bad-gnss-optimizer.ini", "[gnss_fusion]\noptimizer = g2o\n");
  write(w / "bounds-typo.ini", fileText(kSrc + "/ini/bounds.ini") + "\n[boundary]\ncurb_min_jmup_m = 0.1\n");
  {
    std::string b = fileText(kSrc + "/ini/bounds.ini");
    b.replace(b.find("cluster_method = range_image"), 28, "cluster_method = kmeans");
    write(w / "bounds-bad-cluster.ini", b);
  }
  write(w / "map-bad-tracks" / "trajectory.tum", "0.0 0 0 0 0 0 0 1\n");
  write(w / "map-bad-tracks" / "frames.csv",
        "index,stamp_s,status,point_times,deskewed,keyframe,x_m,y_m,z_m,points_in,points_registered,iterations,inliers,"
        "fitness_m,threshold_m,weak_directions,motion_information,ms_preprocess,ms_register,ms_map,ms_total,reason\n"
        "0,0.0,ok,none,0,0,0,0,0,0,0,0,0,0,0,0,nan,0,0,0,0,\n");
  write(w / "map-bad-tracks" / "summary.json",
        R"({"frames": 1, "keyframes": 0, "failed_frames": 0, "frames_by_status": {"ok": 1}, "ms_per_frame_mean": 0,
            "ms_per_frame_p50": 0, "ms_per_frame_p95": 0, "ms_per_frame_max": 0, "complete": true, "warnings": []})");
  write(w / "map-bad-tracks" / "run.json", R"({"format": "roadslam-run", "format_version": 1, "program": "roadslam-map"})");
  write(w / "map-old" / "trajectory.tum", "0.0 0 0 0 0 0 0 1\n");  // a map folder from before run.json
  write(w / "map-bad-tracks" / "tracks.csv",
        "frame,stamp_s,track_id,x,y,vx,vy,speed_mps,heading_rad,length_m,width_m,z_min,z_max,moving,hits,misses,age_s\n"
        "0,0.0,7,abc,0,0,0,0,0,4.5,1.8,-1.9,-0.4,1,3,0,0.3\n");
  write(w / "a-file", "x");
  write(w / "exp-typo.ini", "[experiment]\nbase_config = " + kSrc + "/ini/default.ini\n[dataset.x]\ninput = " +
                                (w / "truncated.pcap").string() + "\n[sweep]\nodometry.registration_voxel_sise_m = 1\n");
  write(w / "exp-no-input.ini", "[experiment]\nbase_config = " + kSrc + "/ini/default.ini\n[dataset.x]\ninput = " +
                                    (w / "nope.pcap").string() + "\n");
  // Output folders that are not the run's to write: another program's, a data folder, a map run
  // (made by roadslam-map itself: a prior map for --prior-map, then --out on it), for the rows *-into-*
  write(w / "sim-folder" / "velodyne.pcap", pcap.substr(0, 100000));
  write(w / "sim-folder" / "run.json", R"({"format": "roadslam-run", "format_version": 1, "program": "roadslam-sim",
      "input": "urban-loop seed 1", "input_id": "/x/urban-loop.ini?seed=1&duration_s=0", "state": "complete"})");
  write(w / "data-folder" / "drive.pcap", pcap.substr(0, 100000));
  // side inputs of another drive: a CAN log and poses of 2001, beside recordings of other times
  write(w / "other-drive.log", "(1000000000.000000) can0 123#0011223344556677\n(1000000060.000000) can0 123#0011223344556677\n");
  write(w / "other-drive.tum", "1000000000.0 0 0 0 0 0 0 1\n1000000010.0 1 0 0 0 0 0 1\n");
  write(w / "data-folder-force" / "drive.pcap", pcap.substr(0, 100000));
  // a long KITTI folder for the signal row: one sweep under 3000 names (hard links, no space)
  {
    std::string sweep;
    for (int i = 0; i < 20000; ++i) {
      const float a = static_cast<float>(i) * 0.0031f, r = 5.0f + static_cast<float>(i % 50);
      const float rec[4] = {r * std::cos(a), r * std::sin(a), -1.7f + 0.01f * static_cast<float>(i % 300), 0.5f};
      sweep.append(reinterpret_cast<const char*>(rec), sizeof rec);
    }
    write(w / "kitti-long" / "000000.bin", sweep);
    for (int i = 1; i < 3000; ++i) {
      char name[16];
      std::snprintf(name, sizeof name, "%06d.bin", i);
      fs::create_hard_link(w / "kitti-long" / "000000.bin", w / "kitti-long" / name);
    }
  }
  // KITTI folders: one good sweep, one damaged; a times file of the wrong length
  std::string bin;
  for (int i = 0; i < 2000; ++i) {
    const float rec[4] = {10.0f + static_cast<float>(i % 40), static_cast<float>(i / 40) - 25.0f, -1.7f, 0.5f};
    bin.append(reinterpret_cast<const char*>(rec), sizeof rec);
  }
  write(w / "kitti-damaged" / "000000.bin", bin);
  write(w / "kitti-two" / "000000.bin", bin);  // a recording for roadslam-view rows
  write(w / "kitti-two" / "000001.bin", bin);
  write(w / "kitti-damaged" / "000001.bin", bin.substr(0, 1001));
  const std::string prior = binDir() + "/roadslam-map --config " + kSrc + "/ini/default.ini --input " + (w / "kitti-two").string() +
                            " --out " + (w / "prior-map").string() + " --quiet 2> /dev/null";
  if (std::system(prior.c_str()) != 0) ADD_FAILURE() << "could not make the prior map: " << prior;
  write(w / "kitti-damaged" / "000002.bin", bin);
  write(w / "kitti-bad-times" / "velodyne" / "000000.bin", bin);
  write(w / "kitti-bad-times" / "times.txt", "0.0\n0.1\n0.2\n");
  write(w / "kitti-bad-times-value" / "velodyne" / "000000.bin", bin);
  write(w / "kitti-bad-times-value" / "times.txt", "zero\n");
  // a KITTI odometry sequence (00/velodyne/*.bin, 00/times.txt from 0.0): its first sweep is stamped
  // at its first firing, 0.05 s before 0.0
  for (const char* n : {"000000.bin", "000001.bin", "000002.bin"}) write(w / "kitti-odometry" / "velodyne" / n, bin);
  write(w / "kitti-odometry" / "times.txt", "0.0\n0.1\n0.2\n");
  // CAN
  write(w / "garbage.log", randomBytes(0, 0) + "hello world\n(12.5) can0 zzz#00\nnot candump\n");
  write(w / "half-good.log", "(1.000000) can0 123#0011\n(1.010000) can0 123#0011\nbroken line\n");
  write(w / "garbage.dbc", "BO_ x y z\nSG_ nonsense\n");
  write(w / "bad-vehicle.ini", "[vehicle]\ndbc = nope.dbc\n");
  write(w / "roadslam-sim.dbc", fileText(kSrc + "/ini/vehicles/roadslam-sim.dbc"));
  write(w / "vehicle-typo.ini", fileText(kSrc + "/ini/vehicles/roadslam-sim.ini") + "\nwheelbase_mm = 2.7\n");
  // GNSS: an NMEA log whose every line is bad (checksum, no fix), and one with a few bad lines
  write(w / "no-fix.nmea", "$GPGGA,000001.00,,,,,0,00,99.9,,M,,M,,*5E\n$GPGGA,000002.00,4808.0,N,01134.0,E,1,08,0.9,0,M,0,M,,*00\n");
  write(w / "some-bad.nmea", "$GPRMC,000001.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*5A\nnot nmea\n"
                             "$GPGGA,000002.00,4808.0,N,01134.0,E,1,08,0.9,0,M,0,M,,*00\n");
  const std::string rmc1 = "$GPRMC,081801.00,A,4808.0000,N,01134.0000,E,0.0,0.0,210116,,,A*58\n";
  const std::string rmc2 = "$GPRMC,081802.00,A,4808.0000,N,01134.0000,E,0.0,0.0,210116,,,A*5B\n";
  const std::string rmc3 = "$GPRMC,081803.00,A,4808.0000,N,01134.0000,E,0.0,0.0,210116,,,A*5A\n";
  write(w / "malformed.nmea", rmc1 + "$GPRMC,12ab,A*0A\n" + rmc2);  // checksum right, time field not a time
  write(w / "backwards.nmea", rmc3 + rmc2 + "$GPRMC,081804.00,A,4808.0000,N,01134.0000,E,0.0,0.0,210116,,,A*5D\n");
  write(w / "other-drive.nmea", "$GPRMC,000001.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*5A\n"
                                "$GPRMC,000002.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*59\n");  // 2024, the box room 2016
  write(w / "void.nmea", "$GPRMC,000001.00,V,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*4D\n"
                         "$GPRMC,000002.00,V,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*4E\n");
  write(w / "empty.nmea", "");
  // [gnss_fusion] keys (line 2 of each)
  write(w / "gnss-typo.ini", "[gnss_fusion]\nuere_mm = 3\n");
  write(w / "gnss-negative-uere.ini", "[gnss_fusion]\nuere_m = -1\n");
  write(w / "gnss-zero-sigma-r.ini", "[gnss_fusion]\nedge_sigma_r_deg = 0\n");
  write(w / "gnss-no-iterations.ini", "[gnss_fusion]\nmax_iterations = 0\n");
  write(w / "gnss-negative-blend.ini", "[gnss_fusion]\nonline_blend_s = -1\n");
  write(w / "gnss-bad-kernel.ini", "[gnss_fusion]\nkernel = tukey\n");
  write(w / "gnss-bad-bool.ini", "[gnss_fusion]\nreceiver_time = maybe\n");
  // a rawlog with two GPS sources: the box-room capture's position packets ("GPS") and a receiver's
  // epochs ("RECEIVER"), two rawlogs made by roadslam-rawlog and concatenated (gzip members)
  write(w / "receiver.nmea", rmc1 + rmc2 + rmc3);
  const std::string rawlog_app = binDir() + "/roadslam-rawlog ";
  const std::string quiet = " > /dev/null 2>&1";
  if (std::system((rawlog_app + "convert " + kSrc + "/rawlogs/boxroom-vlp16.pcap " + (w / "box.rawlog").string() + quiet).c_str()) == 0 &&
      std::system((rawlog_app + "nmea " + (w / "receiver.nmea").string() + " " + (w / "receiver.rawlog").string() +
                   " --label RECEIVER" + quiet).c_str()) == 0)
    write(w / "two-gps.rawlog", fileText(w / "box.rawlog") + fileText(w / "receiver.rawlog"));
  {  // the box room's rawlog cut in the middle of a record (a copy interrupted)
    const std::string box = fileText(w / "box.rawlog");
    write(w / "cut.rawlog", box.substr(0, box.size() * 6 / 10));
    // a roadslam-grab session whose first segment a crash cut short: the next one is read too
    write(w / "session-damaged" / "grab_000.rawlog", box.substr(0, box.size() * 6 / 10));
    write(w / "session-damaged" / "grab_001.rawlog", box);
  }
  // trajectories
  write(w / "three-columns.tum", "1 2 3\n");
  write(w / "words.tum", "# t x y z qx qy qz qw\n1.0 0 0 zero 0 0 0 1\n");
  write(w / "a.tum", "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n");
  write(w / "later.tum", "100.0 0 0 0 0 0 0 1\n101.0 1 0 0 0 0 0 1\n");
  write(w / "standing.tum", "1.0 5 0 0 0 0 0 1\n2.0 5 0 0 0 0 0 1\n3.0 5 0 0 0 0 0 1\n");
  write(w / "a_kitti.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n1 0 0 2 0 1 0 0 0 0 1 0\n");
  // KITTI odometry's camera frame: the car goes along z (forward), 1 m a pose
  write(w / "camera.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 1\n1 0 0 0 0 1 0 0 0 0 1 2\n1 0 0 0 0 1 0 0 0 0 1 3\n");
  write(w / "camera-times.txt", "1.0\n2.0\n3.0\n4.0\n");
  write(w / "lidar.tum", "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n4.0 3 0 0 0 0 0 1\n");
  // simulator and grabber inis
  write(w / "sim-typo.ini", fileText(kSrc + "/ini/sim/urban-loop.ini") + "\n[lidar]\nrange_nosie_m = 0.1\n");
  {
    std::string t = fileText(kSrc + "/ini/sim/urban-loop.ini");
    t.replace(t.find("[world]\n"), 8, "[world]\nmoving_car_headway_s = -1\n");
    write(w / "sim-bad-headway.ini", t);
  }
  write(w / "sim-bad-value.ini", "[scenario]\nduration_s = -5\n");
  write(w / "sim-open-route-offset.ini", fileText(kSrc + "/ini/sim/highway.ini") + "\n[trajectory]\nstart_offset_m = 50\n");
  write(w / "grab-typo.ini", fileText(kSrc + "/ini/grab.ini") + "\n[grab]\nsegmnet_mb = 5\n");
  const std::string grab_gnss = "[grab]\nsensors = l\ngnss = gnss\n[l]\ndata_port = 0\nposition_port = 0\n[gnss]\n";
  write(w / "grab-gnss-no-log.ini", grab_gnss + "source = nmea_log\n");
  write(w / "grab-gpsd-down.ini", grab_gnss + "source = gpsd\ngpsd_host = 127.0.0.1\ngpsd_port = 1\n");
  write(w / "grab-serial-missing.ini", grab_gnss + "source = serial\ndevice = /dev/roadslam-no-such-tty\n");
}

struct Row {
  const char* id;
  const char* command;   ///< app and arguments; {W} = the table's folder, {O} = this row's output, {S} = sources
  int exit_code;         ///< expected exit code
  const char* message;   ///< must appear in stdout + stderr ("" = anything); {W}, {O}, {S} as in command
  int signal_after_ms = 0;  ///< > 0: send SIGINT after this long
};

// clang-format off
const Row kTable[] = {
  // roadslam-map: command line
  {"map-no-config",        "roadslam-map --input {W}/truncated.pcap --out {O}", 106, "--config is required"},
  {"map-config-missing",   "roadslam-map --config {W}/nope.ini --input {W}/truncated.pcap --out {O}", 105, "File does not exist"},
  {"map-unknown-option",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --voxel 3", 109, "--voxel"},
  {"map-bad-max-frames",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --max-frames many", 105, "--max-frames: Value many"},
  {"map-can-no-vehicle",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --can {W}/half-good.log", 1, "--can needs --vehicle"},
  // roadslam-map: inputs
  {"map-input-missing",    "roadslam-map --config {S}/ini/default.ini --input {W}/nope.pcap --out {O}", 1, "does not exist"},
  {"map-random-rawlog",    "roadslam-map --config {S}/ini/default.ini --input {W}/random.rawlog --out {O}", 1, "gives no sweep"},
  {"map-empty-rawlog",     "roadslam-map --config {S}/ini/default.ini --input {W}/empty.rawlog --out {O}", 1, "gives no sweep"},
  {"map-random-pcap",      "roadslam-map --config {S}/ini/default.ini --input {W}/random.pcap --out {O}", 1, "random.pcap"},
  {"map-empty-pcap",       "roadslam-map --config {S}/ini/default.ini --input {W}/empty.pcap --out {O}", 1, "empty.pcap"},
  {"map-truncated-pcap",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --quiet", 0, "input damaged, 4 sweeps read before it: PcapReader: '{W}/truncated.pcap' damaged at record 239 (byte 299344)"},
  {"map-cut-rawlog",       "roadslam-map --config {S}/ini/default.ini --input {W}/cut.rawlog --out {O} --quiet", 0, "warning: input damaged, 3 sweeps read before it: {W}/cut.rawlog: truncated record at uncompressed byte "},
  {"map-product-byte-lies", "roadslam-map --config {S}/ini/default.ini --input {W}/vlp16-hdl32-byte.pcap --out {O} --quiet", 0,
   "warning: packets have the VLP-16 layout (110.6 us per block) but product byte 0x21 says HDL-32E; decoding as VLP-16; set [velodyne] model = hdl32 to force"},
  {"map-model-set-against-layout", "roadslam-map --config {W}/model-hdl32.ini --input {S}/rawlogs/boxroom-vlp16.pcap --out {O} --quiet", 0,
   "warning: packets have the VLP-16 layout (110.6 us per block) but [velodyne] model = hdl32 forces HDL-32E; decoding as HDL-32E as set"},
  {"map-unknown-kind",     "roadslam-map --config {S}/ini/default.ini --input {W}/notes.txt --out {O}", 1, "unknown kind"},
  {"map-empty-folder",     "roadslam-map --config {S}/ini/default.ini --input {W}/empty-dir --out {O}", 1, "holds no .bin"},
  {"map-session-damaged",  "roadslam-map --config {S}/ini/default.ini --input {W}/session-damaged --out {O} --quiet", 0, "warning: input damaged, 3 sweeps read before it, and 6 after it: {W}/session-damaged/grab_000.rawlog: truncated record at uncompressed byte "},
  {"map-kitti-damaged",    "roadslam-map --config {S}/ini/default.ini --input {W}/kitti-damaged --out {O} --quiet", 0, "warning: input damaged, 1 sweep read before it, and 1 after it: KITTI scan '{W}/kitti-damaged/000001.bin' has 1001 bytes, not a multiple of 16"},
  {"map-kitti-times-count","roadslam-map --config {S}/ini/default.ini --input {W}/kitti-bad-times/velodyne --out {O}", 1, "has 3 stamps for 1 .bin"},
  {"map-kitti-times-value","roadslam-map --config {S}/ini/default.ini --input {W}/kitti-bad-times-value/velodyne --out {O}", 1, "times.txt:1"},
  {"map-out-is-a-file",    "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {W}/a-file/x", 1, "cannot create output folder"},
  // roadslam-map: inis
  {"map-config-pcap",      "roadslam-map --config {W}/truncated.pcap --input {W}/truncated.pcap --out {O}", 1, "truncated.pcap' is a binary file, not an ini"},
  {"map-config-empty",     "roadslam-map --config {W}/empty.nmea --input {W}/truncated.pcap --out {O}", 1, "empty.nmea' has no [section]: not a roadslam ini"},
  {"sim-scenario-empty",   "roadslam-sim --config {W}/empty.nmea --out {O}", 1, "has no [section]"},
  {"map-typo-key",         "roadslam-map --config {W}/typo-key.ini --input {W}/truncated.pcap --out {O}", 1, "unknown key 'voxel_sise_m' in [odometry]"},
  {"map-typo-section",     "roadslam-map --config {W}/typo-section.ini --input {W}/truncated.pcap --out {O}", 1, "unknown section [odometri] (nearest known: [odometry])"},
  {"map-typo-allowed",     "roadslam-map --config {W}/typo-key.ini --input {W}/truncated.pcap --out {O} --quiet --allow-unknown-keys", 0, "warning: "},
  {"map-not-a-number",     "roadslam-map --config {W}/not-a-number.ini --input {W}/truncated.pcap --out {O}", 1, "not-a-number.ini:2: [preprocess] voxel_size_m = 'abc' is not a number"},
  {"map-bad-matcher",      "roadslam-map --config {W}/bad-matcher.ini --input {W}/truncated.pcap --out {O}", 1, "bad-matcher.ini:2: [odometry] matcher = 'kiss': expected voxel_map or registration"},
  {"map-bad-graph-optimizer", "roadslam-map --config {W}/bad-graph-optimizer.ini --input {W}/truncated.pcap --out {O}", 1, "optimizer = 'g2o': expected lm, mrpt_levmarq or ceres"},
  {"map-negative-voxel",   "roadslam-map --config {W}/negative-voxel.ini --input {W}/truncated.pcap --out {O}", 1, "must be positive"},
  {"map-tracking-negative-reid", "roadslam-map --config {W}/tracking-negative-reid.ini --input {W}/truncated.pcap --out {O}", 1, "tracking-negative-reid.ini:4: [tracking] reid_gate_m = -1: must be >= 0"},
  {"map-seen-through-zero-tolerance", "roadslam-map --config {W}/seen-through-zero-tolerance.ini --input {W}/truncated.pcap --out {O}", 1, "seen-through-zero-tolerance.ini:2: [seen_through] ray_tolerance_m = 0: must be > 0"},
  {"map-objects-negative-free-lag", "roadslam-map --config {W}/objects-negative-free-lag.ini --input {W}/truncated.pcap --out {O}", 1, "objects-negative-free-lag.ini:3: [objects] free_space_lag_s = -1: must be >= 0 (0: off)"},
  {"map-objects-free-lag-too-long", "roadslam-map --config {W}/objects-free-lag-too-long.ini --input {W}/truncated.pcap --out {O}", 1, "objects-free-lag-too-long.ini:3: [objects] free_space_lag_s = 60: must be <= 5"},
  {"map-tracking-free-fraction", "roadslam-map --config {W}/tracking-free-fraction-above-one.ini --input {W}/truncated.pcap --out {O}", 1, "tracking-free-fraction-above-one.ini:4: [tracking] moving_min_free_fraction = 1.5: must be in [0, 1] (0: off)"},
  {"map-objects-reach-inside-body", "roadslam-map --config {W}/objects-reach-inside-body.ini --input {W}/truncated.pcap --out {O}", 1, "[objects] max_range_m must exceed min_range_m"},
  {"map-bad-spin",         "roadslam-map --config {W}/bad-spin.ini --input {W}/truncated.pcap --out {O}", 1, "[kitti] spin = 'sideways'"},
  {"map-bad-motion-model", "roadslam-map --config {W}/bad-motion-model.ini --input {W}/truncated.pcap --out {O}", 1, "bad-motion-model.ini:4: [tracking] motion_model = 'kalman': expected cv, ctrv or imm"},
  {"map-bad-gnss-optimizer", "roadslam-map --config {W}/bad-gnss-optimizer.ini --input {W}/truncated.pcap --out {O}", 1, "bad-gnss-optimizer.ini:2: [gnss_fusion] optimizer = 'g2o': expected gauss_newton or ceres"},
  {"map-name-and-alias",   "roadslam-map --config {W}/name-and-alias.ini --input {W}/truncated.pcap --out {O}", 1, "name-and-alias.ini:4: [preprocess] rad = 3: alias of 'ego_radius_m', which line 2 sets too: set only one"},
  {"map-bad-stamp-ref",    "roadslam-map --config {W}/bad-stamp-reference.ini --input {W}/truncated.pcap --out {O}", 1, "expected start, middle or end"},
  {"map-bad-bool",         "roadslam-map --config {W}/bad-bool.ini --input {W}/truncated.pcap --out {O}", 1, "is not a boolean"},
  // roadslam-map: signals
  {"map-sigint",           "roadslam-map --config {S}/ini/default.ini --input {W}/kitti-long --out {O} --quiet", 130, "roadslam-map: interrupted: the outputs of the sweeps so far", 1500},
  {"map-out-is-prior-map", "roadslam-map --config {S}/ini/default.ini --input {W}/kitti-two --prior-map {W}/prior-map --out {W}/prior-map", 1, "prior-map' is or holds this run's input"},
  {"map-into-sim-folder",  "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {W}/sim-folder", 1, "sim-folder' holds the outputs of roadslam-sim (its run.json), not of roadslam-map"},
  {"map-into-data-folder", "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {W}/data-folder", 1, "data-folder' holds files no roadslam run wrote (drive.pcap; no run.json); give a new or empty --out folder, or --force"},
  {"map-into-other-run",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {W}/prior-map", 1, "prior-map' holds roadslam-map's run on "},
  {"map-input-in-out",     "roadslam-map --config {S}/ini/default.ini --input {W}/data-folder/drive.pcap --out {W}/data-folder", 1, "is or holds this run's input"},
  {"map-force",            "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {W}/data-folder-force --force --quiet", 0, "warning: --force: '"},
  {"map-can-other-drive",  "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --can {W}/other-drive.log --vehicle {S}/ini/vehicles/roadslam-sim.ini", 1, "other-drive.log covers 1000000000.000 to 1000000060.000 s (60.0 s), but the recording starts at"},
  {"bounds-trajectory-other-drive", "roadslam-bounds --config {S}/ini/bounds.ini --input {W}/kitti-two --out {O} --trajectory {W}/other-drive.tum", 1, "other-drive.tum covers 1000000000.000 to 1000000010.000 s (10.0 s), but the recording starts at -0.050 s, 1000000000.0 s before it: another drive, or another clock"},
  {"bounds-into-map-folder", "roadslam-bounds --config {S}/ini/bounds.ini --input {W}/kitti-two --out {W}/prior-map", 1, "holds the outputs of roadslam-map (its run.json), not of roadslam-bounds"},
  {"sim-into-map-folder",  "roadslam-sim --config {S}/ini/sim/urban-loop.ini --duration 1 --out {W}/prior-map", 1, "holds the outputs of roadslam-map (its run.json), not of roadslam-sim"},
  {"sim-sigint",           "roadslam-sim --config {S}/ini/sim/urban-loop.ini --duration 900 --out {O} --quiet", 130, "roadslam-sim: interrupted: the first", 1500},
  // roadslam-bounds
  {"bounds-sigint",        "roadslam-bounds --config {S}/ini/bounds.ini --input {W}/kitti-long --out {O} --quiet", 130, "interrupted: the outputs of the sweeps so far", 1500},
  {"bounds-typo-key",      "roadslam-bounds --config {W}/bounds-typo.ini --input {W}/truncated.pcap --out {O}", 1, "unknown key 'curb_min_jmup_m' in [boundary] (nearest known: curb_min_jump_m)"},
  {"bounds-bad-cluster",   "roadslam-bounds --config {W}/bounds-bad-cluster.ini --input {W}/truncated.pcap --out {O}", 1, "kmeans"},
  {"bounds-random-rawlog", "roadslam-bounds --config {S}/ini/bounds.ini --input {W}/random.rawlog --out {O}", 1, "gives no sweep"},
  {"bounds-input-missing", "roadslam-bounds --config {S}/ini/bounds.ini --input {W}/nope.pcap --out {O}", 1, "does not exist"},
  {"bounds-bad-trajectory","roadslam-bounds --config {S}/ini/bounds.ini --input {W}/truncated.pcap --trajectory {W}/three-columns.tum --out {O}", 1, "three-columns.tum"},
  {"bounds-truncated-pcap","roadslam-bounds --config {S}/ini/bounds.ini --input {W}/truncated.pcap --out {O} --quiet", 0, "input damaged, 4 sweeps read before it: PcapReader: '{W}/truncated.pcap' damaged at record 239 (byte 299344)"},
  {"bounds-product-byte-lies", "roadslam-bounds --config {S}/ini/bounds.ini --input {W}/vlp16-hdl32-byte.pcap --out {O} --quiet", 0,
   "but product byte 0x21 says HDL-32E; decoding as VLP-16; set [velodyne] model = hdl32 to force"},
  // roadslam-experiment
  {"exp-typo-sweep-key",   "roadslam-experiment --config {W}/exp-typo.ini --out {O}", 1, "exp-typo.ini:6: unknown key 'odometry.registration_voxel_sise_m' in [sweep]: no component of a job reads it (nearest known: odometry.registration_voxel_m)"},
  {"exp-dataset-missing",  "roadslam-experiment --config {W}/exp-no-input.ini --out {O}", 1, "exp-no-input.ini:4: [dataset.x] input"},
  {"exp-bad-emit",         "roadslam-experiment --config {W}/exp-typo.ini --out {O} --emit sge", 105, "--emit"},
  {"exp-collect-no-plan",  "roadslam-experiment collect {W}/empty-dir", 1, "not an experiment folder"},
  {"exp-no-out",           "roadslam-experiment --config {W}/exp-typo.ini", 2, "--config and --out are required"},
  // roadslam-report
  {"report-missing",       "roadslam-report {W}/nope.pcap --out {O}", 1, "nope.pcap: no such file or folder"},
  {"report-random",        "roadslam-report {W}/random.pcap --out {O}", 1, "random.pcap"},
  {"report-truncated",     "roadslam-report {W}/truncated.pcap --out {O}", 0, "damaged at record 239 (byte 299344)"},
  {"report-can-garbage",   "roadslam-report {W}/truncated.pcap --can {W}/garbage.log --out {O}", 1, "garbage.log: no CAN frame in it (3 of 3 lines unreadable, first at line 1)"},
  {"report-can-half-good", "roadslam-report {W}/truncated.pcap --can {W}/half-good.log --out {O}", 0, "1 bad lines"},
  {"report-no-map",        "roadslam-report {W}/truncated.pcap --map {W}/a-file --out {O}", 1, "a-file: not a folder"},
  // roadslam-can
  {"can-decode-garbage",   "roadslam-can decode --dbc {S}/ini/vehicles/roadslam-sim.dbc {W}/garbage.log", 2, "3 of 3 lines unreadable (first at line 1"},
  {"can-decode-allowed",   "roadslam-can decode --dbc {S}/ini/vehicles/roadslam-sim.dbc {W}/garbage.log --max-bad-lines 3", 0, "3 bad log lines"},
  {"can-decode-half-good", "roadslam-can decode --dbc {S}/ini/vehicles/roadslam-sim.dbc {W}/half-good.log", 2, "first at line 3"},
  {"can-info-garbage",     "roadslam-can info {W}/garbage.log", 2, "unreadable"},
  {"can-bad-dbc",          "roadslam-can decode --dbc {W}/garbage.dbc {W}/half-good.log", 1, "garbage.dbc"},
  {"can-log-missing",      "roadslam-can decode --dbc {S}/ini/vehicles/roadslam-sim.dbc {W}/nope.log", 105, "File does not exist"},
  {"can-bad-vehicle",      "roadslam-can odometry --vehicle {W}/bad-vehicle.ini {W}/half-good.log --out {O}/odo.tum", 1, "bad-vehicle.ini"},
  {"can-vehicle-typo",     "roadslam-can odometry --vehicle {W}/vehicle-typo.ini --data-root {S}/ini/vehicles {W}/half-good.log --out {O}/odo.tum", 1, "unknown key 'wheelbase_mm' in [vehicle] (nearest known: wheelbase_m)"},
  {"map-gnss-no-fix",      "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/no-fix.nmea", 1, "holds no valid fix"},
  {"map-gnss-missing",     "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/nope.nmea", 105, "File does not exist"},
  {"map-gnss-empty",       "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/empty.nmea", 1, "empty.nmea' holds no valid fix (0 lines"},
  {"map-gnss-void-fixes",  "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/void.nmea", 1, "void.nmea' holds no valid fix (2 lines, 0 with a bad checksum, 2 epochs without a fix)"},
  {"map-gnss-malformed",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/malformed.nmea --quiet", 0, "warning: GNSS log: 1 x malformed"},
  {"map-gnss-other-drive", "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/other-drive.nmea", 1, "other-drive.nmea covers 1704067201.000 to 1704067202.000 s (1.0 s), but the recording starts at 1453364282.000 s, 250702919.0 s before it: another drive, or another clock"},
  {"map-gnss-backwards",   "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --gnss {W}/backwards.nmea --quiet", 0, "warning: GNSS log: 1 x time backwards"},
  {"map-gnss-typo-key",    "roadslam-map --config {W}/gnss-typo.ini --input {W}/truncated.pcap --out {O}", 1, "gnss-typo.ini:2: unknown key 'uere_mm' in [gnss_fusion] (nearest known: uere_m)"},
  {"map-gnss-negative-uere", "roadslam-map --config {W}/gnss-negative-uere.ini --input {W}/truncated.pcap --out {O}", 1, "gnss-negative-uere.ini:2: [gnss_fusion] uere_m = -1: must be > 0"},
  {"map-gnss-zero-sigma-r", "roadslam-map --config {W}/gnss-zero-sigma-r.ini --input {W}/truncated.pcap --out {O}", 1, "gnss-zero-sigma-r.ini:2: [gnss_fusion] edge_sigma_r_deg = 0: must be > 0"},
  {"map-gnss-no-iterations", "roadslam-map --config {W}/gnss-no-iterations.ini --input {W}/truncated.pcap --out {O}", 1, "gnss-no-iterations.ini:2: [gnss_fusion] max_iterations = 0: must be at least 1"},
  {"map-gnss-negative-blend", "roadslam-map --config {W}/gnss-negative-blend.ini --input {W}/truncated.pcap --out {O}", 1, "gnss-negative-blend.ini:2: [gnss_fusion] online_blend_s = -1: must be >= 0"},
  {"map-gnss-bad-kernel",  "roadslam-map --config {W}/gnss-bad-kernel.ini --input {W}/truncated.pcap --out {O}", 1, "kernel = 'tukey'"},
  {"map-gnss-bad-bool",    "roadslam-map --config {W}/gnss-bad-bool.ini --input {W}/truncated.pcap --out {O}", 1, "gnss-bad-bool.ini:2: [gnss_fusion] receiver_time = 'maybe' is not a boolean"},
  {"map-gnss-two-sources", "roadslam-map --config {S}/ini/default.ini --input {W}/two-gps.rawlog --out {O} --gnss-from-input", 1, "two-gps.rawlog' carries several GPS sources (GPS (5 records), RECEIVER (3 records)); choose the one to fuse with --gnss-label LABEL"},
  {"map-gnss-label-absent", "roadslam-map --config {S}/ini/default.ini --input {W}/two-gps.rawlog --out {O} --gnss-from-input --gnss-label CAN_GPS", 1, "--gnss-label CAN_GPS: '"},
  {"map-gnss-label-alone", "roadslam-map --config {S}/ini/default.ini --input {W}/two-gps.rawlog --out {O} --gnss-label GPS", 107, "--gnss-label requires --gnss-from-input"},
  {"map-gnss-label-chosen", "roadslam-map --config {S}/ini/default.ini --input {W}/two-gps.rawlog --out {O} --gnss-from-input --gnss-label RECEIVER --json", 0, "(RECEIVER)"},
  // roadslam-rawlog
  {"rawlog-nmea-bad-lines","roadslam-rawlog nmea {W}/some-bad.nmea {W}/some-bad.rawlog", 0, "2 bad checksum"},
  {"rawlog-info-random",   "roadslam-rawlog info {W}/random.rawlog", 1, "not a readable MRPT rawlog"},
  {"rawlog-info-truncated","roadslam-rawlog info {W}/truncated.pcap", 0, "roadslam-rawlog: warning: input damaged, 4 sweeps read before it: PcapReader: '{W}/truncated.pcap' damaged at record 239 (byte 299344)"},
  {"rawlog-info-cut-rawlog","roadslam-rawlog info {W}/cut.rawlog", 0, "roadslam-rawlog: warning: input damaged, 3 sweeps read before it: {W}/cut.rawlog: truncated record at uncompressed byte "},
  {"rawlog-convert-truncated","roadslam-rawlog convert {W}/truncated.pcap {O}.rawlog", 0, "roadslam-rawlog: warning: input damaged, 4 sweeps read before it: PcapReader: '{W}/truncated.pcap' damaged at record 239 (byte 299344)"},
  {"rawlog-info-missing",  "roadslam-rawlog info {W}/nope.rawlog", 1, "nope.rawlog"},
  {"rawlog-convert-random","roadslam-rawlog convert {W}/random.pcap {O}/x.rawlog", 1, "random.pcap"},
  {"rawlog-info-product-byte-lies", "roadslam-rawlog info {W}/vlp16-hdl32-byte.pcap", 0,
   "roadslam-rawlog: warning: packets have the VLP-16 layout (110.6 us per block) but product byte 0x21 says HDL-32E; decoding as VLP-16; set --model hdl32 to force"},
  {"rawlog-convert-product-byte-lies", "roadslam-rawlog convert {W}/vlp16-hdl32-byte.pcap {W}/vlp16-hdl32-byte.rawlog", 0, "lidar model VLP-16 (by packet layout)"},
  // roadslam-eval
  {"eval-gt-missing",      "roadslam-eval --gt {W}/nope.tum --est {W}/a.tum", 105, "File does not exist"},
  {"eval-three-columns",   "roadslam-eval --gt {W}/three-columns.tum --est {W}/a.tum", 1, "3 columns, expected 8"},
  {"eval-words",           "roadslam-eval --gt {W}/words.tum --est {W}/a.tum", 1, "words.tum"},
  {"eval-no-pairs",        "roadslam-eval --gt {W}/a.tum --est {W}/later.tum", 1, "only 0 poses"},
  {"eval-untimed-est",     "roadslam-eval --gt {W}/a.tum --est {W}/a_kitti.txt", 1, "a_kitti.txt' is a KITTI 3x4 file without times"},
  {"eval-standing-gt",     "roadslam-eval --gt {W}/standing.tum --est {W}/standing.tum", 1, "span 0.000 m: no motion to score"},
  {"eval-camera-gt",       "roadslam-eval --gt {W}/camera.txt --gt-times {W}/camera-times.txt --est {W}/lidar.tum", 1, "with --calib"},
  // roadslam-sim
  {"sim-typo-key",         "roadslam-sim --config {W}/sim-typo.ini --out {O}", 1, "unknown key 'range_nosie_m' in [lidar] (nearest known: range_noise_m)"},
  {"sim-typo-allowed",     "roadslam-sim --config {W}/sim-typo.ini --duration 0.2 --out {O} --quiet --allow-unknown-keys", 0, "warning: "},
  {"rawlog-convert-onto-input", "roadslam-rawlog convert {W}/data-folder/drive.pcap --out {W}/data-folder/drive.pcap", 1, "drive.pcap' is the input: the conversion would overwrite what it reads"},
  {"rawlog-record-old-spelling", "roadslam-rawlog record {W}/nope-dir/x.pcap --seconds 0.2", 1, "roadslam-rawlog: --seconds is an old spelling: use --duration"},
  {"rawlog-record-no-folder", "roadslam-rawlog record {W}/nope-dir/x.pcap --duration 0.2", 1, "cannot create '{W}/nope-dir/x.pcap': No such file or directory"},
  {"sim-old-spelling",     "roadslam-sim --scenario {S}/ini/sim/urban-loop.ini --duration 0.2 --out {O} --quiet", 0, "roadslam-sim: --scenario is an old spelling: use --config"},
  {"map-negative-max-frames", "roadslam-map --config {S}/ini/default.ini --input {W}/truncated.pcap --out {O} --max-frames -1", 105, "--max-frames"},
  {"sim-bad-value",        "roadslam-sim --config {W}/sim-bad-value.ini --out {O}", 1, "duration_s"},
  {"sim-bad-headway",      "roadslam-sim --config {W}/sim-bad-headway.ini --out {O}", 1, "sim-bad-headway.ini:14: [world] moving_car_headway_s = -1: must be > 0"},
  {"sim-open-route-offset", "roadslam-sim --config {W}/sim-open-route-offset.ini --out {O}", 1, "start_offset_m needs a closed route"},
  {"sim-missing",          "roadslam-sim --config {W}/nope.ini --out {O}", 105, "File does not exist"},
  // roadslam-grab
  {"grab-typo-key",        "roadslam-grab --config {W}/grab-typo.ini --out {O} --duration 0.1", 1, "segmnet_mb"},
  {"grab-missing",         "roadslam-grab --config {W}/nope.ini --out {O}", 105, "File does not exist"},
  {"grab-gnss-no-log",     "roadslam-grab --config {W}/grab-gnss-no-log.ini --out {O} --duration 0.1", 1, "[gnss] nmea_file: required"},
  {"grab-gpsd-down",       "roadslam-grab --config {W}/grab-gpsd-down.ini --out {O} --duration 0.1", 1, "gpsd at 127.0.0.1:1"},
  {"grab-serial-missing",  "roadslam-grab --config {W}/grab-serial-missing.ini --out {O} --duration 0.1", 1, "GNSS serial '/dev/roadslam-no-such-tty'"},
  // roadslam-view live
  {"view-live-silent",     "roadslam-view --udp 0 --render {O}/x.png --timeout 0.3", 1, "no sweep arrived from UDP port"},
  {"view-live-and-rec",    "roadslam-view {W}/truncated.pcap --udp 0", 2, "give one of a recording, --udp PORT or --grab INI"},
  {"view-record-replay",   "roadslam-view {W}/truncated.pcap --record {O}", 2, "--record belongs to a live view"},
  {"view-live-typo-key",   "roadslam-view --grab {W}/grab-typo.ini --render {O}/x.png", 1, "segmnet_mb"},
  {"view-live-sequence",   "roadslam-view --udp 0 --render-sequence {O}/seq", 1, "--render-sequence and --video need a recording"},
  {"view-bad-tracks-csv",  "roadslam-view {W}/kitti-two --map {W}/map-bad-tracks --render {O}/x.png --at 0", 1, "tracks.csv:2: column 'x' is not a number: 'abc'"},
  {"view-map-no-manifest", "roadslam-view {W}/kitti-two --map {W}/map-old --render {O}/x.png --at 0", 1, "map-old/run.json: missing"},
  // roadslam-view: damaged recordings read up to the damage, in roadslam-map's words
  {"view-truncated-pcap",  "roadslam-view {W}/truncated.pcap --render {O}.png --size 160x120", 0, "roadslam-view: warning: input damaged, 4 sweeps read before it: PcapReader: '{W}/truncated.pcap' damaged at record 239 (byte 299344)"},
  {"view-cut-rawlog",      "roadslam-view {W}/cut.rawlog --render {O}.png --size 160x120 --no-index-cache", 0, "roadslam-view: warning: input damaged, 3 sweeps read before it: {W}/cut.rawlog: truncated record at uncompressed byte "},
  {"view-session-damaged", "roadslam-view {W}/session-damaged --render {O}.png --size 160x120", 0, "roadslam-view: warning: input damaged, 3 sweeps read before it, and 6 after it: {W}/session-damaged/grab_000.rawlog: truncated record at uncompressed byte "},
  {"view-kitti-damaged",   "roadslam-view {W}/kitti-damaged --render {O}.png --size 160x120", 0, "roadslam-view: warning: input damaged, 1 sweep read before it, and 1 after it: KITTI scan '{W}/kitti-damaged/000001.bin' has 1001 bytes"},
  {"view-kitti-odometry",  "roadslam-view {W}/kitti-odometry/velodyne --render {O}.png --size 160x120", 0, "kitti-odometry/velodyne: 3 observations over 0.2 s"},
  {"view-kitti-no-times",  "roadslam-view {W}/kitti-two --render {O}.png --size 160x120", 0, "kitti-two: 2 observations over 0.1 s"},
  // roadslam-view: --at outside the recording
  {"view-at-past-end",     "roadslam-view {W}/kitti-two --render {O}/x.png --at 500", 2, "roadslam-view: --at 500 s is past the end of {W}/kitti-two (0.1 s long)"},
  {"view-at-negative",     "roadslam-view {W}/kitti-two --render {O}/x.png --at -1", 2, "roadslam-view: --at -1 s is before the start of {W}/kitti-two"},
  {"report-into-map-folder", "roadslam-report {W}/truncated.pcap --out {W}/prior-map", 1, "holds the outputs of roadslam-map (its run.json), not of roadslam-report"},
  {"report-map-no-manifest", "roadslam-report {W}/truncated.pcap --map {W}/map-old --out {O}", 1, "re-create it with roadslam-map"},
};
// clang-format on

struct Outcome {
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;
  std::string output;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::string expand(std::string s, const std::string& out_dir) {
  const std::pair<std::string, std::string> subst[] = {{"{W}", work().string()}, {"{O}", out_dir}, {"{S}", kSrc}};
  for (const auto& [k, v] : subst) {
    for (size_t p; (p = s.find(k)) != std::string::npos;) s.replace(p, k.size(), v);
  }
  return s;
}

Outcome run(const std::vector<std::string>& argv, const fs::path& log, int signal_after_ms) {
  Outcome o;
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  const auto t0 = std::chrono::steady_clock::now();
  bool signalled = false;
  int status = 0;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count();
    if (signal_after_ms > 0 && !signalled && ms >= signal_after_ms) {
      kill(pid, SIGINT);
      signalled = true;
    }
    if (ms > 120000) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  o.output = fileText(log);
  return o;
}

/// Files an interrupted or failed run must never leave: temporaries of the atomic writers.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name.find(".write_test") != std::string::npos) out.push_back(e.path().string());
  }
  return out;
}

class BadInputs : public ::testing::TestWithParam<Row> {};

}  // namespace

TEST_P(BadInputs, GivesTheDocumentedMessageAndExitCode) {
  makeFiles();
  const Row& row = GetParam();
  const fs::path out = work() / "out" / row.id;
  auto argv = split(expand(row.command, out.string()));
  argv[0] = binDir() + "/" + argv[0];
  ASSERT_TRUE(fs::exists(argv[0])) << argv[0] << " is not built";
  const Outcome o = run(argv, work() / (std::string(row.id) + ".log"), row.signal_after_ms);
  EXPECT_FALSE(o.timed_out) << row.id << " hung";
  EXPECT_EQ(o.signal, 0) << row.id << " crashed with signal " << o.signal << ":\n" << o.output;
  EXPECT_EQ(o.exit_code, row.exit_code) << row.id << ":\n" << o.output;
  const std::string message = expand(row.message, out.string());
  EXPECT_NE(o.output.find(message), std::string::npos) << row.id << ": expected '" << message << "' in:\n" << o.output;
  EXPECT_EQ(o.output.find("runtime error"), std::string::npos) << "UBSan: " << o.output;       // -fsanitize=undefined
  EXPECT_EQ(o.output.find("AddressSanitizer"), std::string::npos) << "ASan: " << o.output;
  const auto left = leftovers(out);
  EXPECT_TRUE(left.empty()) << row.id << " left " << left.front();
  if (row.exit_code != 0 && row.exit_code != 130 && std::string(row.command).find("{O}") != std::string::npos) {
    // a run refused at the door writes nothing, not even an empty folder
    EXPECT_FALSE(fs::exists(out)) << row.id << " made " << out << (fs::is_empty(out) ? " (empty)" : " and wrote into it");
  }
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputs, ::testing::ValuesIn(kTable),
                         [](const ::testing::TestParamInfo<Row>& i) {
                           std::string n = i.param.id;
                           for (auto& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return n;
                         });

TEST(BadInputs, TheTableHasFortyRows) { EXPECT_GE(std::size(kTable), 40u); }

// A full disk: each program writes into a small tmpfs of its own, mounted in a user and mount
// namespace (unshare -rm, no root needed), so the disk really fills (write(2) fails with ENOSPC). The
// program must name the reason, keep what fitted (the small, valuable outputs first) and leave no
// temporary file.
namespace {

struct FullDiskRun {
  int exit_code = -1;
  std::string output;  ///< the program's stdout + stderr
  std::string files;   ///< `ls -A` of the output folder after the run, one name per line
};

/// Runs \p program_args (the program's name, then its arguments; {D} is the small disk's folder) with
/// a tmpfs of \p size at {D}; nullopt when this machine cannot make one (no user namespaces).
std::optional<FullDiskRun> onFullDisk(const std::string& size, const std::string& program_args, const std::string& out_sub) {
  const fs::path mnt = work() / ("disk-" + std::to_string(std::hash<std::string>{}(program_args) % 100000));
  fs::create_directories(mnt);
  std::string args = program_args;
  for (size_t p; (p = args.find("{D}")) != std::string::npos;) args.replace(p, 3, mnt.string());
  const fs::path log = mnt.string() + ".log", listing = mnt.string() + ".ls";
  const std::string inner = "mount -t tmpfs -o size=" + size + " none " + mnt.string() + " || exit 99; " + binDir() + "/" +
                            args + " > " + log.string() + " 2>&1; rc=$?; ls -A " + (mnt / out_sub).string() + " > " +
                            listing.string() + " 2>/dev/null; exit $rc";
  const int status = std::system(("unshare -rm sh -c '" + inner + "'").c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) == 99 || (WEXITSTATUS(status) == 1 && !fs::exists(log))) return std::nullopt;
  return FullDiskRun{WEXITSTATUS(status), fileText(log), fileText(listing)};
}

bool lists(const std::string& files, const std::string& name) { return ("\n" + files).find("\n" + name + "\n") != std::string::npos; }

}  // namespace

TEST(BadInputs, FullDiskMapKeepsTheTrajectoryAndNamesTheReason) {
  makeFiles();
  const auto r = onFullDisk("96k", "roadslam-map --config " + kSrc + "/ini/default.ini --input " + kSrc +
                                       "/rawlogs/boxroom-vlp16.pcap --out {D}/run --quiet", "run");
  if (!r) GTEST_SKIP() << "no tmpfs in a user namespace here (unshare -rm): the full-disk case is not run";
  EXPECT_EQ(r->exit_code, 1) << r->output;
  EXPECT_NE(r->output.find("No space left on device"), std::string::npos) << r->output;
  EXPECT_EQ(r->output.find(".tmp-"), std::string::npos) << "a temporary name in the message:\n" << r->output;
  EXPECT_TRUE(lists(r->files, "trajectory.tum")) << r->files;
  EXPECT_TRUE(lists(r->files, "frames.csv")) << r->files;
  EXPECT_EQ(r->files.find(".tmp"), std::string::npos) << "left a temporary file:\n" << r->files;
}

TEST(BadInputs, FullDiskRawlogConvertNamesTheReasonWithoutABacktrace) {
  makeFiles();
  const auto r = onFullDisk("64k", "roadslam-rawlog convert " + kSrc + "/rawlogs/boxroom-vlp16.pcap {D}/x.rawlog", ".");
  if (!r) GTEST_SKIP() << "no tmpfs in a user namespace here (unshare -rm): the full-disk case is not run";
  EXPECT_EQ(r->exit_code, 1) << r->output;
  EXPECT_NE(r->output.find("No space left on device"), std::string::npos) << r->output;
  EXPECT_EQ(r->output.find("==== MRPT exception"), std::string::npos) << r->output;
  EXPECT_EQ(r->files.find(".tmp"), std::string::npos) << "left a temporary file:\n" << r->files;
}

TEST(BadInputs, FullDiskSimNamesTheReasonAndLeavesNoTemporaryFile) {
  makeFiles();
  const auto r = onFullDisk("64k", "roadslam-sim --config " + kSrc + "/ini/sim/urban-loop.ini --duration 2 --out {D}/sim --quiet", "sim");
  if (!r) GTEST_SKIP() << "no tmpfs in a user namespace here (unshare -rm): the full-disk case is not run";
  EXPECT_EQ(r->exit_code, 1) << r->output;
  EXPECT_NE(r->output.find("No space left on device"), std::string::npos) << r->output;
  EXPECT_EQ(r->files.find(".tmp"), std::string::npos) << "left a temporary file:\n" << r->files;
}
