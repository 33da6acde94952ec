#pragma once
/// \file mrpt_stamp.h
/// An MRPT timestamp (100 ns ticks since 1601-01-01, signed 64 bits) as seconds since the Unix epoch,
/// negative ones included. mrpt::Clock::toDouble (MRPT 2.5.8) subtracts its 1601->1970 offset as an
/// unsigned number, so a stamp before 1970 wraps to about 1.8e12 s: a KITTI sweep stamped at its first
/// firing, 0.05 s before the first line of times.txt (0.0), read back as 1844674407370.9 s.
/// mrpt::Clock::fromDouble converts negative seconds right; read them back with stampSeconds().
#include <mrpt/core/Clock.h>

#include <cstdint>

namespace roadslam::rawlog {

/// 100 ns ticks from 1601-01-01 to 1970-01-01 (MRPT's and Windows' FILETIME epoch to Unix).
constexpr int64_t kUnixEpochTicks = INT64_C(116444736000000000);

/// Seconds since 1970-01-01 of \p t [s]; equal to mrpt::Clock::toDouble for stamps from 1970 on.
inline double stampSeconds(mrpt::Clock::time_point t) {
  return static_cast<double>(t.time_since_epoch().count() - kUnixEpochTicks) / 1e7;
}

}  // namespace roadslam::rawlog
