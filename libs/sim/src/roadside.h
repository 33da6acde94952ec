#pragma once
// Private to libs/sim: placement of sidewalks, the tunnel and roadside objects.
#include <vector>

#include "roadslam/sim/world.h"
#include "roadslam/sim/world_builder.h"

namespace roadslam::sim {

/// Distance queries to road carriageways over 10 m buckets of centreline samples.
class RoadIndex {
 public:
  explicit RoadIndex(const std::vector<Road>& roads);
  /// Distance from (x, y) to the nearest carriageway edge, negative inside a carriageway [m];
  /// roads with index \p exclude are ignored; 1e9 when no road is within 30 m.
  double clearance(double x, double y, int exclude = -1) const;

 private:
  struct Sample {
    double x, y;
    int road;
  };
  const std::vector<Road>& roads_;
  double x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<Sample>> buckets_;
};

void addSidewalks(const WorldParams& p, const RoadIndex& index, World& world);
void addTunnel(const WorldParams& p, World& world);
void addRoadsideObjects(const WorldParams& p, const RoadIndex& index, Rng& rng, World& world);
void addMovingCars(const WorldParams& p, Rng& rng, World& world);

}  // namespace roadslam::sim
