#pragma once
/// \file rawlog_index_impl.h (private to libs/sources)
/// RawlogIndex's state, shared by rawlog_index.cpp (building, lookups, loading) and
/// rawlog_index_sidecar.cpp (the "<rawlog>.idx" file).

#include <mrpt/obs/CObservation.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/rawlog/mrpt_stamp.h"
#include "roadslam/rawlog/rawlog_index.h"
#include "seekable_stream.h"

namespace roadslam::rawlog {
namespace detail {
/// What identifies a version of the rawlog file: its size and modification time.
struct FileStamp {
  uint64_t size = 0;
  int64_t mtime_ns = 0;
  bool operator==(const FileStamp& o) const { return size == o.size && mtime_ns == o.mtime_ns; }
};
/// Throws std::runtime_error naming \p path when it does not exist.
FileStamp stampOf(const std::string& path);
/// Reads entry \p e (observation \p i of \p path) from \p stream; throws naming both on failure.
std::shared_ptr<mrpt::obs::CObservation> loadEntry(SeekableStream& stream, const RawlogEntry& e,
                                                   const std::string& path, std::size_t i);
}  // namespace detail

struct RawlogIndex::Impl {
  std::string path;
  detail::FileStamp stamp;
  RawlogOpenInfo info;
  std::vector<RawlogEntry> entries;
  NameIds labels, classes;
  TimeOrder by_time;
  bool complete = true, gzip = false;
  std::string stop;
  uint64_t uncompressed = 0;
  std::unique_ptr<detail::SeekableStream> stream;

  void add(uint64_t offset, uint64_t size, int32_t sub, const mrpt::obs::CObservation* o,
           const std::string& cls, bool known) {
    RawlogEntry e;
    e.offset = offset;
    e.size = uint32_t(std::min<uint64_t>(size, 0xffffffffu));
    e.sub = sub;
    e.stamp_s = o && o->timestamp != INVALID_TIMESTAMP ? stampSeconds(o->timestamp)
                                                         : std::numeric_limits<double>::quiet_NaN();
    e.label = labels.id(o ? o->sensorLabel : std::string());
    const auto colons = cls.rfind("::");  // "mrpt::obs::CObservationGPS" -> "CObservationGPS"
    e.cls = classes.id(colons == std::string::npos ? cls : cls.substr(colons + 2));
    e.known = known;
    entries.push_back(e);
  }
  /// Reads the whole file; \p progress (may be empty) sees the state every few records and may
  /// abandon the build by returning false (then `abandoned`).
  void build(uint64_t span, const std::function<bool(const Impl&)>& progress = {});
  bool abandoned = false;
  bool resync(uint64_t from);
  /// stop's text for reading stopped at uncompressed byte \p start (compressed \p zstart) for \p failure.
  std::string stopMessageOf(uint64_t start, uint64_t zstart, const std::string& failure) const;
  void finish();
  std::string serialize() const;
  bool deserialize(const std::string& buf, std::string& why);
  /// Reads the first of \p files that exists and is fresh; false, with why the others were not
  /// used in info.cache_note, when none is.
  bool readFirstFresh(const std::vector<std::string>& files);
};

}  // namespace roadslam::rawlog
