#pragma once
// (private to libs/sources) A read-only mrpt::io::CStream over a gzip-compressed (or plain) file
// through zlib's gzread, as mrpt::io::CFileGZInputStream reads it, which also tells the compressed
// bytes consumed (zlib's gzoffset): a replay's progress through the file.
#include <mrpt/io/CStream.h>
#include <zlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace roadslam::sources::detail {

class GzReadStream : public mrpt::io::CStream {
 public:
  GzReadStream() = default;
  ~GzReadStream() override {
    if (f_) gzclose(f_);
  }
  GzReadStream(const GzReadStream&) = delete;
  GzReadStream& operator=(const GzReadStream&) = delete;

  /// false when the file cannot be opened.
  bool open(const std::string& path) {
    std::error_code ec;
    size_ = std::filesystem::file_size(path, ec);
    if (ec) return false;
    f_ = gzopen(path.c_str(), "rb");
    return f_ != nullptr;
  }
  /// A zlib error (damaged data, a stream cut short) reads as the end of the file.
  size_t Read(void* buffer, size_t count) override {
    if (!f_) return 0;
    const int n = gzread(f_, buffer, static_cast<unsigned>(count));
    return n > 0 ? static_cast<size_t>(n) : 0;
  }
  size_t Write(const void*, size_t) override { throw std::runtime_error("GzReadStream: read-only"); }
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override { throw std::runtime_error("GzReadStream: not seekable"); }
  /// The compressed file's size [bytes].
  uint64_t getTotalBytesCount() const override { return size_; }
  /// Uncompressed bytes read [bytes], as CFileGZInputStream::getPosition (gztell).
  uint64_t getPosition() const override { return f_ ? static_cast<uint64_t>(gztell(f_)) : 0; }
  /// Compressed bytes consumed [bytes] (the file offset for a plain file).
  uint64_t compressedPosition() const { return f_ ? static_cast<uint64_t>(gzoffset(f_)) : 0; }

 private:
  gzFile f_ = nullptr;
  uint64_t size_ = 0;
};

}  // namespace roadslam::sources::detail
