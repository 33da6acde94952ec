// The figures of issue 23 (GNSS fusion), printed as tables; not a timed test.
//
//   bench_gnss sim --scenario S.ini --sim SIM --run RUN --config C.ini
//     SIM: a roadslam-sim output of S.ini (its gt_trajectory.tum); RUN: roadslam-map's output on
//     SIM/velodyne.pcap (its trajectory.tum); C.ini: the [gnss_fusion] used. The receiver is simulated
//     here from S.ini's [gnss] (rate, noise) in three variants: as is, with a 30 s outage, with a 50 m
//     multipath jump, each fused into RUN's trajectory and scored in the world (= ENU) frame.
//   bench_gnss rav4 --data DIR/can/rav4-2017 --vehicle ini/vehicles/toyota-rav4-2017.ini [--seed N]
//     the real RAV4 drive: its ECEF reference subsampled to 1 Hz with 1, 2 and 3 m of noise as fixes,
//     fused with its CAN dead reckoning; errors against the full 20 Hz reference.
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <filesystem>

#include <mrpt/config/CConfigFileMemory.h>

#include "roadslam/can/candump.h"
#include "roadslam/common/config.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/gnss/geo.h"
#include "roadslam/mapping/gnss_fusion.h"
#include "roadslam/pipeline/gnss_outputs.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/vehicle/odometry.h"
#include "roadslam/vehicle/params.h"
#include "roadslam/vehicle/vehicle_state.h"

using namespace roadslam;
using mapping::PoseVector;

