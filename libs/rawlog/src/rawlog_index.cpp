#include "roadslam/rawlog/rawlog_index.h"

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>
#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "rawlog_index_impl.h"
#include "roadslam/rawlog/mrpt_message.h"

namespace roadslam::rawlog {

using detail::innermostMessage;

using detail::GzAccessPoint;
using detail::SeekableStream;

namespace {

// "Stored object has class 'X' which is not registered!" -> X
std::optional<std::string> unregisteredClass(const std::string& what) {
  const auto at = what.find("which is not registered");
  if (at == std::string::npos) return std::nullopt;
  const auto q1 = what.rfind('\'', at), q0 = q1 == 0 ? std::string::npos : what.rfind('\'', q1 - 1);
  if (q0 == std::string::npos) return std::string("?");
  return what.substr(q0 + 1, q1 - q0 - 1);
}

}  // namespace

namespace detail {
FileStamp stampOf(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error("rawlog '" + path + "' does not exist");
  return {uint64_t(st.st_size), int64_t(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec};
}

}  // namespace detail

// The next offset after \p from where a record of a registered class starts and reads; the stream
// is left there. False at the end of the file (or damage) without one.
bool RawlogIndex::Impl::resync(uint64_t from) {
  constexpr std::size_t kBlock = 1 << 16, kMaxName = 80;
  std::vector<uint8_t> buf(kBlock + kMaxName + 1);
  for (uint64_t base = from;;) {
    stream->Seek(int64_t(base));
    const std::size_t n = stream->Read(buf.data(), buf.size());
    if (n == 0) return false;
    for (std::size_t j = 0; j + 1 < n && j < kBlock; ++j) {
      const uint8_t b = buf[j];
      const std::size_t len = b & 0x7f;
      if (!(b & 0x80) || len < 2 || len > kMaxName || j + 1 + len > n) continue;
      const char* name = reinterpret_cast<const char*>(&buf[j + 1]);
      if (!std::isalpha(static_cast<unsigned char>(name[0]))) continue;
      if (!std::all_of(name, name + len, [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':'; }))
        continue;
      if (!mrpt::rtti::findRegisteredClass(std::string(name, len))) continue;
      try {  // a candidate: it must read as a whole object
        stream->Seek(int64_t(base + j));
        mrpt::serialization::archiveFrom(*stream).ReadObject();
        stream->Seek(int64_t(base + j));
        return true;
      } catch (const std::exception&) {
        stream->Seek(int64_t(base + n));
      }
    }
    if (n < buf.size()) return false;
    base += kBlock;
  }
}

void RawlogIndex::Impl::build(uint64_t span, const std::function<bool(const Impl&)>& progress) {
  constexpr std::size_t kReportEvery = 32;  // records (~3 MB of VLP-16 sweeps) between progress calls
  stream = std::make_unique<SeekableStream>(path);
  gzip = stream->gzip();
  stream->recordAccessPoints(span);
  auto arch = mrpt::serialization::archiveFrom(*stream);
  for (std::size_t reported = 0;;) {
    if (progress && entries.size() >= reported + kReportEvery) {
      reported = entries.size();
      if (!progress(*this)) {
        abandoned = true;
        return;
      }
    }
    const uint64_t start = stream->getPosition();
    const uint64_t zstart = stream->compressedPosition();
    mrpt::serialization::CSerializable::Ptr rec;
    std::string failure;
    try {
      rec = arch.ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
      if (stream->getPosition() != start) failure = "record cut short";
    } catch (const std::exception& e) {
      if (const auto cls = unregisteredClass(e.what())) {
        // listed and skipped: its size is the distance to the next readable record
        const std::size_t at = entries.size();
        add(start, 0, -1, nullptr, *cls, false);
        const bool more = resync(start + 1);
        const uint64_t next = more ? stream->getPosition() : stream->getPosition();
        entries[at].size = uint32_t(std::min<uint64_t>(next - start, 0xffffffffu));
        if (more) continue;
        if (!stream->damage().empty()) failure = "after a record of unknown class '" + *cls + "'";
        else break;
      } else if (detail::isCutShort(e.what())) {
        failure = "record cut short";  // MRPT wraps its CExceptionEOF from inside an object
      } else {
        failure = innermostMessage(e.what());
      }
    }
    if (!rec && failure.empty() && stream->damage().empty()) break;  // clean end of file
    if (!rec) {
      complete = false;
      stop = stopMessageOf(start, zstart, failure);
      break;
    }
    const uint64_t size = stream->getPosition() - start;
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(rec)) {
      int32_t k = 0;
      for (const auto& o : *sf) add(start, size, k++, o.get(), o->GetRuntimeClass()->className, true);
      if (k == 0) add(start, size, -1, nullptr, "CSensoryFrame", true);
    } else {
      const auto* o = dynamic_cast<const mrpt::obs::CObservation*>(rec.get());
      add(start, size, -1, o, rec->GetRuntimeClass()->className, true);
    }
  }
  uncompressed = stream->getPosition();
  stream->recordAccessPoints(0);
}

// "truncated record at uncompressed byte N (observation K, compressed byte Z); <the stream's damage>"
std::string RawlogIndex::Impl::stopMessageOf(uint64_t start, uint64_t zstart, const std::string& failure) const {
  const std::string& damage = stream->damage();
  // data ending inside a record (or the compressed stream ending): truncated; a record failing
  // with no cause of its own: the stream's damage is the cause
  const bool cut = failure == "record cut short" || (failure.empty() && damage.rfind("compressed stream cut short", 0) == 0);
  const std::string cause = cut ? "" : failure.empty() ? damage : failure;
  std::ostringstream m;
  m << detail::stopPlace(start, cause) << " (observation " << entries.size();
  if (gzip) m << ", compressed byte " << zstart;
  m << ")";
  if (!damage.empty() && cause != damage) m << "; " << damage;
  return m.str();
}

void RawlogIndex::Impl::finish() {
  by_time.clear();
  for (uint32_t i = 0; i < entries.size(); ++i) by_time.add(i, entries[i].stamp_s);
}

std::string RawlogIndex::sidecarPath(const std::string& rawlog_path) { return rawlog_path + ".idx"; }

RawlogIndex::IndexFiles RawlogIndex::indexFiles(const std::string& rawlog_path, const RawlogIndexOptions& opt) {
  IndexFiles f;
  f.read.push_back(sidecarPath(rawlog_path));
  if (!opt.cache_path) {
    f.write = f.read.front();
    return f;
  }
  f.write = opt.cache_path(rawlog_path);
  if (f.write != f.read.front()) f.read.push_back(f.write);
  return f;
}

bool RawlogIndex::Impl::readFirstFresh(const std::vector<std::string>& files) {
  std::string notes;
  for (const auto& file : files) {
    std::ifstream f(file, std::ios::binary);
    if (!f) continue;
    const std::string buf((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    std::string why;
    if (deserialize(buf, why)) return true;
    notes += (notes.empty() ? "index '" : "; index '") + file + "' " + why;
  }
  if (!notes.empty()) info.cache_note = notes + ": rebuilt";
  return false;
}

std::unique_ptr<RawlogIndex> RawlogIndex::open(const std::string& path, const RawlogIndexOptions& opt) {
  return open(path, opt, {});
}

std::unique_ptr<RawlogIndex> RawlogIndex::open(const std::string& path, const RawlogIndexOptions& opt,
                                               const std::function<bool(const Impl&)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->stamp = detail::stampOf(path);
  const IndexFiles files = indexFiles(path, opt);
  const bool loaded = opt.use_cache && impl->readFirstFresh(files.read);
  if (!loaded) {
    impl->labels.clear();
    impl->classes.clear();
    if (opt.on_build) opt.on_build(path);
    impl->build(opt.span_bytes, progress);
    if (impl->abandoned) return nullptr;
    if (opt.write_cache) {
      try {
        writeFileAtomically(files.write, impl->serialize());
        impl->info.cache_written = true;
      } catch (const std::exception& e) {
        impl->info.cache_note = std::string("index not cached: ") + e.what();
      }
    }
  }
  impl->info.from_cache = loaded;
  impl->finish();
  impl->info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return std::unique_ptr<RawlogIndex>(new RawlogIndex(std::move(impl)));
}

RawlogIndex::RawlogIndex(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RawlogIndex::~RawlogIndex() = default;

const std::string& RawlogIndex::path() const { return impl_->path; }
const RawlogOpenInfo& RawlogIndex::openInfo() const { return impl_->info; }
std::size_t RawlogIndex::size() const { return impl_->entries.size(); }
const RawlogEntry& RawlogIndex::entry(std::size_t i) const { return impl_->entries.at(i); }
const std::vector<std::string>& RawlogIndex::labels() const { return impl_->labels.names(); }
const std::vector<std::string>& RawlogIndex::classNames() const { return impl_->classes.names(); }
bool RawlogIndex::complete() const { return impl_->complete; }
const std::string& RawlogIndex::stopMessage() const { return impl_->stop; }
bool RawlogIndex::gzip() const { return impl_->gzip; }
uint64_t RawlogIndex::uncompressedBytes() const { return impl_->uncompressed; }
std::size_t RawlogIndex::accessPoints() const { return impl_->stream->accessPoints().size(); }

std::vector<std::pair<std::string, std::size_t>> RawlogIndex::unknownClasses() const {
  std::map<std::string, std::size_t> n;
  for (const auto& e : impl_->entries)
    if (!e.known) ++n[impl_->classes.names()[e.cls]];
  return {n.begin(), n.end()};
}

double RawlogIndex::firstStamp() const { return impl_->by_time.first(); }
double RawlogIndex::lastStamp() const { return impl_->by_time.last(); }
std::optional<std::size_t> RawlogIndex::findAtTime(double t_s) const { return impl_->by_time.atTime(t_s); }
std::vector<std::size_t> RawlogIndex::findInRange(double t0_s, double t1_s) const {
  return impl_->by_time.inRange(t0_s, t1_s);
}

std::shared_ptr<mrpt::obs::CObservation> RawlogIndex::load(std::size_t i) {
  const RawlogEntry& e = entry(i);
  if (!e.known)
    throw std::runtime_error(impl_->path + ": observation " + std::to_string(i) + " is of class '" + className(i) +
                             "', unknown to this build");
  if (!(detail::stampOf(impl_->path) == impl_->stamp)) throw std::runtime_error(impl_->path + " changed since it was indexed");
  return detail::loadEntry(*impl_->stream, e, impl_->path, i);
}

std::shared_ptr<mrpt::obs::CObservation> detail::loadEntry(SeekableStream& stream, const RawlogEntry& e,
                                                           const std::string& path, std::size_t i) {
  const std::string where = path + ": observation " + std::to_string(i);
  try {
    stream.Seek(int64_t(e.offset));
    const auto rec = mrpt::serialization::archiveFrom(stream).ReadObject();
    if (e.sub >= 0) {
      auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(rec);
      if (!sf || std::size_t(e.sub) >= sf->size()) throw std::runtime_error("not the sensory frame indexed");
      return sf->getObservationByIndex(std::size_t(e.sub));
    }
    return std::dynamic_pointer_cast<mrpt::obs::CObservation>(rec);
  } catch (const std::exception& ex) {
    throw std::runtime_error(where + " (byte " + std::to_string(e.offset) + "): " + innermostMessage(ex.what()));
  }
}

}  // namespace roadslam::rawlog

namespace roadslam::rawlog {

RawlogIndexRecorder::RawlogIndexRecorder() : impl_(std::make_unique<RawlogIndex::Impl>()) {}
RawlogIndexRecorder::~RawlogIndexRecorder() = default;

void RawlogIndexRecorder::add(uint64_t offset, uint64_t size, const mrpt::obs::CObservation& obs) {
  impl_->add(offset, size, -1, &obs, obs.GetRuntimeClass()->className, true);
}

void RawlogIndexRecorder::addAccessPoint(uint64_t out, uint64_t in, const uint8_t* window, uint64_t span_bytes) {
  if (out < SeekableStream::kWindow) return;  // the dictionary must be a full window of history
  if (!points_out_in_.empty() && out - points_out_in_.back()[0] < span_bytes) return;
  uLongf zlen = compressBound(SeekableStream::kWindow);
  std::vector<uint8_t> z(zlen);
  compress2(z.data(), &zlen, window, SeekableStream::kWindow, 1);
  z.resize(zlen);
  points_out_in_.push_back({out, in});
  windows_z_.push_back(std::move(z));
}

void RawlogIndexRecorder::write(const std::string& rawlog_path, uint64_t uncompressed) const {
  RawlogIndex::Impl& im = *impl_;
  im.path = rawlog_path;
  im.stamp = detail::stampOf(rawlog_path);
  im.gzip = true;
  im.complete = true;
  im.uncompressed = uncompressed;
  im.stream = std::make_unique<SeekableStream>(rawlog_path);
  std::vector<GzAccessPoint> pts(points_out_in_.size());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    pts[k].out = points_out_in_[k][0];
    pts[k].in = points_out_in_[k][1];
    pts[k].bits = 0;  // byte-aligned after a sync flush
    pts[k].window_z = windows_z_[k];
  }
  im.stream->setAccessPoints(std::move(pts));
  writeFileAtomically(RawlogIndex::sidecarPath(rawlog_path), im.serialize());
  im.stream.reset();
}

void RawlogIndexRecorder::clear() {
  impl_ = std::make_unique<RawlogIndex::Impl>();
  points_out_in_.clear();
  windows_z_.clear();
}

}  // namespace roadslam::rawlog
