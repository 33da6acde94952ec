#include "roadslam/viewer/model.h"

#include <octomap/OcTree.h>

#include "roadslam/can/candump.h"
#include "roadslam/vehicle/params.h"
#include "roadslam/vehicle/vehicle_state.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include <mrpt/config/CConfigFile.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/obs/CObservationOdometry.h>

#include "roadslam/runfolder/run_folder.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/viewer/scene.h"
#include "roadslam/viewer/sweep.h"

namespace roadslam::viewer {
namespace fs = std::filesystem;


std::vector<Eigen::Vector3f> readPlyPoints(const std::string& path, double voxel_m) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot open point map '" + path + "'");
  std::string line;
  std::size_t n = 0;
  bool binary_le = false, xyz = false;
  int props = 0;
  while (std::getline(f, line) && line != "end_header") {
    if (line.rfind("format binary_little_endian", 0) == 0) binary_le = true;
    if (line.rfind("element vertex ", 0) == 0) n = std::stoul(line.substr(15));
    if (line.rfind("property float ", 0) == 0) ++props;
    if (line == "property float z") xyz = true;
  }
  if (!binary_le || !xyz || props != 3)
    throw std::runtime_error("'" + path + "' is not a binary float x,y,z PLY (as roadslam-map writes)");
  std::vector<float> raw(n * 3);
  if (!f.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * sizeof(float))))
    throw std::runtime_error("point map '" + path + "' is cut short");
  std::vector<Eigen::Vector3f> out;
  std::unordered_set<uint64_t> seen;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f p(raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]);
    if (!p.allFinite()) continue;
    if (voxel_m > 0) {
      const auto k = [&](float v) { return uint64_t(int64_t(std::floor(v / voxel_m)) & 0x1fffff); };
      if (!seen.insert(k(p.x()) | k(p.y()) << 21 | k(p.z()) << 42).second) continue;
    }
    out.push_back(p);
  }
  return out;
}

