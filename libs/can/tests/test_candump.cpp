// candump log format: parsing the can-utils examples, format/parse round trips over random frames,
// bad-line accounting, and interop with can-utils' own log2asc.
#include <roadslam/can/candump.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

using namespace roadslam::can;

namespace {
CanFrame parseOk(const std::string& line) {
  CanFrame f;
  const char* err = nullptr;
  EXPECT_TRUE(parseCandumpLine(line, f, &err)) << line << ": " << (err ? err : "");
  return f;
}
}  // namespace

TEST(Candump, ParsesCanUtilsExamples) {
  CanFrame f = parseOk("(1436509052.249713) can0 123#DEADBEEF");
  EXPECT_EQ(f.t_us, 1436509052249713LL);
  EXPECT_STREQ(f.iface.data(), "can0");
  EXPECT_EQ(f.id, 0x123U);
  EXPECT_FALSE(f.extended());
  ASSERT_EQ(f.len, 4);
  EXPECT_EQ(f.data[0], 0xDE);
  EXPECT_EQ(f.data[3], 0xEF);

  f = parseOk("(0000000001.000001) vcan1 12345678#00.11.22");
  EXPECT_TRUE(f.extended());
  EXPECT_EQ(f.id, 0x12345678U);
  EXPECT_EQ(f.len, 3);
  EXPECT_EQ(f.data[2], 0x22);

  f = parseOk("(1.5) can0 321#R5");
  EXPECT_TRUE(f.remote());
  EXPECT_EQ(f.len, 5);
  EXPECT_EQ(f.t_us, 1500000);

  f = parseOk("(1.000000) can0 123##2112233");
  EXPECT_TRUE(f.fd());
  EXPECT_EQ(f.fd_flags, kFdEsi);
  EXPECT_EQ(f.len, 3);

  f = parseOk("(1.000000) can0 20000080#0000000000000000");
  EXPECT_TRUE(f.error());
  EXPECT_EQ(f.id, 0x80U);

  f = parseOk("(1.000000) can0 123#1122334455667788_E");
  EXPECT_EQ(f.len8_dlc, 0xE);
}

TEST(Candump, RejectsMalformedLinesWithReason) {
  const char* bad[] = {"garbage", "(1.0) can0", "(1.0) can0 1234#00", "(1.0) can0 123#0",
                       "(1.0) can0 123#001122334455667788", "(abc) can0 123#00", "(1.0) can0 800#00",
                       "(1.0) can0 123#R9", "(1.0) can0 123##", "(1.0) can0 123#11_3",
                       "(1.0) can0 123#00 extra"};
  for (const char* line : bad) {
    CanFrame f;
    const char* err = nullptr;
    EXPECT_FALSE(parseCandumpLine(line, f, &err)) << line;
    EXPECT_NE(err, nullptr) << line;
  }
}

