#include "roadslam/common/gz_output.h"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam {

GzOutput::GzOutput(const std::string& path, int level, std::string name) : name_(std::move(name)) {
  const std::string mode = "wb" + std::to_string(level);
  gz_ = gzopen(path.c_str(), mode.c_str());
  if (!gz_) throw std::runtime_error("cannot create '" + name_ + "': " + std::strerror(errno));
}

GzOutput::~GzOutput() {
  if (gz_) gzclose(static_cast<gzFile>(gz_));  // an abandoned file: its caller removes it
}

void GzOutput::fail(int err) {
  if (error_.empty()) error_ = "cannot write '" + name_ + "': " + writeErrorReason(name_, err);
  throw std::runtime_error(error_);
}

size_t GzOutput::Write(const void* buffer, size_t count) {
  if (!gz_) throw std::runtime_error("'" + name_ + "' is closed");
  if (!error_.empty()) throw std::runtime_error(error_);
  if (count == 0) return 0;
  errno = 0;
  const int n = gzwrite(static_cast<gzFile>(gz_), buffer, static_cast<unsigned>(count));
  if (n <= 0 || static_cast<size_t>(n) != count) fail(errno);
  written_ += count;
  return count;
}

size_t GzOutput::Read(void*, size_t) { throw std::logic_error("GzOutput: reading from an output stream"); }
uint64_t GzOutput::Seek(int64_t, TSeekOrigin) { throw std::logic_error("GzOutput: not seekable"); }
uint64_t GzOutput::getTotalBytesCount() const { return written_; }
uint64_t GzOutput::getPosition() const { return written_; }

void GzOutput::close() {
  if (!gz_) return;
  errno = 0;
  const int rc = gzclose(static_cast<gzFile>(gz_));
  gz_ = nullptr;
  if (rc != Z_OK) fail(errno);
  if (!error_.empty()) throw std::runtime_error(error_);
}

}  // namespace roadslam
