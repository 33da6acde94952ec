#include "roadside.h"

#include <algorithm>
#include <cmath>

namespace roadslam::sim {

namespace {
constexpr double kBucket = 10.0;  // [m]

/// Frame of a road at arc length s: point, heading, left normal.
struct Station {
  Vec2 p;
  double h = 0;
  Vec2 left;
  Vec2 at(double along, double side) const {  // side > 0 to the left [m]
    return {p.x + along * std::cos(h) + side * left.x, p.y + along * std::sin(h) + side * left.y};
  }
};
Station station(const Road& r, double s) {
  Station st;
  pointAtArcLength(r, s, st.p, st.h);
  st.left = {-std::sin(st.h), std::cos(st.h)};
  return st;
}

/// Prism at (c, yaw) whose top follows the ground's slope at c, \p top_above_ground [m] above it.
Prism groundPrism(const World& w, Vec2 c, double yaw, double hu, double hv, double bottom_below,
                  double top_above_ground, Material m) {
  Prism q;
  q.cx = c.x;
  q.cy = c.y;
  q.yaw = yaw;
  q.hu = hu;
  q.hv = hv;
  const double g = w.ground.height(c.x, c.y);
  const Vec2 grad = w.ground.gradient(c.x, c.y);
  q.su = grad.x * std::cos(yaw) + grad.y * std::sin(yaw);
  q.sv = -grad.x * std::sin(yaw) + grad.y * std::cos(yaw);
  q.zt = g + top_above_ground;
  q.zb = g - bottom_below;
  q.material = m;
  return q;
}

bool inTunnel(const WorldParams& p, int road, double s, double margin) {
  return p.tunnel_length_m > 0 && road == 0 && s > p.tunnel_start_m - margin &&
         s < p.tunnel_start_m + p.tunnel_length_m + margin;
}
}  // namespace

RoadIndex::RoadIndex(const std::vector<Road>& roads) : roads_(roads) {
  double x1 = -1e300, y1 = -1e300;
  x0_ = y0_ = 1e300;
  for (const Road& r : roads)
    for (const Vec2& q : r.centerline) {
      x0_ = std::min(x0_, q.x);
      y0_ = std::min(y0_, q.y);
      x1 = std::max(x1, q.x);
      y1 = std::max(y1, q.y);
    }
  nx_ = static_cast<int>((x1 - x0_) / kBucket) + 1;
  ny_ = static_cast<int>((y1 - y0_) / kBucket) + 1;
  buckets_.resize(static_cast<std::size_t>(nx_) * ny_);
  for (std::size_t i = 0; i < roads.size(); ++i)
    for (const Vec2& q : roads[i].centerline) {
      const int ix = static_cast<int>((q.x - x0_) / kBucket), iy = static_cast<int>((q.y - y0_) / kBucket);
      buckets_[static_cast<std::size_t>(iy) * nx_ + ix].push_back({q.x, q.y, static_cast<int>(i)});
    }
}

double RoadIndex::clearance(double x, double y, int exclude) const {
  double best = 1e9;
  const int cx = static_cast<int>(std::floor((x - x0_) / kBucket));
  const int cy = static_cast<int>(std::floor((y - y0_) / kBucket));
  for (int iy = std::max(0, cy - 3); iy <= std::min(ny_ - 1, cy + 3); ++iy)
    for (int ix = std::max(0, cx - 3); ix <= std::min(nx_ - 1, cx + 3); ++ix)
      for (const Sample& s : buckets_[static_cast<std::size_t>(iy) * nx_ + ix]) {
        if (s.road == exclude) continue;
        const double d = std::hypot(s.x - x, s.y - y) - roads_[static_cast<std::size_t>(s.road)].half_width_m;
        best = std::min(best, d);
      }
  return best;
}

void addSidewalks(const WorldParams& p, const RoadIndex& index, World& world) {
  if (p.sidewalk_width_m <= 0) return;
  for (std::size_t ri = 0; ri < world.roads.size(); ++ri) {
    Road& r = world.roads[ri];
    const double len = roadLength(r), hw = r.half_width_m, sw = p.sidewalk_width_m;
    for (int side : {+1, -1}) {
      auto& curbs = side > 0 ? r.left_curbs : r.right_curbs;
      std::vector<Vec2> cur;
      auto flush = [&] {
        if (cur.size() >= 2) curbs.push_back(cur);
        cur.clear();
      };
      for (double s = 0, piece = 4.0; len - s > 0.25; s += piece) {
        // Straight pieces (<= 4 m) tangent to the curb line at their middle. On a curve turning by
        // dh over a piece whose curb length is Lc, the curb chord (the ground-truth polyline) and
        // the piece's face each stand off the arc by about Lc dh / 8: halve the piece until the sum
        // is <= 2 cm, so the curb face stays within ~2 cm of the ground-truth polyline.
        const Station a = station(r, s);
        piece = std::min(4.0, len - s);
        while (piece > 0.3) {
          const double dh = std::abs(std::remainder(station(r, s + piece).h - a.h, 2 * M_PI));
          if ((piece + hw * dh) * dh / 4 <= 0.02) break;
          piece *= 0.5;
        }
        const Station mid = station(r, s + 0.5 * piece);
        const Vec2 c = mid.at(0, side * (hw + 0.5 * sw));
        if (index.clearance(c.x, c.y, static_cast<int>(ri)) < 0.5 * sw - 0.3) {
          flush();
          continue;
        }
        world.prisms.push_back(groundPrism(world, c, mid.h, 0.5 * piece + 0.05, 0.5 * sw, 1.0,
                                           p.curb_height_m, Material::Concrete));
        if (cur.empty()) cur.push_back(a.at(0, side * hw));
        cur.push_back(station(r, s + piece).at(0, side * hw));
      }
      flush();
    }
  }
}

void addTunnel(const WorldParams& p, World& world) {
  if (p.tunnel_length_m <= 0 || world.roads.empty()) return;
  const Road& r = world.roads[0];
  const double wall = r.half_width_m + std::max(0.0, p.sidewalk_width_m) + 0.25;
  for (double s = p.tunnel_start_m; s < p.tunnel_start_m + p.tunnel_length_m; s += 4.0) {
    const Station st = station(r, s + 2.0);
    for (int side : {+1, -1})
      world.prisms.push_back(groundPrism(world, st.at(0, side * wall), st.h, 2.05, 0.25, 1.0,
                                         p.tunnel_height_m + 0.5, Material::TunnelWall));
    Prism ceiling = groundPrism(world, st.p, st.h, 2.05, wall + 0.25, 0, p.tunnel_height_m + 0.5,
                                Material::TunnelWall);
    ceiling.zb = ceiling.zt - 0.5;
    world.prisms.push_back(ceiling);
  }
}

namespace {
void addBuilding(const WorldParams& p, const Station& st, int side, double w, double front,
                 Rng& rng, World& world) {
  const double depth = rng.uniform(8, 15), H = rng.uniform(p.building_min_height_m, p.building_max_height_m);
  auto at = [&](double along, double off) { return st.at(along, side * off); };
  const double yaw = st.h;
  // Facade (after ground-floor shops): floors every 3 m; a 0.4 m deep recess between the
  // spandrel bands and the end pillars, glass panes in the recess (lost returns).
  world.prisms.push_back(groundPrism(world, at(0, front + 0.4 + depth / 2), yaw, w / 2, depth / 2,
                                     2.0, H, Material::Facade));
  for (double z = 0; z + 3.0 <= H; z += 3.0) {
    Prism band = groundPrism(world, at(0, front + 0.2), yaw, w / 2, 0.2, 0, z + 0.9, Material::Facade);
    band.zb = band.zt - 0.9 - (z == 0 ? 2.0 : 0.0);
    world.prisms.push_back(band);
    Prism glass = groundPrism(world, at(0, front + 0.375), yaw, 0.2 * w, 0.025, 0, z + 2.7, Material::Glass);
    glass.zb = glass.zt - 1.8;
    world.prisms.push_back(glass);
  }
  for (double e : {-1.0, 1.0})
    world.prisms.push_back(groundPrism(world, at(e * (w / 2 - 0.3), front + 0.2), yaw, 0.3, 0.2,
                                       2.0, H, Material::Facade));
}

/// A hedge along the back of the sidewalk from arc length \p s over \p w [m]: overlapping porous
/// bushes (spheres of diameter ~hedge_height_m) every 0.7 m.
void addHedge(const WorldParams& p, const Road& r, double s, double w, int side, const RoadIndex& index,
              Rng& rng, World& world) {
  const double sw = std::max(0.0, p.sidewalk_width_m), off = r.half_width_m + sw + 0.5;
  for (double a = s; a < s + w; a += 0.7) {
    const Station st = station(r, a);
    const Vec2 c = st.at(0, side * off);
    const double rad = 0.5 * p.hedge_height_m * rng.uniform(0.85, 1.15);
    if (index.clearance(c.x, c.y) < sw + 0.5 - rad) continue;
    world.spheres.push_back({{c.x, c.y, world.ground.height(c.x, c.y) + 0.9 * rad}, rad, Material::Foliage});
  }
}

void addParkedCar(const Station& st, int side, double off, double angle, Rng& rng, World& world) {
  const double yaw = st.h + angle + rng.uniform(-0.04, 0.04);
  const Material m = rng.uniform() < 0.3 ? Material::DarkPaint : Material::CarPaint;
  const Vec2 c = st.at(rng.uniform(-0.3, 0.3), side * off);
  Prism body = groundPrism(world, c, yaw, 2.2, 0.9, 0, 1.0, m);
  body.zb = body.zt - 0.75;
  Prism cabin = groundPrism(world, c, yaw, 1.2, 0.8, 0, 1.5, m);
  cabin.zb = cabin.zt - 0.5;
  world.prisms.push_back(body);
  world.prisms.push_back(cabin);
}
}  // namespace

void addRoadsideObjects(const WorldParams& p, const RoadIndex& index, Rng& rng, World& world) {
  for (std::size_t ri = 0; ri < world.roads.size(); ++ri) {
    const Road r = world.roads[ri];
    const int ir = static_cast<int>(ri);
    const double len = roadLength(r), hw = r.half_width_m, sw = std::max(0.0, p.sidewalk_width_m);
    for (int side : {+1, -1}) {
      const double front = hw + sw + p.building_setback_m;
      for (double s = 0, w = rng.uniform(8, 25); s + w < len; s += w + rng.uniform(0, 4), w = rng.uniform(8, 25)) {
        if (rng.uniform() >= p.building_density || inTunnel(p, ir, s + w / 2, 20)) {
          if (p.hedge_prob > 0 && !inTunnel(p, ir, s + w / 2, 20) && rng.uniform() < p.hedge_prob)
            addHedge(p, r, s, w, side, index, rng, world);
          continue;
        }
        const Station st = station(r, s + w / 2);
        bool ok = true;
        for (double a : {-w / 2, 0.0, w / 2})
          for (double o : {front, front + 16})
            ok = ok && index.clearance(st.at(a, side * o).x, st.at(a, side * o).y) > sw + p.building_setback_m - 0.6;
        if (ok) addBuilding(p, st, side, w, front, rng, world);
      }
      for (double s = rng.uniform(0, p.pole_spacing_m); p.pole_spacing_m > 0 && s < len;
           s += p.pole_spacing_m * rng.uniform(0.7, 1.3)) {
        const Station st = station(r, s);
        const Vec2 c = st.at(0, side * (hw + 0.5));
        if (inTunnel(p, ir, s, 5) || index.clearance(c.x, c.y) < 0.3) continue;
        const double g = world.ground.height(c.x, c.y);
        world.cylinders.push_back({c.x, c.y, rng.uniform(0.08, 0.15), g - 0.5, g + rng.uniform(5, 9), Material::Metal});
        if (rng.uniform() < 0.3)
          world.prisms.push_back(groundPrism(world, c, st.h, 0.03, 0.35, -2.2, 2.9, Material::Metal));
      }
      for (double s = rng.uniform(0, p.tree_spacing_m); p.tree_spacing_m > 0 && s < len;
           s += p.tree_spacing_m * rng.uniform(0.6, 1.4)) {
        const Station st = station(r, s);
        const Vec2 c = st.at(0, side * (sw > 1.6 ? hw + sw - 0.8 : hw + sw + 1.5));
        if (inTunnel(p, ir, s, 10) || index.clearance(c.x, c.y) < 0.5) continue;
        const double g = world.ground.height(c.x, c.y), trunk = rng.uniform(2.5, 3.5), cr = rng.uniform(1.5, 3.0);
        world.cylinders.push_back({c.x, c.y, rng.uniform(0.15, 0.25), g - 0.5, g + trunk + 0.5 * cr, Material::Bark});
        world.spheres.push_back({{c.x, c.y, g + trunk + 0.7 * cr}, cr, Material::Foliage});
        // Irregular canopies: lobes around the crown, each porous with its own random depth.
        for (int l = 0; l < p.canopy_lobes; ++l) {
          const double dir = rng.uniform(0, 2 * M_PI), lr = cr * rng.uniform(0.4, 0.7);
          world.spheres.push_back({{c.x + 0.7 * cr * std::cos(dir), c.y + 0.7 * cr * std::sin(dir),
                                    g + trunk + 0.7 * cr + cr * rng.uniform(-0.3, 0.5)},
                                   lr, Material::Foliage});
        }
      }
      if (p.parking_width_m < 1.5) continue;
      // Parallel parking: 6.5 m slots; angled (perpendicular) parking: 2.7 m slots.
      const double angle = p.parking_angle_deg * M_PI / 180.0;
      const double slot = p.parking_angle_deg > 45 ? 2.7 : 6.5;
      for (double s = 0.5 * slot; s < len - 0.5 * slot; s += slot) {
        if (rng.uniform() >= p.parked_car_prob || inTunnel(p, ir, s, 10)) continue;
        const Station st = station(r, s);
        const Vec2 c = st.at(0, side * (hw - 0.5 * p.parking_width_m));
        if (index.clearance(c.x, c.y, ir) < 1.5) continue;
        addParkedCar(st, side, hw - 0.5 * p.parking_width_m, angle, rng, world);
      }
    }
  }
}

void addMovingCars(const WorldParams& p, Rng& rng, World& world) {
  for (int i = 0; i < p.moving_cars && !world.roads.empty(); ++i) {
    MovingCar c;
    c.road = i % static_cast<int>(world.roads.size());
    c.s0_m = rng.uniform(0, roadLength(world.roads[static_cast<std::size_t>(c.road)]));
    const double v = p.moving_car_speed_mps() * rng.uniform(0.7, 1.3);
    const bool same_dir = p.lanes_per_side >= 2 && rng.uniform() < 0.5;
    // The vehicle drives in the innermost right lane: same-direction traffic uses the next lane.
    c.speed_mps = same_dir ? v : -v;
    // The grid's serpentine drives odd streets against their centreline: keep traffic oncoming.
    if (p.layout == "grid" && c.road < p.streets && c.road % 2 == 1) c.speed_mps = -c.speed_mps;
    c.lateral_m = p.lane_width_m * (same_dir ? 1.5 : 0.5 + std::floor(rng.uniform(0, p.lanes_per_side)));
    c.length_m = rng.uniform(4.0, 5.0);
    c.width_m = rng.uniform(1.7, 1.9);
    c.height_m = rng.uniform(1.4, 1.7);
    c.material = rng.uniform() < 0.25 ? Material::DarkPaint : Material::CarPaint;
    world.cars.push_back(c);
  }
}

}  // namespace roadslam::sim
