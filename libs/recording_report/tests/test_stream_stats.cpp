// streamStats on synthetic stamps whose rate, gaps and bins are known by construction.
#include <gtest/gtest.h>

#include "roadslam/recording_report/recording_report.h"

using namespace roadslam::recording_report;

TEST(StreamStats, TenHertzWithAHoleGivesRateGapAndBins) {
  std::vector<double> t;
  for (int i = 0; i <= 100; ++i)
    if (i < 40 || i > 44) t.push_back(1000.0 + i / 10.0);  // 10 Hz for 10 s, messages 40..44 lost
  ReportParams p;
  const StreamStats s = streamStats(t, 0, 1000.0, p);
  EXPECT_EQ(s.count, 96u);
  EXPECT_NEAR(s.nominal_period_s, 0.1, 1e-9) << "the median interval";
  EXPECT_NEAR(s.gap_threshold_s, 0.3, 1e-9);
  ASSERT_EQ(s.gap_count, 1u);
  ASSERT_EQ(s.gaps.size(), 1u);
  EXPECT_NEAR(s.gaps[0].start_s, 1003.9, 1e-9);
  EXPECT_NEAR(s.gaps[0].end_s, 1004.5, 1e-9);
  EXPECT_NEAR(s.gap_time_s, 0.6, 1e-9);
  EXPECT_NEAR(s.rate_hz, 95.0 / 10.0, 1e-9);
  ASSERT_EQ(s.bin_t_s.size(), 10u) << "whole 1 s bins only: the stamp at 10.0 s opens a bin that is left out";
  EXPECT_DOUBLE_EQ(s.bin_rate_hz[0], 10.0);
  EXPECT_DOUBLE_EQ(s.bin_rate_hz[4], 5.0) << "0.5 s of the hole fall into bin 4 (4.0 .. 4.4 lost)";
}

TEST(StreamStats, NominalPeriodSetsTheThresholdAndMinGapFloorsIt) {
  std::vector<double> t;
  for (int i = 0; i < 1000; ++i) t.push_back(0.001 * i + (i >= 500 ? 0.02 : 0.0));  // 20 ms hole at 0.5 s
  ReportParams p;
  EXPECT_EQ(streamStats(t, 0.001, 0, p).gap_count, 0u) << "20 ms is under min_gap_s = 50 ms";
  p.min_gap_s = 0.005;
  const StreamStats s = streamStats(t, 0.001, 0, p);
  EXPECT_EQ(s.gap_count, 1u);
  EXPECT_NEAR(s.gap_threshold_s, 0.005, 1e-12);
}

TEST(StreamStats, ListsTheLongestGapsInTimeOrderAndCountsThemAll) {
  std::vector<double> t;
  double now = 0;
  for (int g = 1; g <= 30; ++g) {
    for (int i = 0; i < 10; ++i) t.push_back(now += 0.01);
    now += 0.1 * g;  // gap g lasts 0.1 g + 0.01 s
  }
  ReportParams p;
  p.max_listed_gaps = 5;
  const StreamStats s = streamStats(t, 0.01, 0, p);
  EXPECT_EQ(s.gap_count, 29u) << "gap 30 follows the last message; gaps 1..29 are between messages";
  ASSERT_EQ(s.gaps.size(), 5u);
  for (size_t i = 1; i < s.gaps.size(); ++i) EXPECT_LT(s.gaps[i - 1].start_s, s.gaps[i].start_s);
  EXPECT_NEAR(s.gaps.front().length(), 2.5 + 0.01, 1e-9) << "the 5 longest: 25..29";
}

TEST(StreamStats, FarApartStreamsWidenTheBins) {
  ReportParams p;
  const StreamStats s = streamStats({1e9, 1e9 + 1}, 0, 0, p);
  EXPECT_LE(s.bin_t_s.size(), p.max_rate_bins + 1);
}
