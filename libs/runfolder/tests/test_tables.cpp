// The run folder's tables: written and read back, read by column name whatever the order, and a
// missing column or key failing naming the file and the column.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "roadslam/runfolder/csv.h"
#include "roadslam/runfolder/run_folder.h"
#include "test_util.h"

using namespace roadslam::runfolder;
using namespace roadslam::runfolder::test;

namespace {

FrameRow frame(size_t i) {
  FrameRow f;
  f.index = i, f.stamp_s = 1700000000.123456 + 0.1 * i, f.status = i == 1 ? "skipped" : "ok";
  f.point_times = "sensor", f.deskewed = true, f.keyframe = i % 2 == 0;
  f.x_m = 1.25 * i, f.y_m = -2.5, f.z_m = 0.125, f.points_in = 28000 + int(i), f.points_registered = 3000;
  f.iterations = 7, f.inliers = 2900, f.fitness_m = 0.0625, f.threshold_m = 0.5, f.weak_directions = int(i % 3);
  f.motion_information = i == 2 ? std::nan("") : 12.5, f.ms_total = 20.5;
  f.reason = i == 1 ? "too few points: 10, wanted 100" : "";
  return f;
}

/// \p path's columns rearranged into \p order (by name) plus an unknown column "extra".
void reorder(const std::string& path, const std::vector<std::string>& order) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const auto header = splitCsvLine(line);
  std::string out;
  for (const auto& c : order) out += c + ",";
  out += "extra\n";
  while (std::getline(in, line)) {
    const auto cells = splitCsvLine(line);
    for (const auto& c : order)
      out += cells[size_t(std::find(header.begin(), header.end(), c) - header.begin())] + ",";
    out += "42\n";
  }
  in.close();
  writeText(path, out);
}

void expectSame(const FrameRow& a, const FrameRow& b) {
  EXPECT_EQ(a.index, b.index);
  EXPECT_NEAR(a.stamp_s, b.stamp_s, 1e-6);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.point_times, b.point_times);
  EXPECT_EQ(a.deskewed, b.deskewed);
  EXPECT_EQ(a.keyframe, b.keyframe);
  EXPECT_EQ(a.x_m, b.x_m);
  EXPECT_EQ(a.points_in, b.points_in);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.fitness_m, b.fitness_m);
  EXPECT_EQ(a.weak_directions, b.weak_directions);
  EXPECT_EQ(std::isnan(a.motion_information), std::isnan(b.motion_information));
  EXPECT_EQ(a.ms_total, b.ms_total);
}

}  // namespace

TEST(FramesCsv, RoundTripAndReasonsLoseOnlyTheirCommas) {
  const std::string p = freshDir("frames") + "/frames.csv";
  std::vector<FrameRow> rows = {frame(0), frame(1), frame(2)};
  writeFramesCsv(p, rows);
  const auto back = readFramesCsv(p);
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) expectSame(back[i], rows[i]);
  EXPECT_EQ(back[1].reason, "too few points: 10; wanted 100");
  EXPECT_EQ(back[0].reason, "");
  EXPECT_EQ(readText(p).substr(0, 22), "index,stamp_s,status,p");
}

TEST(FramesCsv, ColumnsInAnotherOrderWithAnExtraOneReadTheSame) {
  const std::string p = freshDir("frames-reordered") + "/frames.csv";
  std::vector<FrameRow> rows = {frame(0), frame(1), frame(2)};
  writeFramesCsv(p, rows);
  reorder(p, {"reason", "ms_total", "keyframe", "status", "inliers", "index", "z_m", "y_m", "x_m", "stamp_s",
              "point_times", "deskewed", "points_in", "points_registered", "iterations", "fitness_m", "threshold_m",
              "weak_directions", "motion_information", "ms_preprocess", "ms_register", "ms_map"});
  EXPECT_EQ(readText(p).substr(0, 16), "reason,ms_total,");
  const auto back = readFramesCsv(p);
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) expectSame(back[i], rows[i]);
}

