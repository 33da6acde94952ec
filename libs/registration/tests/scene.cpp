#include "scene.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace roadslam::registration::test {
namespace {

struct Sampler {
  std::mt19937 rng;
  double density, noise;
  PointCloud pts;
  double u(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  Eigen::Vector3d jitter() {
    std::normal_distribution<double> n(0.0, noise);
    return noise > 0 ? Eigen::Vector3d(n(rng), n(rng), n(rng)) : Eigen::Vector3d::Zero();
  }
  // Rectangle o + s*a + t*b, s,t in [0,1].
  void rect(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const int n = static_cast<int>(density * a.cross(b).norm());
    for (int i = 0; i < n; ++i) pts.push_back(o + u(0, 1) * a + u(0, 1) * b + jitter());
  }
  void box(const Eigen::Vector3d& c, const Eigen::Vector3d& size) {
    const Eigen::Vector3d o = c - 0.5 * Eigen::Vector3d(size.x(), size.y(), 0);
    const Eigen::Vector3d X(size.x(), 0, 0), Y(0, size.y(), 0), Z(0, 0, size.z());
    rect(o, X, Z);
    rect(o + Y, X, Z);
    rect(o, Y, Z);
    rect(o + X, Y, Z);
    rect(o + Z, X, Y);
  }
  void cylinder(const Eigen::Vector3d& base, double r, double h) {
    const int n = static_cast<int>(density * 2 * M_PI * r * h);
    for (int i = 0; i < n; ++i) {
      const double a = u(0, 2 * M_PI);
      pts.push_back(base + Eigen::Vector3d(r * std::cos(a), r * std::sin(a), u(0, h)) + jitter());
    }
  }
};

}  // namespace

PointCloud structuredScene(double density, double noise, uint32_t seed) {
  Sampler s{std::mt19937(seed), density, noise, {}};
  s.rect({-20, -20, 0}, {40, 0, 0}, {0, 40, 0});
  s.box({6, 4, 0}, {3, 2, 2.5});
  s.box({-8, 6, 0}, {4, 4, 3});
  s.box({10, -7, 0}, {2, 5, 1.5});
  s.box({-5, -9, 0}, {6, 1.5, 4});
  s.cylinder({3, -3, 0}, 0.3, 4);
  s.cylinder({-3, 2, 0}, 0.5, 3);
  s.cylinder({14, 3, 0}, 1.0, 2);
  s.rect({20, -20, 0}, {0, 40, 0}, {0, 0, 6});
  return s.pts;
}

PointCloud corridorScene(double density, double noise, uint32_t seed) {
  Sampler s{std::mt19937(seed), density, noise, {}};
  s.rect({-30, -2, 0}, {60, 0, 0}, {0, 4, 0});
  s.rect({-30, -2, 0}, {60, 0, 0}, {0, 0, 3});
  s.rect({-30, 2, 0}, {60, 0, 0}, {0, 0, 3});
  return s.pts;
}

PointCloud transformed(const PointCloud& pts, const Eigen::Isometry3d& T) {
  PointCloud out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back(T * p);
  return out;
}

}  // namespace roadslam::registration::test
