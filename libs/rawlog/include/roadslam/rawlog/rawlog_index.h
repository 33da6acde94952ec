#pragma once
/// \file rawlog_index.h
/// Random access to an MRPT rawlog (observations format: a plain or gzip stream of serialized
/// objects; also the sensory-frames format). The file is read once to build an index (per
/// observation: uncompressed byte offset, size, time, sensor label, class name) that is cached in a
/// sidecar file beside it, "<rawlog>.idx", or where RawlogIndexOptions::cache_path says, stamped with
/// the rawlog's size and modification time; a stale or unreadable one is rebuilt. Observation i is then loaded by seeking to its offset:
/// a gzip rawlog keeps zlib access points (zran.c) every `span` uncompressed bytes in the sidecar, so a
/// seek decompresses at most `span` bytes.
///
/// Damage never throws: a truncated or corrupt rawlog is indexed up to the damage, and complete() is
/// false with stopMessage() naming the byte and the observation where reading stopped. A record of
/// a class this build does not know (not registered with MRPT) is listed with its class name and
/// skipped by searching forward for the next record a registered class reads.
///
/// Not thread-safe: load() moves the single read position.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "roadslam/rawlog/observation_index.h"

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::rawlog {

struct RawlogIndexOptions {
  uint64_t span_bytes = 4u << 20;  ///< gzip: uncompressed bytes between access points [bytes]
  bool use_cache = true;           ///< read the first fresh one of RawlogIndex::indexFiles().read
  bool write_cache = true;         ///< write indexFiles().write after building (atomically; a failure is a warning)
  /// Where the index is kept, for a program that must not write beside its input (roadslam-view):
  /// given the rawlog's path, the index file to write, and to read after the sidecar beside the
  /// rawlog (read when fresh: roadslam-grab writes one for each segment). Empty: "<rawlog>.idx".
  std::function<std::string(const std::string& rawlog_path)> cache_path;
  /// Called once when the index has to be built (reading the whole file: ~1 s per 100 MB of gzip
  /// here), e.g. to tell the user; may be empty.
  std::function<void(const std::string& rawlog_path)> on_build;
};

/// How open() went.
struct RawlogOpenInfo {
  bool from_cache = false;     ///< the sidecar was fresh and read
  bool cache_written = false;  ///< the index was built and the sidecar written
  std::string cache_note;      ///< why the sidecar was rebuilt or could not be written (empty: no note)
  double seconds = 0;          ///< wall time of open() [s]
};

class RawlogIndex : public ObservationIndex {
 public:
  /// Opens \p path (throws std::runtime_error naming it when it does not exist or cannot be read at
  /// all) and indexes it, or reads its fresh sidecar.
  static std::unique_ptr<RawlogIndex> open(const std::string& path, const RawlogIndexOptions& options = {});
  ~RawlogIndex() override;

  /// Sidecar path for \p rawlog_path: "<rawlog_path>.idx".
  static std::string sidecarPath(const std::string& rawlog_path);
  /// The index files of \p rawlog_path under \p options: those open() reads, in order (the first
  /// fresh one is used: the sidecar, then options.cache_path's file), and the one it writes.
  struct IndexFiles {
    std::vector<std::string> read;
    std::string write;
  };
  static IndexFiles indexFiles(const std::string& rawlog_path, const RawlogIndexOptions& options);

  const std::string& path() const;
  const RawlogOpenInfo& openInfo() const;
  std::size_t size() const override;
  const RawlogEntry& entry(std::size_t i) const override;
  const std::vector<std::string>& labels() const override;
  const std::vector<std::string>& classNames() const override;

  /// False when reading stopped at damage (a truncated or corrupt file) before the end.
  bool complete() const;
  /// Where reading stopped and why, in the replay's words (sources::RawlogPacketSource) followed by
  /// what only the index knows, e.g. "truncated record at uncompressed byte 3781234 (observation 41,
  /// compressed byte 1203321); compressed stream cut short at compressed byte 1250000", or
  /// "unreadable record at uncompressed byte N: CAUSE (observation K)"; empty when complete.
  const std::string& stopMessage() const;
  /// Classes this build cannot read, with their number of records.
  std::vector<std::pair<std::string, std::size_t>> unknownClasses() const;
  bool gzip() const;
  /// Uncompressed bytes indexed [bytes].
  uint64_t uncompressedBytes() const;
  /// gzip access points kept (0 for a plain file) [count].
  std::size_t accessPoints() const;

  /// First and last finite stamps [s]; both 0 for a rawlog without any.
  double firstStamp() const override;
  double lastStamp() const override;
  /// The observation shown at time \p t_s: the last one (in time order) stamped at or before it,
  /// else the first; nullopt when no observation has a stamp.
  std::optional<std::size_t> findAtTime(double t_s) const override;
  /// Indices of the observations whose stamp lies in [t0_s, t1_s), in time order.
  std::vector<std::size_t> findInRange(double t0_s, double t1_s) const override;

  /// Reads observation \p i from the file. Throws std::runtime_error naming the rawlog and the
  /// index when it cannot be read (an unknown class, an I/O error, the file changed).
  std::shared_ptr<mrpt::obs::CObservation> load(std::size_t i) override;

 private:
  friend class BackgroundRawlogIndex;
  friend class RawlogIndexRecorder;
  struct Impl;
  /// open(), reporting the index as it grows: \p progress runs on the calling thread every few
  /// records; returning false abandons the build (nullptr is returned, no sidecar written).
  static std::unique_ptr<RawlogIndex> open(const std::string& path, const RawlogIndexOptions& options,
                                           const std::function<bool(const Impl&)>& progress);
  explicit RawlogIndex(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace roadslam::rawlog

namespace roadslam::rawlog {

/// The index of a gzip rawlog kept by the program that writes it (roadslam-grab's segments), written
/// as the "<rawlog>.idx" sidecar RawlogIndex reads, so even the first open of a recording reads the
/// sidecar instead of the whole file. The writer reports each record and, after each gzip
/// Z_SYNC_FLUSH (the stream is byte-aligned at a block boundary there: RFC 1951, 3.2.4), an access
/// point with the 32 KiB of data before it.
class RawlogIndexRecorder {
 public:
  RawlogIndexRecorder();
  ~RawlogIndexRecorder();
  /// \p obs was serialized as the record at uncompressed \p offset, \p size bytes long [bytes].
  void add(uint64_t offset, uint64_t size, const mrpt::obs::CObservation& obs);
  /// After a sync flush: \p out uncompressed bytes written, \p in compressed bytes in the file,
  /// \p window the last 32768 uncompressed bytes. Points closer than \p span_bytes to the last
  /// one are not kept.
  void addAccessPoint(uint64_t out, uint64_t in, const uint8_t* window, uint64_t span_bytes = 4u << 20);
  /// Writes the sidecar of the closed rawlog \p rawlog_path (\p uncompressed bytes in all),
  /// stamped with its size and modification time; throws naming the file on failure.
  void write(const std::string& rawlog_path, uint64_t uncompressed) const;
  /// Forgets everything (the next segment).
  void clear();

 private:
  std::unique_ptr<RawlogIndex::Impl> impl_;
  std::vector<std::array<uint64_t, 2>> points_out_in_;
  std::vector<std::vector<uint8_t>> windows_z_;
};

}  // namespace roadslam::rawlog
