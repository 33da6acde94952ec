// The GNSS fusion figures, printed as tables; not a timed test.
//
//   bench_gnss sim --scenario S.ini --sim SIM --run RUN --config C.ini
//     SIM: a roadslam-sim output of S.ini (its gt_trajectory.tum); RUN: roadslam-map's output on
//     SIM/velodyne.pcap (its trajectory.tum); C.ini: the [gnss_fusion] used. The receiver is simulated
//     here from S.ini's [gnss] (rate, noise) in three variants: as is, with a 30 s outage, with a 50 m
//     multipath jump, each fused into RUN's trajectory and scored in the world (= ENU) frame.
//   bench_gnss rav4 --data DIR/can/rav4-2017 --vehicle ini/vehicles/toyota-rav4-2017.ini [--seed N]
//     the real RAV4 drive: its ECEF reference subsampled to 1 Hz with 1, 2 and 3 m of noise as fixes,
//     fused with its CAN dead reckoning; errors against the full 20 Hz reference.
//   either with --optimizer gauss_newton | ceres: the solver of the fusion ([gnss_fusion] optimizer).
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
#include "roadslam/gnss_fusion/gnss_fusion.h"
#include "roadslam/gnss_fusion/gnss_fusion_online.h"
#include "roadslam/jobs/gnss_outputs.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/vehicle/can_odometry.h"
#include "roadslam/vehicle/params.h"
#include "roadslam/vehicle/vehicle_state.h"

using namespace roadslam;
using gnss_fusion::PoseVector;

