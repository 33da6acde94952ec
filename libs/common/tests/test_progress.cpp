// The progress line as a pure function of the counts and the time so far (progress.h).
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/common/progress.h"

using namespace roadslam;

TEST(Progress, FractionAndEtaAtTheRateSoFar) {
  // 30 % in 12 s: 0.4 s per percent, 70 % left = 28 s.
  const ProgressEstimate e = estimateProgress(3e6, 10e6, 12.0);
  EXPECT_DOUBLE_EQ(e.fraction, 0.3);
  EXPECT_NEAR(e.eta_s, 28.0, 1e-9);
  const ProgressEstimate done = estimateProgress(10e6, 10e6, 40.0);
  EXPECT_DOUBLE_EQ(done.fraction, 1.0);
  EXPECT_DOUBLE_EQ(done.eta_s, 0.0);
  // More than the total (a file that grew while read) is done, not more.
  EXPECT_DOUBLE_EQ(estimateProgress(11, 10, 5).fraction, 1.0);
}

TEST(Progress, UnknownTotalOrNothingDoneHasNoEta) {
  EXPECT_TRUE(std::isnan(estimateProgress(5, 0, 3).fraction));
  EXPECT_TRUE(std::isnan(estimateProgress(5, 0, 3).eta_s));
  EXPECT_DOUBLE_EQ(estimateProgress(0, 100, 3).fraction, 0.0);
  EXPECT_TRUE(std::isnan(estimateProgress(0, 100, 3).eta_s));
}

TEST(Progress, LinesForEachMeasure) {
  EXPECT_EQ(progressLine("roadslam-map", ProgressMeasure::Items, 90, 300, 90, 9.0),
            "roadslam-map [#########                     ] 90/300, 10.0/s, ETA 21 s");
  EXPECT_EQ(progressLine("roadslam-map", ProgressMeasure::Items, 90, 0, 90, 9.0), "roadslam-map 90 frames, 10.0/s, 9 s");
  EXPECT_EQ(progressLine("roadslam-map", ProgressMeasure::Bytes, 4.1e6, 10e6, 120, 12.0),
            "roadslam-map [############                  ] 41 % of 10.0 MB, 120 frames, 10.0/s, ETA 17 s");
  EXPECT_EQ(progressLine("roadslam-sim", ProgressMeasure::SimulatedSeconds, 12.0, 60.0, 0, 3.0),
            "roadslam-sim [######                        ] 12.0 of 60.0 s simulated, 4.0x real time, ETA 12 s");
  // Bytes without a total (a live source) fall back to frames and rate.
  EXPECT_EQ(progressLine("roadslam-map", ProgressMeasure::Bytes, 4e6, 0, 20, 2.0), "roadslam-map 20 frames, 10.0/s, 2 s");
  EXPECT_EQ(progressLine("x", ProgressMeasure::Bytes, 0, 10e6, 0, 0.5),
            "x [                              ] 0 % of 10.0 MB, 0 frames, 0.0/s, ETA ?");
}
