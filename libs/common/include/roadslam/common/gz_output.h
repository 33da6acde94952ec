#pragma once
/// \file gz_output.h
/// A gzip output stream for MRPT serialization that reports write errors. MRPT's
/// CFileGZOutputStream returns gzwrite's count unchecked and ignores gzclose's result
/// (mrpt/libs/io/src/CFileGZOutputStream.cpp), so a disk that fills at the last flush silently cuts
/// the end of a rawlog. This one throws "cannot write 'NAME': REASON" (NAME: the final file, not
/// the temporary one written to) at the first failed write and at a failed close.

#include <mrpt/io/CStream.h>

#include <string>

namespace roadslam {

class GzOutput : public mrpt::io::CStream {
 public:
  /// Creates \p path (gzip level \p level, 0-9); \p name is the file errors name. Throws naming it.
  GzOutput(const std::string& path, int level, std::string name);
  ~GzOutput() override;
  GzOutput(const GzOutput&) = delete;
  GzOutput& operator=(const GzOutput&) = delete;

  size_t Write(const void* buffer, size_t count) override;  ///< throws on a short or failed write
  size_t Read(void* buffer, size_t count) override;         ///< throws: an output stream
  uint64_t Seek(int64_t offset, TSeekOrigin origin) override;  ///< throws: not seekable
  uint64_t getTotalBytesCount() const override;             ///< uncompressed bytes written
  uint64_t getPosition() const override;                    ///< uncompressed bytes written
  /// Flushes and closes; throws naming the file and the reason. Idempotent.
  void close();
  /// The first error (empty: none), e.g. "cannot write 'x.rawlog': No space left on device".
  const std::string& error() const { return error_; }

 private:
  [[noreturn]] void fail(int err);
  void* gz_ = nullptr;
  std::string name_, error_;
  uint64_t written_ = 0;
};

}  // namespace roadslam
