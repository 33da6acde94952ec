#pragma once
/// \file segment_writer.h
/// MRPT rawlog ("observations" format: a gzip stream of serialized CSerializable objects, what
/// CRawlog::saveToRawLogFile writes and RawLogViewer / rawlog-edit / RawlogPacketSource read) in
/// segments <dir>/<prefix>_000.rawlog, _001, ... rotated by size or age.
///
/// Crash safety: segments are written under their final names and syncFlush() issues a gzip
/// Z_SYNC_FLUSH (RFC 1951 empty stored block: everything before it is decodable) through write(2), so
/// after a SIGKILL or a power cut a reader decodes every object written before the last sync
/// flush and then sees a truncated stream (no gzip trailer). close() writes the trailer.
/// Segments concatenate: `cat grab_*.rawlog > all.rawlog` is a valid multi-member gzip rawlog.
///
/// Each closed segment gets its index sidecar "<segment>.idx" (rawlog::RawlogIndexRecorder: every
/// observation's offset, size, time, label and class, and a gzip access point at the sync flushes
/// every 4 MB), so the first open of a recording (roadslam-view) reads the sidecar, not the whole
/// file. A segment cut short by a crash has none and is indexed when opened.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/rawlog/rawlog_index.h"

namespace mrpt::serialization {
class CSerializable;
}

namespace roadslam::grabber {

struct SegmentPolicy {
  double max_size_bytes = 512e6;  ///< rotate once the compressed segment exceeds this [bytes]
  double max_age_s = 0;           ///< rotate after this long since the segment opened [s]; 0 = never
  int compression_level = 1;      ///< gzip level 0..9 [-]
};

class SegmentWriter {
 public:
  /// Opens the first segment; throws std::runtime_error naming the file when it cannot be created.
  SegmentWriter(std::string dir, std::string prefix, const SegmentPolicy& policy);
  ~SegmentWriter();  ///< close()s (errors swallowed: call close() to see them)
  SegmentWriter(const SegmentWriter&) = delete;
  SegmentWriter& operator=(const SegmentWriter&) = delete;

  /// Serializes \p obj into the current segment; rotates first when the policy says so
  /// (\p now_s: monotonic time [s]). Throws naming the segment on a write error (disk full).
  void write(const mrpt::serialization::CSerializable& obj, double now_s);
  /// Z_SYNC_FLUSH of the current segment, handed to the kernel with write(2) (see the file comment).
  void syncFlush();
  /// Writes the gzip trailer of the current segment, closes it and writes its index sidecar;
  /// idempotent. Throws naming the segment when either fails.
  void close();

  const std::vector<std::string>& segments() const { return segments_; }  ///< paths so far
  std::uint64_t objectsWritten() const { return objects_; }
  std::uint64_t bytesUncompressed() const { return raw_bytes_; }  ///< all segments [bytes]
  /// Compressed size of the current segment up to the last flush [bytes].
  std::uint64_t currentSegmentBytes() const;
  /// Compressed size of all segments [bytes].
  std::uint64_t totalBytes() const { return closed_bytes_ + currentSegmentBytes(); }

 private:
  void openNext(double now_s);
  void closeCurrent();

  std::string dir_, prefix_;
  SegmentPolicy policy_;
  void* gz_ = nullptr;  // gzFile
  double opened_s_ = 0;
  bool first_ = true;
  std::vector<std::string> segments_;
  std::uint64_t objects_ = 0, raw_bytes_ = 0, closed_bytes_ = 0;
  std::uint64_t segment_raw_ = 0;          // uncompressed bytes of the current segment
  std::vector<std::uint8_t> history_;      // its last 32 KiB, circular: the access points' dictionary
  rawlog::RawlogIndexRecorder index_;
};

}  // namespace roadslam::grabber
