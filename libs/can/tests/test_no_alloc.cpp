// The per-frame decode path must not allocate: global operator new is counted while decoding.
#include <roadslam/can/decoder.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <random>

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace roadslam::can;

TEST(Decoder, PerFramePathIsNoexceptAndDoesNotAllocate) {
  const Decoder dec(parseDbc(R"(BO_ 170 WHEEL_SPEEDS: 8 X
 SG_ WHEEL_SPEED_FR : 7|16@0+ (0.01,-67.67) [0|250] "km/h" X
 SG_ WHEEL_SPEED_FL : 23|16@0+ (0.01,-67.67) [0|250] "km/h" X
BO_ 2566844926 EXT: 8 X
 SG_ MUX M : 0|4@1+ (1,0) [0|15] "" X
 SG_ A m1 : 8|56@1- (0.5,3) [0|0] "" X
)"));
  CanFrame f;
  double out[8];
  static_assert(noexcept(dec.decode(f, out, nullptr)), "decode must be noexcept");
  std::mt19937 rng(3);
  double sink = 0;
  const long before = g_allocations.load();
  for (int i = 0; i < 20000; ++i) {
    f.id = (i % 3 == 0) ? 170 : (i % 3 == 1 ? (2566844926U & 0x1FFFFFFFU) : 0x123);
    f.flags = (i % 3 == 1) ? kExtended : 0;
    f.len = 8;
    for (int b = 0; b < 8; ++b) f.data[static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(rng());
    if (dec.decode(f, out, nullptr) == DecodeStatus::kOk) sink += out[0];
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_NE(sink, 0.0);
}