namespace {

std::string arg(int argc, char** argv, const std::string& name, const std::string& def = "") {
  for (int i = 2; i + 1 < argc; ++i)
    if (argv[i] == name) return argv[i + 1];
  if (def.empty()) throw std::runtime_error("missing " + name);
  return def;
}

/// --optimizer gauss_newton | ceres ([gnss_fusion] optimizer; absent: the config's or the default).
void optimizerArg(int argc, char** argv, gnss_fusion::GnssFusionParams& fp) {
  const std::string o = arg(argc, argv, "--optimizer", "-");
  if (o == "ceres") fp.optimizer = gnss_fusion::GnssOptimizer::Ceres;
  else if (o == "gauss_newton") fp.optimizer = gnss_fusion::GnssOptimizer::GaussNewton;
  else if (o != "-") throw std::runtime_error("--optimizer " + o + ": expected gauss_newton or ceres");
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

/// The online (causal) mode on the odometry's own trajectory: its error over the frames it anchored,
/// and the largest step error (fused step against the true step) anywhere and within 2 s of \p t_reacq.
template <class GtAt>
void onlineRow(const std::string& name, const datasets::Trajectory& odo, const std::vector<gnss_fusion::GnssFactor>& fixes,
               const gnss_fusion::GnssFusionParams& fp, const gnss::EnuFrame& world, const gnss::EnuFrame& fe, GtAt gtAt,
               double t_reacq, bool outage) {
  gnss_fusion::GnssOnlineStats st;
  const auto on = gnss_fusion::replayOnline(odo.stamps_s, odo.poses, fixes, fp, &st);
  std::vector<Eigen::Vector3d> est, truth;
  std::vector<double> t;
  for (size_t i = 0; i < on.size(); ++i) {
    if (!on[i]) continue;
    est.push_back(world.toEnu(fe.toGeodetic(on[i]->translation())));
    truth.push_back(gtAt(odo.stamps_s[i]).translation());
    t.push_back(odo.stamps_s[i]);
  }
  double worst = 0, worst_reacq = 0;
  for (size_t i = 1; i < est.size(); ++i) {
    const double d = ((est[i] - est[i - 1]) - (truth[i] - truth[i - 1])).norm();
    worst = std::max(worst, d);
    if (outage && std::abs(t[i] - t_reacq) < 2.0) worst_reacq = std::max(worst_reacq, d);
  }
  char notes[400], bias[80] = "";
  if (fp.online_yaw_rate_bias)
    std::snprintf(bias, sizeof(bias), ", yaw-rate correction %.4f deg/s, scale %.5f", st.yaw_rate_correction_radps * 180 / M_PI, st.scale);
  std::snprintf(notes, sizeof(notes), "%zu of %zu frames anchored, %zu solves, %.1f ms per solve (max %.0f), largest step error %.3f m%s%s",
                est.size(), on.size(), st.solves, st.solves ? st.ms_total / double(st.solves) : 0.0, st.ms_max, worst,
                outage ? (", " + std::to_string(worst_reacq).substr(0, 5) + " m within 2 s of reacquisition").c_str() : "", bias);
  row("online, causal (" + name + ")", errors(est, truth), notes);
}

int simFigures(int argc, char** argv) {
  const auto sp0 = sim::ScenarioParams::fromFile(arg(argc, argv, "--scenario"));
  const std::string sim_dir = arg(argc, argv, "--sim"), run = arg(argc, argv, "--run");
  gnss_fusion::GnssFusionParams fp;
  fp.loadFromConfigFile(*loadIniFile(arg(argc, argv, "--config")), "gnss_fusion");
  optimizerArg(argc, argv, fp);
  const auto traj = datasets::readTum(run + "/trajectory.tum");
  const auto odo_traj = datasets::readTum(run + "/trajectory_odometry.tum");  // causal: the online mode's input
  const auto gt = datasets::readTum(sim_dir + "/gt_trajectory.tum");
  const gnss::EnuFrame world({sp0.origin_lat_deg, sp0.origin_lon_deg, sp0.gnss.origin_h_m});
  auto gtAt = [&](double t) { return gnss_fusion::interpolatePose(gt.stamps_s, gt.poses, t); };
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
    double outage_start, outage_len, mp_start, mp_len, bias_walk;
  };
  const std::vector<Variant> variants = {{"as simulated", 0, 0, 0, 0, 0},
                                         {"30 s outage from t = 60 s", 60, 30, 0, 0, 0},
                                         {"50 m multipath jump, t = 100-103 s", 0, 0, 100, 3, 0},
                                         {"+ bias walk 0.05 m/sqrt(s)", 0, 0, 0, 0, 0.05}};
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
    if (v.bias_walk > 0) sp.gnss.bias_walk_m_per_sqrt_s = v.bias_walk;
    const sim::Simulator s(sp);
    const std::string dir = (std::filesystem::temp_directory_path() / "bench_gnss_sim").string() + "/";
    std::filesystem::create_directories(dir);
    const auto gr = sim::writeGnss(s, T_end, dir);
    const auto in = jobs::readGnssInput(dir + "gnss.nmea", fp);
    const gnss::EnuFrame fe(in.origin);
    // GNSS alone: each fix against the true antenna
    std::vector<Eigen::Vector3d> fx, fx_truth;
    for (const auto& f : in.factors) {
      fx.push_back(world.toEnu(fe.toGeodetic(f.p_enu)));
      fx_truth.push_back(gtAt(f.t_s) * fp.lever());
    }
    const auto r = gnss_fusion::fuseGnss(traj.stamps_s, traj.poses, in.factors, fp);
    std::vector<Eigen::Vector3d> fused;
    for (const auto& T : r.T_enu_node) fused.push_back(world.toEnu(fe.toGeodetic(T.translation())));
    row("GNSS fixes alone (" + v.name + ")", errors(fx, fx_truth),
        std::to_string(in.factors.size()) + " fixes of " + std::to_string(gr.epochs) + " epochs");
    char notes[300];
    std::snprintf(notes, sizeof(notes), "%zu used, %zu rejected (%zu multipath epochs), %d iterations, %.0f ms", r.used,
                  r.rejected, gr.multipath_epochs, r.iterations, r.ms);
    row("fused (" + v.name + ")", errors(fused, truth), notes);
    const double t_reacq = static_cast<double>(sp.start_epoch_s) + v.outage_start + v.outage_len;
    onlineRow(v.name, odo_traj, in.factors, fp, world, fe, gtAt, t_reacq, v.outage_len > 0);
    auto biased = fp;  // the same with the yaw-rate bias state, side by side
    biased.online_yaw_rate_bias = true;
    onlineRow(v.name + ", online_yaw_rate_bias", odo_traj, in.factors, biased, world, fe, gtAt, t_reacq, v.outage_len > 0);
    biased.online_odometry_scale = true;
    onlineRow(v.name + ", + online_odometry_scale", odo_traj, in.factors, biased, world, fe, gtAt, t_reacq, v.outage_len > 0);
    if (v.outage_len > 0) {  // the blending's share: the same without it
      auto jump = fp;
      jump.online_blend_s = 0;
      onlineRow(v.name + ", online_blend_s = 0", odo_traj, in.factors, jump, world, fe, gtAt, t_reacq, true);
    }
    if (v.outage_len == 0 && v.mp_len == 0 && v.bias_walk == 0) {  // the first anchoring on 50 m of path
      auto late = fp;
      late.online_min_path_m = 50;
      onlineRow(v.name + ", online_min_path_m = 50", odo_traj, in.factors, late, world, fe, gtAt, t_reacq, false);
    }
    // steps: the fused path's step against the true step, worst near reacquisition and anywhere
    double worst = 0, worst_reacq = 0;
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
  // dead reckoning as nodes at 10 Hz over the reference's span, T_enu_base with the start on the reference
  struct Dr {
    std::vector<double> t;
    PoseVector T;
    std::vector<vehicle::MotionSample> samples;
  };
  auto deadReckon = [&](double bias_radps) {
    vehicle::VehicleDecoder dec(vp);
    vehicle::DeadReckoningParams dp;
    dp.yaw_rate_bias_radps = bias_radps;
    const auto dr = vehicle::runOdometry(frames, dec, dp, start);
    std::vector<double> dt_all;
    PoseVector dr_all;
    for (const auto& p : dr.poses) {
      if (!dt_all.empty() && p.t_s <= dt_all.back()) continue;
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(p.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      T.translation() = Eigen::Vector3d(p.x_m, p.y_m, 0);
      dt_all.push_back(p.t_s);
      dr_all.push_back(T);
    }
    Dr out;
    out.samples = dr.samples;
    for (double t = rt.front(); t <= rt.back() + 1e-9; t += 0.1) {
      out.t.push_back(t);
      out.T.push_back(gnss_fusion::interpolatePose(dt_all, dr_all, t));
    }
    // re-anchored at the first reference time (the log starts ~0.04 s before the reference)
    const Eigen::Vector3d shift = ref[0] - out.T[0].translation();
    for (auto& T : out.T) T.translation() += shift;
    return out;
  };
  const Dr raw = deadReckon(0.0);
  // scored on the reference times the fixes span (1 Hz: the last second has no fix after it)
  const size_t n_eval = ((rt.size() - 1) / 20) * 20 + 1;
  const std::vector<Eigen::Vector3d> ref_eval(ref.begin(), ref.begin() + static_cast<long>(n_eval));
  auto at = [&](const std::vector<double>& t, const PoseVector& T) {
    std::vector<Eigen::Vector3d> out;
    for (size_t i = 0; i < n_eval; ++i) out.push_back(gnss_fusion::interpolatePose(t, T, rt[i]).translation());
    return out;
  };
  gnss_fusion::GnssFusionParams fp;  // [gnss_fusion] defaults but the dead reckoning's looser steps:
  fp.edge_sigma_t_per_m = 0.01;  // wheel-speed scale errors of a few tenths of a percent
  fp.edge_sigma_r_rad_per_m = 0.01 * M_PI / 180;
  fp.attitude_prior_sigma_rad = 0.5 * M_PI / 180;
  fp.edge_vertical_scale = 100;  // planar: no height, roll or pitch
  optimizerArg(argc, argv, fp);
  std::printf("RAV4 drive: %zu reference poses over %.1f s, %zu dead-reckoning nodes (10 Hz), seed %llu; fixes = "
              "reference at 1 Hz + white noise (sigma horizontally, 1.5 sigma up)\n",
              rt.size(), rt.back() - rt.front(), raw.t.size(), static_cast<unsigned long long>(seed));
  std::printf("| %-44s | ATE 3D  | ATE 2D  | max 2D  | notes\n|---|---|---|---|---|\n", "trajectory vs 20 Hz reference");
  row("CAN dead reckoning alone (raw yaw rate)", errors(at(raw.t, raw.T), ref_eval));
  for (double sigma : {1.0, 2.0, 3.0}) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01(0, 1);
    std::vector<gnss_fusion::GnssFactor> fixes;
    for (size_t i = 0; i < rt.size(); i += 20) {
      gnss_fusion::GnssFactor f;
      f.t_s = rt[i];
      f.p_enu = ref[i] + Eigen::Vector3d(n01(rng) * sigma, n01(rng) * sigma, n01(rng) * 1.5 * sigma);
      f.cov = Eigen::Vector3d(sigma * sigma, sigma * sigma, 2.25 * sigma * sigma).asDiagonal();
      fixes.push_back(f);
    }
    // fixes alone: linearly interpolated at the reference times
    std::vector<double> ft;
    PoseVector fT;
    std::vector<gnss::GnssFix> course;  // for the dead reckoning's yaw-rate bias (vehicle/can_odometry.h)
    for (size_t k = 0; k < fixes.size(); ++k) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = fixes[k].p_enu;
      ft.push_back(fixes[k].t_s);
      fT.push_back(T);
      if (k == 0 || k + 1 == fixes.size()) continue;
      const Eigen::Vector3d d = fixes[k + 1].p_enu - fixes[k - 1].p_enu;  // central difference over 2 s
      const gnss::Geodetic g = enu.toGeodetic(fixes[k].p_enu);
      gnss::GnssFix c;
      c.t_receiver_s = c.t_receive_s = fixes[k].t_s;
      c.position = g;
      c.has_position = true;
      c.speed_mps = d.head<2>().norm() / (fixes[k + 1].t_s - fixes[k - 1].t_s);
      c.course_rad = std::atan2(d.x(), d.y());
      course.push_back(c);
    }
    const auto bias = vehicle::estimateYawRateBias(raw.samples, course);
    const Dr cal = deadReckon(bias.bias_radps);
    const auto r = gnss_fusion::fuseGnss(cal.t, cal.T, fixes, fp);
    char s[64];
    std::snprintf(s, sizeof(s), "%.0f m", sigma);
    row(std::string("fixes alone, 1 Hz, ") + s + " noise, interpolated", errors(at(ft, fT), ref_eval),
        std::to_string(fixes.size()) + " fixes");
    // fixes alone, causal (the online mode's fair peer): the newest fix carried on by the velocity of
    // the last two, t in [t_k, t_k+1)
    std::vector<Eigen::Vector3d> fc;
    for (size_t i = 0; i < n_eval; ++i) {
      size_t k = 0;
      while (k + 1 < fixes.size() && fixes[k + 1].t_s <= rt[i]) ++k;
      const Eigen::Vector3d v = k == 0 ? Eigen::Vector3d::Zero()
                                       : Eigen::Vector3d((fixes[k].p_enu - fixes[k - 1].p_enu) / (fixes[k].t_s - fixes[k - 1].t_s));
      fc.push_back(fixes[k].p_enu + v * (rt[i] - fixes[k].t_s));
    }
    row(std::string("fixes alone, causal, ") + s + " noise, extrapolated", errors(fc, ref_eval),
        "the newest fix + the last two fixes' velocity x age");
    char b[80];
    std::snprintf(b, sizeof(b), "yaw-rate bias %.3f deg/s from the fixes' course", bias.bias_radps * 180 / M_PI);
    row(std::string("dead reckoning, bias from the ") + s + " fixes", errors(at(cal.t, cal.T), ref_eval), b);
    char notes[300];
    std::snprintf(notes, sizeof(notes), "%s: %zu used, %zu rejected, %d iterations%s, %.0f ms", r.status.c_str(), r.used,
                  r.rejected, r.iterations, r.converged ? "" : " (max)", r.ms);
    row(std::string("fused, ") + s + " noise (bias-corrected DR)", errors(at(cal.t, r.T_enu_node), ref_eval), notes);
    // online: causal, so on the raw dead reckoning (the bias above is estimated from every fix); without
    // and with its own causal yaw-rate bias state
    for (int mode : {0, 1, 2}) {  // no state, the yaw-rate bias, the bias and the scale
      const bool with_bias = mode > 0;
      auto op = fp;
      op.online_yaw_rate_bias = with_bias;
      op.online_odometry_scale = mode == 2;
      gnss_fusion::GnssOnlineStats ost;
      const auto on = gnss_fusion::replayOnline(raw.t, raw.T, fixes, op, &ost);
      std::vector<double> ot;
      PoseVector oT;
      for (size_t i = 0; i < on.size(); ++i)
        if (on[i]) {
          ot.push_back(raw.t[i]);
          oT.push_back(*on[i]);
        }
      std::vector<Eigen::Vector3d> oe, orf;
      for (size_t i = 0; !ot.empty() && i < n_eval; ++i)
        if (rt[i] >= ot.front()) {
          oe.push_back(gnss_fusion::interpolatePose(ot, oT, rt[i]).translation());
          orf.push_back(ref[i]);
        }
      std::snprintf(notes, sizeof(notes), "scored from its first solve (t = %.0f s), %zu solves, %zu failed, %.1f ms per solve%s",
                    ot.empty() ? 0.0 : ot.front() - rt.front(), ost.solves, ost.failed,
                    ost.solves ? ost.ms_total / double(ost.solves) : 0.0,
                    with_bias ? (", yaw-rate bias " + std::to_string(-ost.yaw_rate_correction_radps * 180 / M_PI).substr(0, 6) +
                                 " deg/s, scale " + std::to_string(ost.scale).substr(0, 6) + " at the end, " +
                                 std::to_string(ost.bias_updates) + " updates").c_str() : "");
      row(std::string("online, causal, ") + s + " noise (raw DR)" + (mode == 1 ? ", bias state" : mode == 2 ? ", bias + scale" : ""),
          errors(oe, orf), notes);
    }
    gnss_fusion::GnssOnlineStats ost;
    if (sigma == 1.0) {  // the first anchoring on 50 m of path
      auto late = fp;
      late.online_min_path_m = 50;
      const auto on50 = gnss_fusion::replayOnline(raw.t, raw.T, fixes, late, &ost);
      std::vector<double> t50;
      PoseVector T50;
      for (size_t i = 0; i < on50.size(); ++i)
        if (on50[i]) {
          t50.push_back(raw.t[i]);
          T50.push_back(*on50[i]);
        }
      std::vector<Eigen::Vector3d> e50, r50;
      for (size_t i = 0; !t50.empty() && i < n_eval; ++i)
        if (rt[i] >= t50.front()) {
          e50.push_back(gnss_fusion::interpolatePose(t50, T50, rt[i]).translation());
          r50.push_back(ref[i]);
        }
      std::snprintf(notes, sizeof(notes), "scored from its first solve (t = %.0f s)", t50.empty() ? 0.0 : t50.front() - rt.front());
      row("online, causal, 1 m noise (raw DR), online_min_path_m = 50", errors(e50, r50), notes);
    }
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
