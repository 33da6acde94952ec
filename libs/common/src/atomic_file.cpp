#include "roadslam/common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace roadslam {
namespace {
void fsyncPath(const std::string& p) {
  const int fd = ::open(p.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}
}  // namespace

std::string tempPathFor(const std::string& path) {
  return path + ".tmp-" + std::to_string(::getpid());
}

void commitTempFile(const std::string& tmp_path, const std::string& final_path) {
  fsyncPath(tmp_path);
  if (std::rename(tmp_path.c_str(), final_path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp_path.c_str());
    throw std::runtime_error("cannot write '" + final_path + "': " + why);
  }
}

AtomicFile::AtomicFile(std::string path, std::ios::openmode mode)
    : path_(std::move(path)), tmp_(tempPathFor(path_)) {
  out_.open(tmp_, mode);
  if (!out_) {
    throw std::runtime_error("cannot create '" + path_ + "': " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::remove(tmp_.c_str());
  }
}

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw std::runtime_error("write error on '" + path_ + "'");
  out_.close();
  commitTempFile(tmp_, path_);
  committed_ = true;
}

void writeFileAtomically(const std::string& path, const std::string& contents) {
  AtomicFile f(path, std::ios::out | std::ios::trunc | std::ios::binary);
  f.stream() << contents;
  f.commit();
}

}  // namespace roadslam
