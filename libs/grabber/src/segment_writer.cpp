#include "roadslam/grabber/segment_writer.h"

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/CSerializable.h>
#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace roadslam::grabber {
namespace {
constexpr std::size_t kWindow = 32768;  // deflate's history (RFC 1951): an access point's dictionary
}

SegmentWriter::SegmentWriter(std::string dir, std::string prefix, const SegmentPolicy& policy)
    : dir_(std::move(dir)), prefix_(std::move(prefix)), policy_(policy) {
  openNext(0);
}

SegmentWriter::~SegmentWriter() {
  try {
    close();
  } catch (...) {
  }
}

void SegmentWriter::openNext(double now_s) {
  char name[64];
  std::snprintf(name, sizeof(name), "_%03zu.rawlog", segments_.size());
  const std::string path = dir_ + "/" + prefix_ + name;
  const std::string mode = "wb" + std::to_string(policy_.compression_level);
  gz_ = gzopen(path.c_str(), mode.c_str());
  if (!gz_) throw std::runtime_error("cannot create rawlog segment '" + path + "'");
  gzbuffer(static_cast<gzFile>(gz_), 1 << 18);
  segments_.push_back(path);
  opened_s_ = now_s;
  first_ = true;
  segment_raw_ = 0;
  history_.assign(kWindow, 0);
  index_.clear();
}

void SegmentWriter::closeCurrent() {
  if (!gz_) return;
  const int rc = gzclose(static_cast<gzFile>(gz_));
  gz_ = nullptr;
  struct stat st {};
  if (::stat(segments_.back().c_str(), &st) == 0) closed_bytes_ += std::uint64_t(st.st_size);
  if (rc != Z_OK) throw std::runtime_error("error closing rawlog segment '" + segments_.back() + "'");
  try {
    index_.write(segments_.back(), segment_raw_);
  } catch (const std::exception& e) {
    throw std::runtime_error("rawlog segment '" + segments_.back() + "' closed, its index not written: " + e.what());
  }
}

std::uint64_t SegmentWriter::currentSegmentBytes() const {
  if (!gz_) return 0;
  const auto off = gzoffset(static_cast<gzFile>(gz_));
  return off > 0 ? std::uint64_t(off) : 0;
}

void SegmentWriter::write(const mrpt::serialization::CSerializable& obj, double now_s) {
  if (!gz_) throw std::runtime_error("rawlog segment writer used after close()");
  if (first_) {
    opened_s_ = now_s;
    first_ = false;
  } else if (double(currentSegmentBytes()) >= policy_.max_size_bytes ||
             (policy_.max_age_s > 0 && now_s - opened_s_ >= policy_.max_age_s)) {
    closeCurrent();
    openNext(now_s);
    first_ = false;
  }
  mrpt::io::CMemoryStream mem;
  auto ar = mrpt::serialization::archiveFrom(mem);
  ar << obj;
  const auto n = mem.getTotalBytesCount();
  const int w = gzwrite(static_cast<gzFile>(gz_), mem.getRawBufferData(), unsigned(n));
  if (w != int(n)) throw std::runtime_error("write error on rawlog segment '" + segments_.back() + "'");
  if (const auto* o = dynamic_cast<const mrpt::obs::CObservation*>(&obj)) index_.add(segment_raw_, n, *o);
  const auto* bytes = static_cast<const std::uint8_t*>(mem.getRawBufferData());
  for (std::size_t k = n > kWindow ? n - kWindow : 0; k < n; ++k)  // the last 32 KiB, circular
    history_[(segment_raw_ + k) % kWindow] = bytes[k];
  ++objects_;
  raw_bytes_ += n;
  segment_raw_ += n;
}

void SegmentWriter::syncFlush() {
  if (!gz_) return;
  if (gzflush(static_cast<gzFile>(gz_), Z_SYNC_FLUSH) != Z_OK)
    throw std::runtime_error("flush error on rawlog segment '" + segments_.back() + "'");
  // Byte-aligned at a block boundary now: the file's size is where a raw inflate can restart.
  std::vector<std::uint8_t> window(kWindow);
  for (std::size_t k = 0; k < kWindow; ++k) window[k] = history_[(segment_raw_ + k) % kWindow];
  index_.addAccessPoint(segment_raw_, currentSegmentBytes(), window.data());
}

void SegmentWriter::close() { closeCurrent(); }

}  // namespace roadslam::grabber
