// Log summary: rates, gaps, unknown ids and DLC mismatches on a synthetic log with known defects.
#include <roadslam/can/log_info.h>

#include <gtest/gtest.h>

using namespace roadslam::can;

TEST(LogInfo, FindsRatesGapsUnknownIdsAndDlcMismatches) {
  const Database db = parseDbc("BO_ 256 A: 8 X\n SG_ S : 0|8@1+ (1,0) [0|0] \"\" X\n");
  std::vector<CanFrame> frames;
  for (int i = 0; i < 100; ++i) {
    if (i >= 40 && i < 50) continue;  // 10 frames missing: one 0.11 s gap
    CanFrame f;
    f.t_us = 1000000 + i * 10000;  // 100 Hz
    f.setInterface("can0");
    f.id = 0x100;
    f.len = i == 70 ? 5 : 8;  // one short frame
    frames.push_back(f);
    if (i % 10 == 0) {
      CanFrame u = f;
      u.id = 0x200;
      u.t_us += 1;
      frames.push_back(u);
    }
  }
  const LogInfo info = analyzeLog(frames, &db);
  ASSERT_EQ(info.ids.size(), 2U);
  const IdInfo& a = info.ids[0];
  EXPECT_EQ(a.id, 0x100U);
  EXPECT_EQ(a.name, "A");
  EXPECT_EQ(a.count, 90U);
  EXPECT_NEAR(a.median_period_s, 0.01, 1e-9);
  EXPECT_EQ(a.gaps, 1U);
  EXPECT_EQ(a.dlc_mismatches, 1U);
  EXPECT_EQ(info.unknown_ids, 1U);
  EXPECT_EQ(info.unknown_frames, 9U);  // every 10th frame, the one at i = 40 is missing
  ASSERT_EQ(info.gaps.size(), 1U);
  EXPECT_NEAR(info.gaps[0].length_s, 0.11, 1e-9);
  EXPECT_NEAR(info.gaps[0].t_s, 1.5, 1e-9);
  const std::string text = formatLogInfoText(info);
  EXPECT_NE(text.find("UNKNOWN"), std::string::npos) << text;
  EXPECT_NE(text.find("DLC-MISMATCH x1"), std::string::npos) << text;
  EXPECT_NE(formatLogInfoJson(info).find("\"unknown_ids\": 1"), std::string::npos);
}