ViewerModel::ViewerModel(const ViewerInputs& in) : in_(in) {
  rawlog::RawlogIndexOptions opt = in.index;
  opt.on_build = nullptr;  // told here, on this thread, not from the indexing ones
  std::vector<std::string> segments = fs::is_directory(in.recording) ? rawlog::RawlogSession::segmentsOf(in.recording)
                                                                     : std::vector<std::string>{in.recording};
  if (segments.empty()) throw std::runtime_error("folder '" + in.recording + "' holds no rawlog segment (NAME_000.rawlog)");
  auto idx = rawlog::RawlogSession::open(segments, opt);
  session_ = idx.get();
  index_ = std::move(idx);
  if (!session_->done() && in.index.on_build) in.index.on_build(in.recording);
  while (!session_->done() && session_->size() == 0 && session_->errors().empty()) {
    session_->poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (session_->size() == 0 && !session_->errors().empty()) throw std::runtime_error(session_->errors().front());
  if (session_->done()) indexDone();
  loadResults();
}

namespace {
/// The sweeps of each segment of \p session (a rawlog's observation holding points is one sweep).
std::vector<uint64_t> sweepsPerSegment(const rawlog::RawlogSession& session) {
  std::vector<uint64_t> n(session.segments(), 0);
  for (std::size_t k = 0; k < n.size(); ++k)
    if (const rawlog::RawlogIndex* idx = session.segment(k).done())
      for (std::size_t i = 0; i < idx->size(); ++i) n[k] += idx->entry(i).known && holdsSweep(idx->className(i));
  return n;
}

/// The damage of segment \p k in sources::damageWarning()'s words: the sweeps up to its end are
/// before it, those of the later segments (a session goes on past a damaged segment) after it.
std::string damageOf(const rawlog::RawlogSession& session, std::size_t k) {
  const auto n = sweepsPerSegment(session);
  const uint64_t before = std::accumulate(n.begin(), n.begin() + long(k) + 1, uint64_t(0));
  const uint64_t after = std::accumulate(n.begin() + long(k) + 1, n.end(), uint64_t(0));
  const rawlog::RawlogIndex& idx = *session.segment(k).done();
  return sources::damageWarning(before, idx.path() + ": " + idx.stopMessage(), after);
}
}  // namespace

// The checks that need the whole recording.
void ViewerModel::indexDone() {
  const bool one = session_->segments() == 1;
  for (std::size_t k = 0; k < session_->segments(); ++k) {
    const rawlog::RawlogIndex* idx = session_->segment(k).done();
    if (!idx) continue;  // its indexing stopped: in errors()
    const std::string what = one ? "recording" : "segment " + idx->path();
    if (!idx->complete()) warnings_.push_back(damageOf(*session_, k));
    for (const auto& [cls, n] : idx->unknownClasses())
      warnings_.push_back(what + ": " + std::to_string(n) + " observations of unknown class " + cls + " skipped");
    if (!idx->openInfo().cache_note.empty()) warnings_.push_back(idx->openInfo().cache_note);
  }
  for (const auto& e : session_->errors()) warnings_.push_back(e);
  if (session_->size() == 0) {
    const rawlog::RawlogIndex* first = session_->segment(0).done();
    throw std::runtime_error("recording '" + in_.recording + "' holds no readable observation" +
                             (first && !first->complete() ? ": " + first->stopMessage() : std::string()));
  }
  for (const auto& o : deferred_overlaps_) checkOverlap(o.what, o.t0, o.t1);
  deferred_overlaps_.clear();
}

ViewerModel::LidarModel ViewerModel::lidarModel() {
  constexpr std::size_t kLookAhead = 1000;  // observations searched for the first Velodyne sweep
  const auto& idx = recording();
  for (std::size_t i = 0; i < std::min(idx.size(), kLookAhead); ++i) {
    if (!idx.entry(i).known || idx.className(i) != "CObservationVelodyneScan") continue;
    try {
      const auto sweep = sweepOf(*index_->load(i));
      if (!sweep) continue;
      return {sweep->model + " (by " + sweep->model_source + ")", sweep->model_warning};
    } catch (const std::exception&) {
      continue;  // a damaged observation: the next one
    }
  }
  return {};
}

void ViewerModel::waitForIndex() {
  if (!indexing()) return;
  session_->waitUntilDone();
  indexDone();
}

ViewerModel::ViewerModel(const ViewerInputs& in, std::unique_ptr<sources::LiveObservations> live) : in_(in) {
  if (!live) throw std::invalid_argument("ViewerModel: no live source");
  live_ = live.get();
  index_ = std::move(live);
  loadResults();
}

void ViewerModel::loadResults() {
  if (!in_.map_dir.empty()) loadMapFolder(in_.map_dir);
  if (!in_.bounds_dir.empty()) loadBounds(in_.bounds_dir);
  if (!in_.ground_truth.empty()) loadGroundTruth(in_.ground_truth);
  if (!in_.can_log.empty()) loadCan(in_.can_log, in_.vehicle_ini);
}

std::size_t ViewerModel::poll() {
  if (indexing()) {
    const std::size_t n = session_->poll();
    if (session_->done()) indexDone();
    return n;
  }
  if (!live_) return 0;
  const std::size_t first = live_->poll();
  for (std::size_t i = first; i < live_->size(); ++i) {
    const std::string& cls = live_->className(i);
    if (cls != "CObservationOdometry" && cls != "CObservationIMU") continue;
    const auto obs = live_->load(i);
    CanSample c;
    c.t_s = live_->entry(i).stamp_s;
    if (const auto* odo = dynamic_cast<const mrpt::obs::CObservationOdometry*>(obs.get())) {
      if (!odo->hasVelocities) continue;
      c.speed_mps = odo->velocityLocal.vx;
      c.yaw_rate_rad_s = odo->velocityLocal.omega;
    } else if (const auto* imu = dynamic_cast<const mrpt::obs::CObservationIMU*>(obs.get())) {
      if (!imu->has(mrpt::obs::IMU_WZ)) continue;
      c.yaw_rate_rad_s = imu->get(mrpt::obs::IMU_WZ);
      if (!can_.empty()) c.speed_mps = can_.back().speed_mps;
    }
    addCanSample(c);
  }
  return live_->size() - first;
}

// 20 Hz is plenty for a plot, and bounds the memory of long logs and live sessions.
void ViewerModel::addCanSample(const CanSample& c) {
  if (!std::isfinite(c.t_s)) return;
  if (!can_.empty() && c.t_s - can_.back().t_s < 0.05) return;
  can_.push_back(c);
}

ViewerModel::~ViewerModel() = default;

double ViewerModel::startTime() const {
  if (index_->lastStamp() > 0) return index_->firstStamp();
  return frames_.empty() ? 0.0 : frames_.front().stamp_s;
}
double ViewerModel::endTime() const {
  if (index_->lastStamp() > 0) return index_->lastStamp();
  return frames_.empty() ? 0.0 : frames_.back().stamp_s;
}

void ViewerModel::checkOverlap(const std::string& what, double t0, double t1) {
  if (indexing()) {
    deferred_overlaps_.push_back({what, t0, t1});
    return;
  }
  if (index_->lastStamp() <= 0) return;
  if (t1 < index_->firstStamp() || t0 > index_->lastStamp()) {
    char buf[200];
    std::snprintf(buf, sizeof buf, " (%.3f-%.3f s) do not overlap the recording (%.3f-%.3f s)", t0, t1,
                  index_->firstStamp(), index_->lastStamp());
    warnings_.push_back(what + buf);
  }
}

void ViewerModel::appendFrame(const ViewerFrame& f) {
  if (frames_.empty() || frames_.back().stamp_s <= f.stamp_s) {
    frames_.push_back(f);
    return;
  }
  const auto at = std::upper_bound(frames_.begin(), frames_.end(), f.stamp_s,
                                   [](double t, const ViewerFrame& r) { return t < r.stamp_s; });
  frames_.insert(at, f);
}

void ViewerModel::postFrame(const ViewerFrame& f) {
  std::lock_guard<std::mutex> lock(posted_mutex_);
  posted_.push_back(f);
}

std::size_t ViewerModel::takePosted() {
  std::vector<ViewerFrame> taken;
  std::vector<ObjectBoxes> objects;
  {
    std::lock_guard<std::mutex> lock(posted_mutex_);
    taken.swap(posted_);
    objects.swap(posted_objects_);
  }
  for (const auto& f : taken) appendFrame(f);
  for (auto& o : objects) appendObjects(std::move(o));
  return taken.size();
}

void ViewerModel::postObjects(ObjectBoxes f) {
  std::lock_guard<std::mutex> lock(posted_mutex_);
  posted_objects_.push_back(std::move(f));
}

void ViewerModel::appendObjects(ObjectBoxes f) {
  const auto it = std::upper_bound(objects_.begin(), objects_.end(), f.stamp_s,
                                   [](double t, const ObjectBoxes& o) { return t < o.stamp_s; });
  objects_.insert(it, std::move(f));
}

std::size_t ViewerModel::framesUpTo(double t_s) const {
  return std::size_t(std::upper_bound(frames_.begin(), frames_.end(), t_s,
                                      [](double t, const ViewerFrame& r) { return t < r.stamp_s; }) -
                     frames_.begin());
}

namespace {
template <class V, class Stamp>
const typename V::value_type* nearest(const V& v, double t_s, double tol_s, Stamp stamp) {
  const auto it = std::lower_bound(v.begin(), v.end(), t_s,
                                   [&](const auto& r, double t) { return stamp(r) < t; });
  const typename V::value_type* best = nullptr;
  double best_dt = tol_s;
  for (auto c : {it, it == v.begin() ? it : it - 1}) {
    if (c == v.end()) continue;
    const double dt = std::abs(stamp(*c) - t_s);
    if (dt <= best_dt) best = &*c, best_dt = dt;
  }
  return best;
}
}  // namespace

const ViewerFrame* ViewerModel::frameNear(double t_s, double tol_s) const {
  return nearest(frames_, t_s, tol_s, [](const ViewerFrame& r) { return r.stamp_s; });
}
const ViewerBoundary* ViewerModel::boundaryNear(double t_s, double tol_s) const {
  return nearest(bounds_, t_s, tol_s, [](const ViewerBoundary& r) { return r.stamp_s; });
}
const ObjectBoxes* ViewerModel::objectsNear(double t_s, double tol_s) const {
  return nearest(objects_, t_s, tol_s, [](const ObjectBoxes& r) { return r.stamp_s; });
}

void ViewerModel::loadCan(const std::string& log, const std::string& vehicle_ini) {
  if (vehicle_ini.empty()) throw std::runtime_error("--can needs --vehicle (the car's vehicle ini)");
  vehicle::VehicleLogReader reader(log, vehicle::loadVehicleIni(vehicle_ini));
  reader.readUntil(std::numeric_limits<double>::infinity(), [this](const vehicle::VehicleState& state, vehicle::UpdateMask mask) {
    const double t = state.t_s;
    if (!mask || (!can_.empty() && t - can_.back().t_s < 0.05)) return;
    CanSample c;
    c.t_s = t;
    const bool wheels = state.has(vehicle::Quantity::kWheelFL) || state.has(vehicle::Quantity::kVehicleSpeed);
    if (wheels) c.speed_mps = state.speed();
    if (state.has(vehicle::Quantity::kYawRate)) c.yaw_rate_rad_s = state.value(vehicle::Quantity::kYawRate);
    if (state.has(vehicle::Quantity::kSteeringAngle)) c.steering_rad = state.value(vehicle::Quantity::kSteeringAngle);
    addCanSample(c);
  });
  const auto& st = reader.logStats();
  if (st.bad > 0) warnings_.push_back("CAN log '" + log + "': " + std::to_string(st.bad) + " of " + std::to_string(st.lines) + " lines unreadable, skipped");
  if (can_.empty()) warnings_.push_back("CAN log '" + log + "': no frame the vehicle ini '" + vehicle_ini + "' decodes");
  else checkOverlap("CAN log '" + log + "' times", can_.front().t_s, can_.back().t_s);
}

void ViewerModel::loadMapFolder(const std::string& dir) {
  const runfolder::RunFolder run = runfolder::openMapRun(dir);
  const runfolder::StampedTrajectory traj = run.trajectory();
  const std::vector<runfolder::FrameRow> rows = run.frames();
  const std::vector<long> pose_row = runfolder::trajectoryRowOfFrames(rows, traj.size(), dir);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (pose_row[i] < 0) continue;  // skipped: no pose to draw
    const auto k = static_cast<std::size_t>(pose_row[i]);
    ViewerFrame f;
    f.stamp_s = traj.stamp(k);
    f.T_map_lidar = traj.pose(k);
    f.status = rows[i].status;
    f.keyframe = rows[i].keyframe;
    f.ms = rows[i].ms_total;
    f.inliers = rows[i].inliers;
    appendFrame(f);
  }
  if (!traj.empty()) checkOverlap("map folder '" + dir + "' times", traj.front(), traj.back());
  objects_ = readObjectsFolder(dir);  // a run with [objects] enabled
  for (const auto& l : run.mapSummary().loops_accepted) {
    if (l.query_frame >= rows.size() || l.match_frame >= rows.size()) continue;
    const long q = pose_row[l.query_frame], m = pose_row[l.match_frame];
    if (q < 0 || m < 0) continue;
    loops_.push_back({traj.stamp(std::size_t(q)), traj.pose(std::size_t(q)).translation(), traj.pose(std::size_t(m)).translation()});
  }
  if (in_.octomap) {
    const std::string bt = dir + "/map.bt";
    if (!fs::exists(bt)) throw std::runtime_error("--octomap: map folder '" + dir + "' has no map.bt ([octomap] enabled = false?)");
    octomap::OcTree tree(0.1);
    if (!tree.readBinary(bt)) throw std::runtime_error("cannot read the OctoMap '" + bt + "'");
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
      if (!tree.isNodeOccupied(*it)) continue;
      const auto c = it.getCoordinate();
      octo_voxels_.emplace_back(c.x(), c.y(), c.z(), static_cast<float>(it.getSize()));
    }
  } else if (fs::exists(dir + "/map.ply")) {
    map_points_ = readPlyPoints(dir + "/map.ply", in_.map_voxel_m);
  }
  if (in_.grid) loadGrid(dir);
}

