#pragma once
/// \file seekable_stream.h (private to libs/sources)
/// A read-only mrpt::io::CStream over a plain or gzip-compressed file that can seek to any
/// uncompressed offset quickly. A plain file seeks with fseeko. A gzip file seeks through access
/// points recorded while the file is read once from its start (zlib's examples/zran.c, Mark Adler):
/// at a deflate block boundary every `span` uncompressed bytes, the compressed offset, the bit offset
/// inside that byte and the last 32 KiB of output (the dictionary) are kept; a seek restarts a raw
/// inflate at the nearest point before the target and decompresses forward (at most `span` bytes).
/// Multi-member gzip files (concatenated streams) are followed across members.

#include <mrpt/io/CStream.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace roadslam::rawlog::detail {

/// One restart point in a gzip stream (zran.c's `point`). The dictionary is kept zlib-compressed.
struct GzAccessPoint {
  uint64_t out = 0;    ///< uncompressed offset of the first byte after the point
  uint64_t in = 0;     ///< compressed offset of the first full byte after the point
  int32_t bits = 0;    ///< bits of the byte before `in` that belong to the next block (0-7)
  std::vector<uint8_t> window_z;  ///< the preceding 32 KiB of output, compressed with zlib compress()
};

class SeekableStream : public mrpt::io::CStream {
 public:
  static constexpr std::size_t kWindow = 32768;
  /// Opens \p path; throws std::runtime_error naming it when it cannot be opened.
  explicit SeekableStream(const std::string& path);
  ~SeekableStream() override;
  SeekableStream(const SeekableStream&) = delete;
  SeekableStream& operator=(const SeekableStream&) = delete;

  bool gzip() const { return gzip_; }
  /// Record access points every \p span_bytes of output from now on while reading forward.
  void recordAccessPoints(uint64_t span_bytes) { span_ = span_bytes; }
  const std::vector<GzAccessPoint>& accessPoints() const { return points_; }
  void setAccessPoints(std::vector<GzAccessPoint> points) { points_ = std::move(points); }
  /// Set when the compressed data is damaged (zlib error) or cut short; names the compressed byte.
  const std::string& damage() const { return damage_; }
  /// Compressed bytes consumed so far (the file offset for a plain file).
  uint64_t compressedPosition() const;

  size_t Read(void* buffer, size_t count) override;
  size_t Write(const void*, size_t) override { return 0; }
  /// Only sFromBeginning and sFromCurrent; returns the new uncompressed position.
  uint64_t Seek(int64_t offset, CStream::TSeekOrigin origin = sFromBeginning) override;
  uint64_t getTotalBytesCount() const override { return file_size_; }  ///< compressed size
  uint64_t getPosition() const override { return out_total_ - (have_ - rd_); }

 private:
  bool inflateMore();
  void restartAt(const GzAccessPoint* point);  // nullptr: the file start, gzip header mode
  void skipForward(uint64_t n);

  std::string path_;
  FILE* file_ = nullptr;
  uint64_t file_size_ = 0;
  bool gzip_ = false;
  // gzip state
  z_stream strm_{};
  bool strm_init_ = false, raw_mode_ = false, at_end_ = false;
  std::vector<uint8_t> in_buf_, win_;
  std::size_t have_ = 0, rd_ = 0;  // bytes in win_ produced / consumed
  uint64_t in_total_ = 0;          // compressed bytes read from the file into in_buf_
  uint64_t out_total_ = 0;         // uncompressed bytes produced (plain: file position)
  uint64_t span_ = 0;
  std::vector<GzAccessPoint> points_;
  std::string damage_;
};

}  // namespace roadslam::rawlog::detail