TEST(FramesCsv, AMissingColumnOrABadCellFailsNamingFileAndColumn) {
  const std::string p = freshDir("frames-missing") + "/frames.csv";
  writeFramesCsv(p, {frame(0)});
  reorder(p, {"index", "stamp_s", "status", "point_times", "deskewed", "x_m", "y_m", "z_m", "points_in",
              "points_registered", "iterations", "inliers", "fitness_m", "threshold_m", "weak_directions",
              "motion_information", "ms_preprocess", "ms_register", "ms_map", "ms_total", "reason"});  // no keyframe
  const std::string e = thrown([&] { readFramesCsv(p); });
  EXPECT_EQ(e, p + ": no column 'keyframe' in the header line");
  writeText(p, framesCsvHeader() + "0,12.5,ok,sensor,1,1,abc,0,0,1,1,1,1,0,0,0,0,0,0,0,0,\n");
  EXPECT_EQ(thrown([&] { readFramesCsv(p); }), p + ":2: column 'x_m' is not a number: 'abc'");
  EXPECT_NE(thrown([&] { readFramesCsv(p + ".nope"); }).find("frames.csv.nope: cannot be read"), std::string::npos);
}

TEST(ObjectsCsv, ObjectsTracksAndEndedTracksRoundTrip) {
  const std::string d = freshDir("objects");
  ObjectRow o;
  o.frame = 4, o.stamp_s = 100.25, o.object = 2, o.box.centre_m = {12.345, -3.5}, o.box.yaw_rad = 0.7854, o.box.length_m = 4.5;
  o.box.width_m = 1.8, o.box.z_min_m = -1.9, o.box.z_max_m = -0.4, o.points = 310, o.track_id = 7;
  writeText(d + "/objects.csv", objectsCsvHeader() + objectsCsvRow(o));
  const auto ob = readObjectsCsv(d + "/objects.csv");
  ASSERT_EQ(ob.size(), 1u);
  EXPECT_EQ(ob[0].object, 2u);
  EXPECT_EQ(ob[0].box.centre_m, Eigen::Vector2d(12.345, -3.5));
  EXPECT_EQ(ob[0].box.yaw_rad, 0.7854);
  EXPECT_EQ(ob[0].box.length_m, 4.5);
  EXPECT_EQ(ob[0].box.width_m, 1.8);
  EXPECT_EQ(ob[0].box.z_min_m, -1.9);
  EXPECT_EQ(ob[0].box.z_max_m, -0.4);
  EXPECT_EQ(ob[0].track_id, 7);
  EXPECT_EQ(ob[0].points, 310u);
  TrackRow t;
  t.frame = 4, t.stamp_s = 100.25, t.track_id = 7, t.box.centre_m = {1, 2}, t.vx = 8, t.vy = -1, t.speed_mps = 8.062;
  t.box.yaw_rad = -0.1244, t.box.length_m = 4.5, t.box.width_m = 1.8, t.moving = true, t.hits = 9, t.misses = 1, t.age_s = 0.75;
  writeText(d + "/tracks.csv", tracksCsvHeader() + tracksCsvRow(t));
  const auto tr = readTracksCsv(d + "/tracks.csv");
  ASSERT_EQ(tr.size(), 1u);
  EXPECT_EQ(tr[0].vx, 8);
  EXPECT_EQ(tr[0].box.centre_m, Eigen::Vector2d(1, 2));
  EXPECT_EQ(tr[0].box.yaw_rad, -0.1244);
  EXPECT_EQ(tr[0].box.length_m, 4.5);
  EXPECT_TRUE(tr[0].moving);
  EXPECT_EQ(tr[0].misses, 1);
  EXPECT_EQ(tr[0].age_s, 0.75);
  EndedTrackRow e;
  e.track_id = 7, e.t_birth = 99.5, e.t_end = 101, e.hits = 12, e.confirmed = true, e.reason = "missed";
  writeText(d + "/tracks_ended.csv", tracksEndedCsvHeader() + tracksEndedCsvRow(e));
  const auto en = readTracksEndedCsv(d + "/tracks_ended.csv");
  ASSERT_EQ(en.size(), 1u);
  EXPECT_EQ(en[0].reason, "missed");
  EXPECT_TRUE(en[0].confirmed);
  EXPECT_FALSE(en[0].moving);
  writeText(d + "/tracks.csv", "frame,stamp_s,track_id,y\n0,1,2,3\n");
  EXPECT_EQ(thrown([&] { readTracksCsv(d + "/tracks.csv"); }), d + "/tracks.csv: no column 'x' in the header line");
}

