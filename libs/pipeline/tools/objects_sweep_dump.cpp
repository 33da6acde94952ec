// Dumps one sweep's points with what the objects stage made of them, for diagnosing a missed car:
//   objects_sweep_dump CONFIG.ini RECORDING FRAME [X Y RADIUS]
// One CSV row per point (x, y, z in the lidar frame, ring, ground label, height above the local
// ground as the objects take it (objects::objectGroundLabels), object index or -1); with X Y RADIUS
// only the points within RADIUS (x-y, lidar frame) of (X, Y). The sweep is not deskewed (the
// pipeline deskews it by the odometry's motion first; at 10 Hz a point moves by at most the car's
// speed x 0.1 s).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "roadslam/common/config.h"
#include "roadslam/objects/params.h"
#include "roadslam/objects/segmentation.h"
#include "roadslam/sources/scan_source.h"

using namespace roadslam;

namespace {

/// \p s as a number, the whole of it; throws naming \p what.
double number(const char* s, const char* what) {
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || *end != '\0' || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " '" + s + "' is not a number");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 7) {
    std::fprintf(stderr, "usage: objects_sweep_dump CONFIG.ini RECORDING FRAME [X Y RADIUS]\n");
    return 2;
  }
  try {
    const auto cfg = loadIniFile(argv[1]);
    objects::ClusterParams p;
    p.loadFromConfigFile(*cfg);
    const double frame_d = number(argv[3], "FRAME");
    if (frame_d < 0 || frame_d != std::floor(frame_d)) throw std::invalid_argument(std::string("FRAME '") + argv[3] + "' is not a sweep index");
    const long frame = static_cast<long>(frame_d);
    const bool sel = argc == 7;
    const double qx = sel ? number(argv[4], "X") : 0, qy = sel ? number(argv[5], "Y") : 0, qr = sel ? number(argv[6], "RADIUS") : 0;
    auto src = sources::openScanSource(argv[2], *cfg);
    for (long k = 0;; ++k) {
      std::optional<Scan> s = src->next();
      if (!s) {
        std::fprintf(stderr, "%s: %ld sweeps, no frame %ld\n", argv[2], k, frame);
        return 1;
      }
      if (k < frame) continue;
      const auto g = objects::objectGroundLabels(s->points, p);
      const auto objs = objects::segmentObjects(s->points, s->has_rings, g.ground, g.height_above_ground_m, p);
      std::vector<int> obj(s->points.size(), -1);
      for (size_t o = 0; o < objs.size(); ++o) {
        for (uint32_t i : objs[o].indices) obj[i] = static_cast<int>(o);
      }
      std::printf("# stamp_s %.6f, %zu points, %zu objects\nx,y,z,ring,ground,height_m,object\n", s->stamp_s,
                  s->points.size(), objs.size());
      for (size_t i = 0; i < s->points.size(); ++i) {
        const ScanPoint& q = s->points[i];
        if (sel && std::hypot(q.x - qx, q.y - qy) > qr) continue;
        std::printf("%.3f,%.3f,%.3f,%d,%d,%.3f,%d\n", q.x, q.y, q.z, q.ring, g.ground[i], g.height_above_ground_m[i], obj[i]);
      }
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "objects_sweep_dump: %s\n", e.what());
    return 1;
  }
}