void ViewerModel::loadGrid(const std::string& dir) {
  const std::string path = dir + "/grid.gridmap";
  if (!fs::exists(path)) throw std::runtime_error("--grid: map folder '" + dir + "' has no grid.gridmap");
  mrpt::maps::COccupancyGridMap2D g;
  try {
    mrpt::io::CFileGZInputStream f(path);
    mrpt::serialization::archiveFrom(f) >> g;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read the grid '" + path + "': " + std::string(e.what()).substr(0, 200));
  }
  GridLayer L;
  L.x_min = g.getXMin();
  L.x_max = g.getXMax();
  L.y_min = g.getYMin();
  L.y_max = g.getYMax();
  const int w = int(g.getSizeX()), h = int(g.getSizeY());
  L.rgb.resize(w, h, mrpt::img::CH_RGB);
  L.alpha.resize(w, h, mrpt::img::CH_GRAY);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float p = g.getCell(x, y);  // probability of free: 0 occupied, 1 free, 0.5 unknown
      const bool occ = p < 0.3f, fre = p > 0.7f;
      L.occupied += occ;
      L.free += fre;
      const unsigned char* c = occ ? SceneColors::grid_occupied : SceneColors::grid_free;
      auto* px = L.rgb.ptr<uint8_t>(x, h - 1 - y);  // image row 0 is the grid's top (y_max); BGR
      px[0] = c[2];
      px[1] = c[1];
      px[2] = c[0];
      *L.alpha.ptr<uint8_t>(x, h - 1 - y) = occ ? 255 : fre ? 150 : 0;
    }
  mrpt::config::CConfigFile cfg(dir + "/config_used.ini");  // the height the grid was made with
  L.lidar_height_m = cfg.read_double("grid", "lidar_height_m", L.lidar_height_m);
  grid_ = std::move(L);
}