TEST(LocalizationCsv, RoundTrip) {
  const std::string p = freshDir("localization") + "/localization.csv";
  LocalizationRow a, b;
  a.frame = 0, a.stamp_s = 12.5, a.status = "relocalized", a.confidence = 0.8125, a.keyframe = 31;
  b.frame = 1, b.stamp_s = 12.6, b.status = "lost", b.reason = "no overlap, 0.1 < 0.3";
  writeLocalizationCsv(p, {a, b});
  EXPECT_EQ(readText(p), "frame,stamp_s,status,confidence,keyframe,weak_directions,reason\n"
                         "0,12.500000,relocalized,0.812500,31,0,\n1,12.600000,lost,0.000000,0,0,no overlap; 0.1 < 0.3\n");
  const auto r = readLocalizationCsv(p);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].keyframe, 31u);
  EXPECT_EQ(r[0].confidence, 0.8125);
  EXPECT_EQ(r[1].status, "lost");
}

TEST(Summary, TypedViewRoundTripAndAMissingKeyNamesTheFile) {
  MapSummary s;
  s.frames = 3, s.keyframes = 2, s.frames_by_status = {{"ok", 2}, {"skipped", 1}}, s.ms_per_frame_p95 = 31.5;
  s.loops_accepted.push_back({2, 0, 1, 0, 0.05, 0.8, 0.4, ""});
  s.complete = true, s.warnings = {"w"}, s.input = "x.pcap";
  s.json = {{"extra", 1}};
  const std::string d = freshDir("summary");
  writeSummaryJson(d + "/summary.json", mapSummaryJson(s));
  const auto j = readSummaryJson(d + "/summary.json");
  const MapSummary r = mapSummaryFromJson(j, d + "/summary.json");
  EXPECT_EQ(r.frames, 3u);
  EXPECT_EQ(r.byStatus("skipped"), 1);
  EXPECT_EQ(r.byStatus("degenerate"), 0);
  EXPECT_EQ(r.loop_closures, std::optional<size_t>(1));
  ASSERT_EQ(r.loops_accepted.size(), 1u);
  EXPECT_EQ(r.loops_accepted[0].query_frame, 2u);
  EXPECT_EQ(r.ms_per_frame_p95, 31.5);
  EXPECT_EQ(r.warnings, std::vector<std::string>{"w"});
  EXPECT_EQ(r.json["extra"], 1);
  auto bad = j;
  bad.erase("frames_by_status");
  EXPECT_EQ(thrown([&] { mapSummaryFromJson(bad, "S"); }), "S: no key 'frames_by_status'");
  bad = j;
  bad["frames"] = "many";
  EXPECT_NE(thrown([&] { mapSummaryFromJson(bad, "S"); }).find("S: key 'frames': "), std::string::npos);
}

TEST(Boundaries, LinesWithAndWithoutAPose) {
  const std::string d = freshDir("boundaries");
  nlohmann::json full = {{"index", 3}, {"stamp_s", 5.5}, {"status", "ok"},
                         {"T_map_lidar", {1, 0, 0, 10, 0, 1, 0, 20, 0, 0, 1, 0, 0, 0, 0, 1}},
                         {"left", {{"found", true}, {"confidence", 0.9}, {"polyline_map", {{1, 2, 0.5}, {3, 4, 0.5}}}}},
                         {"right", {{"found", false}, {"reason", "no curb"}, {"polyline_map", nlohmann::json::array()}}},
                         {"free_space", {{1, 1}, {2, 1}, {2, 2}}}};
  writeText(d + "/boundaries.jsonl", noPoseLine(5.4, "odometry: not converged") + full.dump() + "\n");
  const auto r = readBoundariesJsonl(d + "/boundaries.jsonl");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_FALSE(r[0].has_pose);
  EXPECT_EQ(r[0].reason, "odometry: not converged");
  EXPECT_TRUE(r[1].has_pose);
  EXPECT_EQ(r[1].T_map_lidar.translation(), Eigen::Vector3d(10, 20, 0));
  ASSERT_EQ(r[1].left.polyline_map.size(), 2u);
  EXPECT_EQ(r[1].left.polyline_map[1], Eigen::Vector3d(3, 4, 0.5));
  EXPECT_EQ(r[1].right.reason, "no curb");
  EXPECT_EQ(r[1].free_space.size(), 3u);
  full.erase("T_map_lidar");
  writeText(d + "/boundaries.jsonl", full.dump() + "\n");
  EXPECT_NE(thrown([&] { readBoundariesJsonl(d + "/boundaries.jsonl"); }).find(d + "/boundaries.jsonl:1: "),
            std::string::npos);
}
