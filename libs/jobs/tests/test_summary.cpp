// summary.json's `blind` block on a hand-made frame sequence whose answer is counted by hand.
#include <gtest/gtest.h>

#include "roadslam/jobs/map_job.h"

using namespace roadslam;
using odometry::FrameStatus;

TEST(Summary, BlindStretchesCountedFromTheLastSeeingFrame) {
  // 0.1 s apart: first, 3 ok, 4 degenerate, ok, skipped (no pose), 2 degenerate, ok
  const std::vector<FrameStatus> seq = {FrameStatus::First, FrameStatus::Ok, FrameStatus::Ok, FrameStatus::Ok,
                                        FrameStatus::Degenerate, FrameStatus::Degenerate, FrameStatus::Degenerate,
                                        FrameStatus::Degenerate, FrameStatus::Ok, FrameStatus::Skipped,
                                        FrameStatus::Degenerate, FrameStatus::Degenerate, FrameStatus::Ok};
  std::vector<odometry::FrameResult> frames;
  for (size_t i = 0; i < seq.size(); ++i) {
    odometry::FrameResult f;
    f.index = i;
    f.stamp_s = 100.0 + 0.1 * i;
    f.status = seq[i];
    frames.push_back(f);
  }
  const auto b = jobs::summarize(frames)["blind"];
  EXPECT_EQ(b["degenerate_frames"].get<int>(), 6);
  EXPECT_NEAR(b["degenerate_fraction"].get<double>(), 6.0 / 12.0, 1e-12);  // 12 frames have a pose
  EXPECT_EQ(b["longest_blind_frames"].get<int>(), 4);
  EXPECT_NEAR(b["longest_blind_s"].get<double>(), 0.4, 1e-9);  // frame 3 (last seeing) to frame 7
  EXPECT_NEAR(b["longest_blind_start_s"].get<double>(), 100.3, 1e-9);
}

TEST(Summary, NoBlindFramesOnAGoodDrive) {
  std::vector<odometry::FrameResult> frames(5);
  for (size_t i = 0; i < frames.size(); ++i) frames[i].stamp_s = 0.1 * i;
  frames[0].status = FrameStatus::First;
  const auto b = jobs::summarize(frames)["blind"];
  EXPECT_EQ(b["degenerate_frames"].get<int>(), 0);
  EXPECT_EQ(b["degenerate_fraction"].get<double>(), 0.0);
  EXPECT_EQ(b["longest_blind_frames"].get<int>(), 0);
  EXPECT_EQ(b["longest_blind_s"].get<double>(), 0.0);
}
