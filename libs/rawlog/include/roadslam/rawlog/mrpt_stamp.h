#pragma once
/// \file mrpt_stamp.h
/// An MRPT timestamp (100 ns ticks since 1601-01-01, signed 64 bits) as seconds since the Unix epoch,
/// negative ones included. mrpt::Clock::toDouble (MRPT 2.5.8) subtracts its 1601->1970 offset as an
/// unsigned number, so a stamp before 1970 wraps to about 1.8e12 s: a KITTI sweep stamped at its first
/// firing, 0.05 s before the first line of times.txt (0.0), read back as 1844674407370.9 s.
/// mrpt::Clock::fromDouble gets negative seconds right only through an out-of-range double to
/// unsigned conversion (undefined behaviour that happens to wrap on x86); stampOf() does it in signed
/// arithmetic.
#include <mrpt/core/Clock.h>

#include <cmath>
#include <cstdint>

namespace roadslam::rawlog {

/// 100 ns ticks from 1601-01-01 to 1970-01-01 (MRPT's and Windows' FILETIME epoch to Unix).
constexpr int64_t kUnixEpochTicks = INT64_C(116444736000000000);

/// Seconds since 1970-01-01 of \p t [s]; equal to mrpt::Clock::toDouble for stamps from 1970 on.
inline double stampSeconds(mrpt::Clock::time_point t) {
  return static_cast<double>(t.time_since_epoch().count() - kUnixEpochTicks) / 1e7;
}

/// The MRPT timestamp of \p t_s seconds since 1970-01-01, negative ones included [100 ns ticks].
inline mrpt::Clock::time_point stampOf(double t_s) {
  return mrpt::Clock::time_point(mrpt::Clock::duration(kUnixEpochTicks + static_cast<int64_t>(std::llround(t_s * 1e7))));
}

}  // namespace roadslam::rawlog