TEST(Candump, RandomFramesRoundTripThroughText) {
  std::mt19937 rng(42);
  for (int i = 0; i < 5000; ++i) {
    CanFrame f;
    f.t_us = static_cast<std::int64_t>(rng() % 2000000000ULL) * 1000000 + rng() % 1000000;
    f.setInterface(i % 2 ? "can0" : "vcan12");
    const unsigned kind = rng() % 5;
    f.flags = (rng() % 2) ? kExtended : 0;
    f.id = f.extended() ? rng() & 0x1FFFFFFFU : rng() & 0x7FFU;
    if (kind == 0) {
      f.flags |= kRemote;
      f.len = static_cast<std::uint8_t>(rng() % 9);
    } else if (kind == 1) {
      f.flags |= kFd;
      f.fd_flags = static_cast<std::uint8_t>(rng() % 4);
      f.len = fdDlcToLen(static_cast<std::uint8_t>(rng() % 16));
    } else if (kind == 2) {
      f.flags = kError;
      f.id = rng() & 0x1FFFFFFFU;
      f.len = 8;
    } else {
      f.len = static_cast<std::uint8_t>(rng() % 9);
      if (f.len == 8 && kind == 3) f.len8_dlc = static_cast<std::uint8_t>(9 + rng() % 7);
    }
    if (!f.remote()) {
      for (std::size_t b = 0; b < f.len; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
    }
    const std::string line = formatCandumpLine(f);
    ASSERT_FALSE(line.empty());
    CanFrame g;
    const char* err = nullptr;
    ASSERT_TRUE(parseCandumpLine(std::string_view(line).substr(0, line.size() - 1), g, &err)) << line << err;
    EXPECT_EQ(f, g) << line;
    EXPECT_EQ(formatCandumpLine(g), line);
  }
}

TEST(Candump, ReaderCountsBadLinesAndKeepsTheRest) {
  std::istringstream in(
      "(1.000000) can0 123#01\n"
      "this is not a frame\n"
      "\n"
      "(1.000100) can0 124#0203\n"
      "(1.000200) can0 XYZ#00\n"
      "(1.000300) can0 125#0405\n"
      "(1.000400) can0 126#06");  // cut-off last line without newline: still parses
  CandumpReader r(in, "mem");
  std::vector<CanFrame> got;
  CanFrame f;
  while (r.next(f)) got.push_back(f);
  ASSERT_EQ(got.size(), 4U);
  EXPECT_EQ(got[3].id, 0x126U);
  EXPECT_EQ(r.stats().bad, 2U);
  EXPECT_EQ(r.stats().empty, 1U);
  ASSERT_EQ(r.stats().issues.size(), 2U);
  EXPECT_EQ(r.stats().issues[0].line, 2U);
  EXPECT_EQ(r.stats().issues[1].line, 5U);
  EXPECT_FALSE(r.stats().truncated_tail);

  std::istringstream cut2("(1.000000) can0 123#01\n(1.000100) can0 12");
  CandumpReader r2(cut2, "cut");
  int n = 0;
  while (r2.next(f)) ++n;
  EXPECT_EQ(n, 1);
  EXPECT_TRUE(r2.stats().truncated_tail);
  EXPECT_EQ(r2.stats().issues.at(0).line, 2U);
}

TEST(Candump, CanUtilsLog2ascAndAsc2logRoundTrip) {
  if (std::system("command -v log2asc >/dev/null 2>&1") != 0) GTEST_SKIP() << "can-utils log2asc not installed";
  const std::string path = ::testing::TempDir() + "/roadslam_log2asc.log";
  std::vector<CanFrame> frames(3);
  frames[0].t_us = 1436509052249713LL;
  frames[0].setInterface("can0");
  frames[0].id = 0x123;
  frames[0].len = 4;
  frames[0].data = {0xDE, 0xAD, 0xBE, 0xEF};
  frames[1] = frames[0];
  frames[1].t_us += 100000;
  frames[1].flags = kExtended;
  frames[1].id = 0x12345678;
  frames[2] = frames[0];
  frames[2].t_us += 200000;
  frames[2].flags = kRemote;
  frames[2].len = 0;
  CanFrame fd = frames[0];
  fd.t_us += 300000;
  fd.flags = kFd;
  fd.fd_flags = kFdBrs;
  fd.len = 12;
  for (std::uint8_t b = 0; b < 12; ++b) fd.data[b] = static_cast<std::uint8_t>(0x10 + b);
  frames.push_back(fd);
  writeCandumpFile(path, frames);
  const std::string asc = path + ".asc";
  ASSERT_EQ(std::system(("log2asc -I " + path + " -O " + asc + " can0").c_str()), 0);
  std::ifstream in(asc);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("0.000000 1  123             Rx   d 4 DE AD BE EF"), std::string::npos) << text;
  EXPECT_NE(text.find("0.100000 1  12345678x       Rx   d 4 DE AD BE EF"), std::string::npos) << text;
  EXPECT_NE(text.find("0.200000 1  123             Rx   r"), std::string::npos) << text;
  EXPECT_EQ(readCandumpFile(path), frames);

  // And back with can-utils' asc2log, whose candump output (with the " R" direction suffix) we read.
  const std::string back = path + ".back.log";
  ASSERT_EQ(std::system(("asc2log -I " + asc + " -O " + back + " >/dev/null 2>&1").c_str()), 0);
  CandumpStats st;
  const auto again = readCandumpFile(back, &st);
  EXPECT_EQ(st.bad, 0U);
  ASSERT_EQ(again.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    CanFrame a = again[i];
    a.t_us = frames[i].t_us - frames[0].t_us + again[0].t_us;  // asc keeps relative times only
    EXPECT_EQ(a.t_us, again[i].t_us);
    a.t_us = frames[i].t_us;
    EXPECT_EQ(a, frames[i]) << formatCandumpLine(again[i]);
  }
}
