#include "roadslam/runfolder/objects_csv.h"

#include "roadslam/runfolder/csv.h"

namespace roadslam::runfolder {
namespace {

/// The box of the row \p c is on: centre in columns \p x and \p y, length axis in \p yaw, and the
/// extents and heights in the columns both files name alike.
OrientedBox boxOf(const CsvReader& c, const char* x, const char* y, const char* yaw) {
  OrientedBox b;
  b.centre_m = {c.number(x), c.number(y)}, b.yaw_rad = c.number(yaw);
  b.length_m = c.number("length_m"), b.width_m = c.number("width_m");
  b.z_min_m = c.number("z_min"), b.z_max_m = c.number("z_max");
  return b;
}

}  // namespace

std::string objectsCsvHeader() { return "frame,stamp_s,object,cx,cy,yaw_rad,length_m,width_m,z_min,z_max,points,track_id\n"; }

std::string objectsCsvRow(const ObjectRow& r) {
  const OrientedBox& b = r.box;
  return format("%zu,%.6f,%zu,%.3f,%.3f,%.4f,%.3f,%.3f,%.3f,%.3f,%zu,%d\n", r.frame, r.stamp_s, r.object, b.centre_m.x(),
                b.centre_m.y(), b.yaw_rad, b.length_m, b.width_m, b.z_min_m, b.z_max_m, r.points, r.track_id);
}

std::string tracksCsvHeader() {
  return "frame,stamp_s,track_id,x,y,vx,vy,speed_mps,heading_rad,length_m,width_m,z_min,z_max,moving,hits,misses,age_s\n";
}

std::string tracksCsvRow(const TrackRow& r) {
  const OrientedBox& b = r.box;
  return format("%zu,%.6f,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.4f,%.3f,%.3f,%.3f,%.3f,%d,%d,%d,%.2f\n", r.frame, r.stamp_s,
                r.track_id, b.centre_m.x(), b.centre_m.y(), r.vx, r.vy, r.speed_mps, b.yaw_rad, b.length_m, b.width_m,
                b.z_min_m, b.z_max_m, r.moving ? 1 : 0, r.hits, r.misses, r.age_s);
}

std::string tracksEndedCsvHeader() { return "track_id,t_birth,t_end,hits,confirmed,moving,reason\n"; }

std::string tracksEndedCsvRow(const EndedTrackRow& r) {
  return format("%d,%.6f,%.6f,%d,%d,%d,", r.track_id, r.t_birth, r.t_end, r.hits, r.confirmed ? 1 : 0, r.moving ? 1 : 0) +
         csvText(r.reason) + "\n";
}

std::vector<ObjectRow> readObjectsCsv(const std::string& path) {
  std::vector<ObjectRow> rows;
  for (CsvReader c(path, {"frame", "stamp_s", "object", "cx", "cy", "yaw_rad", "length_m", "width_m", "z_min", "z_max",
                          "points", "track_id"});
       c.next();) {
    ObjectRow r;
    r.frame = static_cast<size_t>(c.integer("frame"));
    r.stamp_s = c.number("stamp_s");
    r.object = static_cast<size_t>(c.integer("object"));
    r.box = boxOf(c, "cx", "cy", "yaw_rad");
    r.points = static_cast<size_t>(c.integer("points"));
    r.track_id = static_cast<int>(c.integer("track_id"));
    rows.push_back(r);
  }
  return rows;
}

std::vector<TrackRow> readTracksCsv(const std::string& path) {
  std::vector<TrackRow> rows;
  for (CsvReader c(path, {"frame", "stamp_s", "track_id", "x", "y", "vx", "vy", "speed_mps", "heading_rad", "length_m",
                          "width_m", "z_min", "z_max", "moving", "hits", "misses", "age_s"});
       c.next();) {
    TrackRow r;
    r.frame = static_cast<size_t>(c.integer("frame"));
    r.stamp_s = c.number("stamp_s");
    r.track_id = static_cast<int>(c.integer("track_id"));
    r.box = boxOf(c, "x", "y", "heading_rad");
    r.vx = c.number("vx"), r.vy = c.number("vy"), r.speed_mps = c.number("speed_mps");
    r.moving = c.flag("moving");
    r.hits = static_cast<int>(c.integer("hits")), r.misses = static_cast<int>(c.integer("misses"));
    r.age_s = c.number("age_s");
    rows.push_back(r);
  }
  return rows;
}

std::vector<EndedTrackRow> readTracksEndedCsv(const std::string& path) {
  std::vector<EndedTrackRow> rows;
  for (CsvReader c(path, {"track_id", "t_birth", "t_end", "hits", "confirmed", "moving", "reason"}); c.next();) {
    EndedTrackRow r;
    r.track_id = static_cast<int>(c.integer("track_id"));
    r.t_birth = c.number("t_birth"), r.t_end = c.number("t_end");
    r.hits = static_cast<int>(c.integer("hits"));
    r.confirmed = c.flag("confirmed"), r.moving = c.flag("moving");
    r.reason = c.text("reason");
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace roadslam::runfolder