namespace {

std::string arg(int argc, char** argv, const std::string& name, const std::string& def = "") {
  for (int i = 2; i + 1 < argc; ++i)
    if (argv[i] == name) return argv[i + 1];
  if (def.empty()) throw std::runtime_error("missing " + name);
  return def;
}

struct Err {
  double rms3 = 0, rms2 = 0, max2 = 0;
};
Err errors(const std::vector<Eigen::Vector3d>& est, const std::vector<Eigen::Vector3d>& gt) {
  Err e;
  for (size_t i = 0; i < est.size(); ++i) {
    const Eigen::Vector3d d = est[i] - gt[i];
    e.rms3 += d.squaredNorm();
    e.rms2 += d.head<2>().squaredNorm();
    e.max2 = std::max(e.max2, d.head<2>().norm());
  }
  e.rms3 = std::sqrt(e.rms3 / std::max<size_t>(1, est.size()));
  e.rms2 = std::sqrt(e.rms2 / std::max<size_t>(1, est.size()));
  return e;
}

/// Umeyama (no scale): best rigid T with T a_i ~ b_i.
Eigen::Isometry3d rigidFit(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  Eigen::Matrix3Xd A(3, a.size()), B(3, b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    A.col(static_cast<Eigen::Index>(i)) = a[i];
    B.col(static_cast<Eigen::Index>(i)) = b[i];
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.matrix() = Eigen::umeyama(A, B, false);
  return T;
}

void row(const std::string& name, const Err& e, const std::string& extra = "") {
  std::printf("| %-44s | %7.3f | %7.3f | %7.2f | %s\n", name.c_str(), e.rms3, e.rms2, e.max2, extra.c_str());
}

int simFigures(int argc, char** argv) {
  const auto sp0 = sim::ScenarioParams::fromFile(arg(argc, argv, "--scenario"));
  const std::string sim_dir = arg(argc, argv, "--sim"), run = arg(argc, argv, "--run");
  mapping::GnssFusionParams fp;
  fp.loadFromConfigFile(*loadIniFile(arg(argc, argv, "--config")), "gnss_fusion");
  const auto traj = datasets::readTum(run + "/trajectory.tum");
  const auto gt = datasets::readTum(sim_dir + "/gt_trajectory.tum");
  const gnss::EnuFrame world({sp0.origin_lat_deg, sp0.origin_lon_deg, sp0.gnss.origin_h_m});
  auto gtAt = [&](double t) { return mapping::interpolatePose(gt.stamps_s, gt.poses, t); };
  std::vector<Eigen::Vector3d> truth, odo;
  for (size_t i = 0; i < traj.poses.size(); ++i) {
    truth.push_back(gtAt(traj.stamps_s[i]).translation());
    odo.push_back(traj.poses[i].translation());
  }
  // odometry alone: placed by the true first pose, and by its best rigid fit to the truth (flattering)
  const Eigen::Isometry3d T_first = gtAt(traj.stamps_s[0]) * traj.poses[0].inverse();
  std::vector<Eigen::Vector3d> odo_first, odo_fit;
  const Eigen::Isometry3d T_fit = rigidFit(odo, truth);
  for (const auto& p : odo) {
    odo_first.push_back(T_first * p);
    odo_fit.push_back(T_fit * p);
  }
  const double T_end = traj.stamps_s.back() - static_cast<double>(sp0.start_epoch_s);
  struct Variant {
    std::string name;
    double outage_start, outage_len, mp_start, mp_len;
  };
  const std::vector<Variant> variants = {{"as simulated", 0, 0, 0, 0},
                                         {"30 s outage from t = 60 s", 60, 30, 0, 0},
                                         {"50 m multipath jump, t = 100-103 s", 0, 0, 100, 3}};
  std::printf("scenario %s: %.0f m, %zu frames, GNSS %.0f Hz, %.1f m white noise (%.1f m up), lever arm in the lidar frame "
              "(%.2f, %.2f, %.2f) m\n",
              sp0.name.c_str(), sim::Simulator(sp0).trajectory().at(T_end).s_m, traj.poses.size(), sp0.gnss.rate_hz,
              sp0.gnss.noise_sigma_m, sp0.gnss.noise_sigma_up_m, fp.lever_x_m, fp.lever_y_m, fp.lever_z_m);
  std::printf("| %-44s | ATE 3D  | ATE 2D  | max 2D  | notes\n|---|---|---|---|---|\n", "trajectory (world = ENU frame)");
  row("LiDAR odometry + loops, placed by its first pose", errors(odo_first, truth));
  row("LiDAR odometry + loops, best rigid fit (flatters)", errors(odo_fit, truth));
  for (const Variant& v : variants) {
    auto sp = sp0;
    sp.gnss.enabled = true;
    sp.gnss.outage_start_s = v.outage_start;
    sp.gnss.outage_duration_s = v.outage_len;
    sp.gnss.multipath_start_s = v.mp_start;
    sp.gnss.multipath_duration_s = v.mp_len;
    sp.gnss.multipath_offset_m = 50;
    const sim::Simulator s(sp);
    const std::string dir = (std::filesystem::temp_directory_path() / "bench_gnss_sim").string() + "/";
    std::filesystem::create_directories(dir);
    const auto gr = sim::writeGnss(s, T_end, dir);
    const auto in = pipeline::readGnssInput(dir + "gnss.nmea", fp);
    const gnss::EnuFrame fe(in.origin);
    // GNSS alone: each fix against the true antenna
    std::vector<Eigen::Vector3d> fx, fx_truth;
    for (const auto& f : in.factors) {
      fx.push_back(world.toEnu(fe.toGeodetic(f.p_enu)));
      fx_truth.push_back(gtAt(f.t_s) * fp.lever());
    }
    const auto r = mapping::fuseGnss(traj.stamps_s, traj.poses, in.factors, fp);
    std::vector<Eigen::Vector3d> fused;
    for (const auto& T : r.T_enu_node) fused.push_back(world.toEnu(fe.toGeodetic(T.translation())));
    row("GNSS fixes alone (" + v.name + ")", errors(fx, fx_truth),
        std::to_string(in.factors.size()) + " fixes of " + std::to_string(gr.epochs) + " epochs");
    char notes[300];
    std::snprintf(notes, sizeof(notes), "%zu used, %zu rejected (%zu multipath epochs), %d iterations, %.0f ms", r.used,
                  r.rejected, gr.multipath_epochs, r.iterations, r.ms);
    row("fused (" + v.name + ")", errors(fused, truth), notes);
    // steps: the fused path's step against the true step, worst near reacquisition and anywhere
    double worst = 0, worst_reacq = 0;
    const double t_reacq = static_cast<double>(sp.start_epoch_s) + v.outage_start + v.outage_len;
    for (size_t i = 1; i < fused.size(); ++i) {
      const double d = ((fused[i] - fused[i - 1]) - (truth[i] - truth[i - 1])).norm();
      worst = std::max(worst, d);
      if (v.outage_len > 0 && std::abs(traj.stamps_s[i] - t_reacq) < 2.0) worst_reacq = std::max(worst_reacq, d);
    }
    if (v.outage_len > 0) {
      std::vector<Eigen::Vector3d> in_out, in_truth;
      for (size_t i = 0; i < fused.size(); ++i) {
        const double t = traj.stamps_s[i] - static_cast<double>(sp.start_epoch_s);
        if (t >= v.outage_start && t < v.outage_start + v.outage_len) {
          in_out.push_back(fused[i]);
          in_truth.push_back(truth[i]);
        }
      }
      const Err eo = errors(in_out, in_truth);
      std::printf("|   outage: largest step error within 2 s of reacquisition %.3f m, anywhere %.3f m; in the outage "
                  "rms %.3f m, max %.3f m (2D)\n", worst_reacq, worst, eo.rms2, eo.max2);
    }
    if (v.mp_len > 0) {
      double worst_mp = 0;
      for (size_t i = 0; i < fused.size(); ++i) {
        const double t = traj.stamps_s[i] - static_cast<double>(sp.start_epoch_s);
        if (t >= v.mp_start - 1 && t < v.mp_start + v.mp_len + 1) worst_mp = std::max(worst_mp, (fused[i] - truth[i]).head<2>().norm());
      }
      std::printf("|   multipath: %zu of %zu jump epochs rejected; largest 2D error within 1 s of the jump %.3f m\n",
                  r.rejected, gr.multipath_epochs, worst_mp);
    }
  }
  return 0;
}

int rav4Figures(int argc, char** argv) {
  const std::string dir = arg(argc, argv, "--data") + "/";
  const uint64_t seed = std::stoull(arg(argc, argv, "--seed", "23"));
  // the reference: ECEF camera poses at 20 Hz, into an ENU frame at the first
  std::ifstream in(dir + "gt_camera_pose_ecef_20hz.csv");
  if (!in) throw std::runtime_error("cannot read " + dir + "gt_camera_pose_ecef_20hz.csv");
  std::string line;
  std::getline(in, line);
  std::vector<double> rt;
  std::vector<Eigen::Vector3d> ecef;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<double> v;
    for (std::string tok; std::getline(ss, tok, ',');) v.push_back(std::stod(tok));
    rt.push_back(v.at(0));
    ecef.emplace_back(v.at(4), v.at(5), v.at(6));
  }
  const gnss::EnuFrame enu(gnss::geodeticFromEcef(ecef.front()));
  std::vector<Eigen::Vector3d> ref;
  for (const auto& x : ecef) ref.push_back(enu.enuFromEcef(x));
  // dead reckoning from the CAN log, started on the reference (position, direction of travel over 2 s)
  const auto vp = vehicle::loadVehicleIni(arg(argc, argv, "--vehicle"), arg(argc, argv, "--data") + "/../..");
  const auto frames = can::readCandumpFile(dir + "rav4_2018-08-02_seg40.candump.log");
  size_t k2 = 0;
  while (k2 + 1 < rt.size() && rt[k2] - rt[0] < 2.0) ++k2;
  vehicle::Pose2D start;
  start.x_m = ref[0].x();
  start.y_m = ref[0].y();
  start.yaw_rad = std::atan2(ref[k2].y() - ref[0].y(), ref[k2].x() - ref[0].x());
  vehicle::VehicleDecoder dec(vp);
  const auto dr = vehicle::runOdometry(frames, dec, vehicle::DeadReckoningParams{}, start);
  // nodes: dead reckoning at 10 Hz over the reference's span
  std::vector<double> nt;
  PoseVector nodes;
  std::vector<double> dt_all;
  PoseVector dr_all;
  for (const auto& p : dr.poses) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(p.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(p.x_m, p.y_m, 0);
    if (!dt_all.empty() && p.t_s <= dt_all.back()) continue;
    dt_all.push_back(p.t_s);
    dr_all.push_back(T);
  }
  for (double t = rt.front(); t <= rt.back() + 1e-9; t += 0.1) {
    nt.push_back(t);
    nodes.push_back(mapping::interpolatePose(dt_all, dr_all, t));
  }
  // dead reckoning re-anchored at the first reference time
  const Eigen::Isometry3d anchor = [&] {
    Eigen::Isometry3d A = Eigen::Isometry3d::Identity();
    A.translation() = ref[0] - nodes[0].translation();
    A.translation().z() = ref[0].z();
    return A;
  }();
  std::vector<Eigen::Vector3d> dr_ref;
  for (double t : rt) dr_ref.push_back(anchor * mapping::interpolatePose(nt, nodes, t).translation());
  mapping::GnssFusionParams fp;
  // dead reckoning's motion: the raw yaw rate carries a -0.4 deg/s bias (0.024 deg per metre at
  // 17 m/s); the wheel speeds a scale error of a few tenths of a percent
  fp.edge_sigma_t_per_m = 0.01;
  fp.edge_sigma_r_rad_per_m = 0.05 * M_PI / 180;
  fp.attitude_prior_sigma_rad = 0.5 * M_PI / 180;
  std::printf("RAV4 drive: %zu reference poses over %.1f s, %zu dead-reckoning nodes (10 Hz), seed %llu; fixes = "
              "reference at 1 Hz + white noise (sigma horizontally, 1.5 sigma up)\n",
              rt.size(), rt.back() - rt.front(), nt.size(), static_cast<unsigned long long>(seed));
  std::printf("| %-44s | ATE 3D  | ATE 2D  | max 2D  | notes\n|---|---|---|---|---|\n", "trajectory vs 20 Hz reference");
  row("CAN dead reckoning alone (raw yaw rate)", errors(dr_ref, ref));
  for (double sigma : {1.0, 2.0, 3.0}) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01(0, 1);
    std::vector<mapping::GnssFactor> fixes;
    for (size_t i = 0; i < rt.size(); i += 20) {
      mapping::GnssFactor f;
      f.t_s = rt[i];
      f.p_enu = ref[i] + Eigen::Vector3d(n01(rng) * sigma, n01(rng) * sigma, n01(rng) * 1.5 * sigma);
      f.cov = Eigen::Vector3d(sigma * sigma, sigma * sigma, 2.25 * sigma * sigma).asDiagonal();
      fixes.push_back(f);
    }
    // fixes alone: the fixes linearly interpolated at the reference times
    std::vector<double> ft;
    PoseVector fT;
    for (const auto& f : fixes) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = f.p_enu;
      ft.push_back(f.t_s);
      fT.push_back(T);
    }
    std::vector<Eigen::Vector3d> fix_ref, fused_ref;
    for (double t : rt) fix_ref.push_back(mapping::interpolatePose(ft, fT, t).translation());
    const auto r = mapping::fuseGnss(nt, nodes, fixes, fp);
    for (double t : rt) fused_ref.push_back(mapping::interpolatePose(nt, r.T_enu_node, t).translation());
    char s[64];
    std::snprintf(s, sizeof(s), "%.0f m", sigma);
    row(std::string("fixes alone, 1 Hz, ") + s + " noise, interpolated", errors(fix_ref, ref),
        std::to_string(fixes.size()) + " fixes");
    char notes[200];
    std::snprintf(notes, sizeof(notes), "%s: %zu used, %zu rejected, %d iterations, %.0f ms", r.status.c_str(), r.used,
                  r.rejected, r.iterations, r.ms);
    row(std::string("fused, ") + s + " noise", errors(fused_ref, ref), notes);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "sim") return simFigures(argc, argv);
    if (mode == "rav4") return rav4Figures(argc, argv);
    std::fprintf(stderr, "usage: bench_gnss sim --scenario S.ini --sim SIM --run RUN --config C.ini\n"
                         "       bench_gnss rav4 --data DIR/can/rav4-2017 --vehicle ini/vehicles/toyota-rav4-2017.ini [--seed N]\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_gnss: %s\n", e.what());
    return 1;
  }
}
