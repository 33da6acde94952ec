// LiveObservations: what a live view indexes. Oracles: the observations posted (their stamps,
// labels, classes and serialized sizes), posted from another thread as the grabber does.
#include <gtest/gtest.h>

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>

#include <thread>

#include "roadslam/sources/live_observations.h"

namespace {
using roadslam::sources::LiveObservations;

std::shared_ptr<mrpt::obs::CObservation> odometry(double t, const std::string& label = "CAN_ODOMETRY") {
  auto o = std::make_shared<mrpt::obs::CObservationOdometry>();
  o->timestamp = mrpt::Clock::fromDouble(t);
  o->sensorLabel = label;
  o->odometry = mrpt::poses::CPose2D(t, 0, 0);
  return o;
}
}  // namespace

TEST(LiveObservations, PostedFromAnotherThreadVisibleAfterPoll) {
  LiveObservations live("test");
  std::thread poster([&] {
    for (int i = 0; i < 500; ++i) live.post(odometry(1000.0 + 0.01 * i));
  });
  poster.join();
  EXPECT_EQ(live.size(), 0u) << "nothing is visible before poll()";
  EXPECT_EQ(live.posted(), 500u);
  EXPECT_EQ(live.poll(), 0u);
  ASSERT_EQ(live.size(), 500u);
  EXPECT_EQ(live.poll(), 500u) << "nothing new";
  EXPECT_DOUBLE_EQ(live.firstStamp(), 1000.0);
  EXPECT_NEAR(live.lastStamp(), 1004.99, 1e-6);
  EXPECT_EQ(live.className(7), "CObservationOdometry");
  EXPECT_EQ(live.label(7), "CAN_ODOMETRY");
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf).WriteObject(odometry(1000.07).get());
  EXPECT_EQ(live.entry(7).size, buf.getTotalBytesCount()) << "the size a rawlog record of it has";
  const auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(live.load(7));
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->odometry.x(), 1000.07, 1e-9);
}

TEST(LiveObservations, TimeLookupsKeepALateArrivalInOrder) {
  LiveObservations live("test");
  for (double t : {10.0, 10.1, 10.2, 10.4}) live.post(odometry(t));
  live.post(odometry(10.3, "LATE"));  // the writer's reorder window let it through late
  auto gps = std::make_shared<mrpt::obs::CObservationGPS>();  // no stamp: listed, not on the timeline
  gps->timestamp = INVALID_TIMESTAMP;
  live.post(gps);
  live.poll();
  ASSERT_EQ(live.size(), 6u);
  EXPECT_EQ(*live.findAtTime(10.35), 4u) << "the late one, by time";
  EXPECT_EQ(*live.findAtTime(10.45), 3u);
  EXPECT_EQ(*live.findAtTime(0.0), 0u) << "before the first: the first";
  EXPECT_EQ(live.findInRange(10.15, 10.45), (std::vector<std::size_t>{2, 4, 3}));
  EXPECT_TRUE(std::isnan(live.entry(5).stamp_s));
  EXPECT_DOUBLE_EQ(live.lastStamp(), 10.4);
}

TEST(LiveObservations, PayloadsOlderThanTheKeepWindowAreFreedAndSaySo) {
  LiveObservations live("live view", 2.0);
  for (int i = 0; i <= 50; ++i) live.post(odometry(100.0 + 0.1 * i));  // 5 s
  live.poll();
  ASSERT_EQ(live.size(), 51u) << "every entry stays for the timeline";
  EXPECT_NO_THROW(live.load(50));
  EXPECT_NO_THROW(live.load(30)) << "103.0 s: 2 s behind the newest (105.0 s)";
  try {
    live.load(10);
    FAIL() << "a payload out of the window was returned";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("live view: observation 10 is no longer held (a live view keeps the last 2 s)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(live.load(51), std::runtime_error);
}
