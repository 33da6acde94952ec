#include "roadslam/common/atomic_file.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <streambuf>
#include <vector>

namespace roadslam {
namespace {

/// A write(2) stream buffer that remembers the errno of its first failed write.
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buf_(1 << 16) { setp(buf_.data(), buf_.data() + buf_.size()); }
  int error() const { return err_; }
  int sync() override { return drain() ? 0 : -1; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }

 private:
  bool drain() {
    const char* p = pbase();
    while (p < pptr() && err_ == 0) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) err_ = n < 0 ? errno : EIO;
      else p += n;
    }
    setp(buf_.data(), buf_.data() + buf_.size());
    return err_ == 0;
  }
  int fd_;
  int err_ = 0;
  std::vector<char> buf_;
};

/// fsync(2) of \p p; its errno, 0 when it succeeded (delayed allocation reports ENOSPC here).
int fsyncPath(const std::string& p) {
  const int fd = ::open(p.c_str(), O_RDONLY);
  if (fd < 0) return errno;
  const int rc = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return rc == EINVAL ? 0 : rc;  // a file system without fsync (some FUSE mounts) is not a write error
}

std::runtime_error cannotWrite(const std::string& path, const std::string& reason) {
  return std::runtime_error("cannot write '" + path + "': " + reason);
}

}  // namespace

std::string writeErrorReason(const std::string& path, int err) {
  if (err != 0) return std::strerror(err);
  struct statvfs st {};
  const std::string dir = std::filesystem::path(path).parent_path().string();
  if (::statvfs(dir.empty() ? "." : dir.c_str(), &st) == 0 && st.f_bavail == 0) return std::strerror(ENOSPC);
  return "write error";
}

std::string tempPathFor(const std::string& path) {
  return path + ".tmp-" + std::to_string(::getpid());
}

void commitTempFile(const std::string& tmp_path, const std::string& final_path) {
  int err = fsyncPath(tmp_path);
  if (err == 0 && std::rename(tmp_path.c_str(), final_path.c_str()) != 0) err = errno;
  if (err != 0) {
    std::remove(tmp_path.c_str());
    throw cannotWrite(final_path, std::strerror(err));
  }
}

struct AtomicFile::Impl {
  int fd = -1;
  std::unique_ptr<FdBuf> buf;
  std::unique_ptr<std::ostream> out;
};

AtomicFile::AtomicFile(std::string path, std::ios::openmode)
    : path_(std::move(path)), tmp_(tempPathFor(path_)), impl_(std::make_unique<Impl>()) {
  impl_->fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (impl_->fd < 0) throw std::runtime_error("cannot create '" + path_ + "': " + std::strerror(errno));
  impl_->buf = std::make_unique<FdBuf>(impl_->fd);
  impl_->out = std::make_unique<std::ostream>(impl_->buf.get());
}

AtomicFile::~AtomicFile() {
  if (impl_->fd >= 0) ::close(impl_->fd);
  if (!committed_) std::remove(tmp_.c_str());
}

std::ostream& AtomicFile::stream() { return *impl_->out; }

void AtomicFile::commit() {
  impl_->out->flush();
  int err = impl_->buf->error();
  if (err == 0 && !*impl_->out) err = EIO;
  if (err == 0 && ::fsync(impl_->fd) != 0 && errno != EINVAL) err = errno;
  if (::close(impl_->fd) != 0 && err == 0) err = errno;
  impl_->fd = -1;
  if (err != 0) {
    std::remove(tmp_.c_str());
    throw cannotWrite(path_, writeErrorReason(path_, err));
  }
  commitTempFile(tmp_, path_);
  committed_ = true;
}

void writeFileAtomically(const std::string& path, const std::string& contents) {
  AtomicFile f(path);
  f.stream() << contents;
  f.commit();
}

TempFile::TempFile(std::string final_path, const std::string& extension)
    : path_(std::move(final_path)), tmp_(tempPathFor(path_) + extension) {}

TempFile::~TempFile() {
  if (!committed_) std::remove(tmp_.c_str());
}

void TempFile::commit() {
  commitTempFile(tmp_, path_);
  committed_ = true;
}

std::string TempFile::failure(const std::string& what) const {
  const int err = errno;
  return "cannot write " + (what.empty() ? "" : what + " ") + "'" + path_ + "': " + writeErrorReason(path_, err);
}

}  // namespace roadslam