void ViewerModel::loadBounds(const std::string& dir) {
  for (const auto& r : runfolder::openBoundsRun(dir).boundaries()) {
    if (!r.has_pose) continue;  // a sweep without a pose has no boundaries
    ViewerBoundary b;
    b.stamp_s = r.stamp_s;
    b.left = r.left.polyline_map;
    b.right = r.right.polyline_map;
    for (const auto& p : r.free_space) b.free_space.push_back(r.T_map_lidar * Eigen::Vector3d(p.x(), p.y(), 0.0));
    bounds_.push_back(std::move(b));
  }
  std::sort(bounds_.begin(), bounds_.end(), [](const auto& a, const auto& b) { return a.stamp_s < b.stamp_s; });
  if (!bounds_.empty()) checkOverlap("bounds folder '" + dir + "' times", bounds_.front().stamp_s, bounds_.back().stamp_s);
}

// Ground truth is in its own world frame: it is drawn anchored to the estimated trajectory at the
// first estimated frame it covers (T_map_gt = T_map_lidar(t) * T_gt_lidar(t)^-1, the ground truth
// interpolated at the frame's time), or as is without one.
void ViewerModel::loadGroundTruth(const std::string& path) {
  const runfolder::StampedTrajectory gt = runfolder::readTrajectory(path);
  if (gt.empty()) return;
  checkOverlap("ground truth '" + path + "' times", gt.front(), gt.back());
  constexpr double kMaxGtGap_s = 0.12;  // a frame between ground-truth poses farther apart is not covered
  Eigen::Isometry3d T_map_gt = Eigen::Isometry3d::Identity();
  for (const auto& f : frames_) {
    const auto T_gt_lidar = gt.at(f.stamp_s, kMaxGtGap_s);
    if (!T_gt_lidar) continue;
    T_map_gt = f.T_map_lidar * T_gt_lidar->inverse();
    break;
  }
  for (std::size_t i = 0; i < gt.size(); ++i) {
    gt_stamps_.push_back(gt.stamp(i));
    gt_positions_.push_back((T_map_gt * gt.pose(i)).translation());
  }
}

}  // namespace roadslam::viewer
