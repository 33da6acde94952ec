// StampedTrajectory::at: linear translation and slerped rotation between the poses around t, the
// poses themselves at their stamps, nothing outside the span or across a gap.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/runfolder/trajectory.h"
#include "test_util.h"

using namespace roadslam::runfolder;

namespace {
Eigen::Isometry3d pose(double x, double y, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << x, y, 0;
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}
double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T(1, 0), T(0, 0)); }

StampedTrajectory threePoses() {
  roadslam::datasets::Trajectory t;
  t.stamps_s = {10.0, 11.0, 13.0};
  t.poses = {pose(0, 0, 0), pose(10, 0, M_PI / 2), pose(10, 20, M_PI / 2)};
  return StampedTrajectory(t);
}
}  // namespace

TEST(StampedTrajectory, AtInterpolatesBetweenAndHitsThePoses) {
  const auto tr = threePoses();
  ASSERT_TRUE(tr.at(11.0));
  EXPECT_TRUE(tr.at(11.0)->isApprox(tr.pose(1)));
  EXPECT_TRUE(tr.at(10.0)->isApprox(tr.pose(0)));
  EXPECT_TRUE(tr.at(13.0)->isApprox(tr.pose(2)));
  const auto q = tr.at(10.25);  // a quarter of the way: 2.5 m and a quarter of the 90 deg turn
  ASSERT_TRUE(q);
  EXPECT_NEAR(q->translation().x(), 2.5, 1e-12);
  EXPECT_NEAR(yawOf(*q), M_PI / 8, 1e-9);
  const auto h = tr.at(12.0);  // half of the 2 s step
  ASSERT_TRUE(h);
  EXPECT_NEAR(h->translation().y(), 10.0, 1e-12);
  EXPECT_NEAR(yawOf(*h), M_PI / 2, 1e-9);
}

TEST(StampedTrajectory, NothingOutsideTheSpanOrAcrossAGap) {
  const auto tr = threePoses();
  EXPECT_FALSE(tr.at(9.999));
  EXPECT_FALSE(tr.at(13.001));
  EXPECT_FALSE(tr.at(std::nan("")));
  EXPECT_FALSE(tr.at(12.0, 1.5));  // the 2 s step is a gap at 1.5 s
  EXPECT_TRUE(tr.at(10.5, 1.5));
  EXPECT_TRUE(tr.at(13.0, 1.5));   // a stamp is always its pose
  EXPECT_FALSE(StampedTrajectory().at(0));
}

TEST(StampedTrajectory, NearestAndStampsThatStepBack) {
  roadslam::datasets::Trajectory t;
  t.stamps_s = {1.0, 2.0, 1.5};  // a recording's clock stepping back: kept in file order
  t.poses = {pose(0, 0, 0), pose(2, 0, 0), pose(1.5, 0, 0)};
  const StampedTrajectory tr(t);
  EXPECT_EQ(tr.pose(2).translation().x(), 1.5);
  EXPECT_EQ(tr.nearest(1.6, 0.2), std::optional<size_t>(2));
  EXPECT_FALSE(tr.nearest(3.0, 0.5));
  EXPECT_NEAR(tr.at(1.75)->translation().x(), 1.75, 1e-12);
  EXPECT_EQ(tr.front(), 1.0);
  EXPECT_EQ(tr.back(), 2.0);
  t.stamps_s.pop_back();
  EXPECT_THROW(StampedTrajectory{t}, std::invalid_argument);
}

TEST(StampedTrajectory, TumRoundTrip) {
  const std::string d = roadslam::runfolder::test::freshDir("trajectory");
  const auto tr = threePoses();
  writeTrajectory(d + "/trajectory.tum", tr);
  const auto back = readTrajectory(d + "/trajectory.tum");
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.stamp(i), tr.stamp(i));
    EXPECT_TRUE(back.pose(i).isApprox(tr.pose(i), 1e-9));
  }
}
