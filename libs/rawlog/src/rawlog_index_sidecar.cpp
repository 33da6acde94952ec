#include <cstring>
#include <stdexcept>

#include "rawlog_index_impl.h"

// The sidecar "<rawlog>.idx": magic, format version, the rawlog's size and modification time, then
// the index (names, entries, damage) and the gzip access points; an end marker. Any mismatch makes
// the caller rebuild it.
namespace roadslam::rawlog {

using detail::GzAccessPoint;
using detail::SeekableStream;

namespace {
constexpr char kMagic[8] = {'R', 'S', 'R', 'L', 'I', 'D', 'X', '\n'};
constexpr uint32_t kFormatVersion = 1;
constexpr uint64_t kEndMarker = 0x454e44494458ULL;  // "XDIDNE"

// Binary writer / bounds-checked reader of the sidecar (host byte order: the sidecar is a cache).
struct Out {
  std::string buf;
  template <class T>
  void put(const T& v) { buf.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void str(const std::string& s) {
    put(uint32_t(s.size()));
    buf += s;
  }
};
struct In {
  const std::string& buf;
  std::size_t at = 0;
  template <class T>
  T get() {
    if (at + sizeof(T) > buf.size()) throw std::runtime_error("sidecar cut short");
    T v;
    std::memcpy(&v, buf.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::string str() {
    const auto n = get<uint32_t>();
    if (at + n > buf.size()) throw std::runtime_error("sidecar cut short");
    std::string s = buf.substr(at, n);
    at += n;
    return s;
  }
};
}  // namespace

std::string RawlogIndex::Impl::serialize() const {
  Out o;
  o.buf.append(kMagic, sizeof kMagic);
  o.put(kFormatVersion);
  o.put(stamp.size);
  o.put(stamp.mtime_ns);
  o.put(uint8_t(gzip));
  o.put(uint8_t(complete));
  o.put(uncompressed);
  o.str(stop);
  o.put(uint32_t(labels.names().size()));
  for (const auto& s : labels.names()) o.str(s);
  o.put(uint32_t(classes.names().size()));
  for (const auto& s : classes.names()) o.str(s);
  o.put(uint64_t(entries.size()));
  for (const auto& e : entries) {
    o.put(e.offset);
    o.put(e.size);
    o.put(e.sub);
    o.put(e.stamp_s);
    o.put(e.label);
    o.put(e.cls);
    o.put(uint8_t(e.known));
  }
  const auto& pts = stream->accessPoints();
  o.put(uint64_t(pts.size()));
  for (const auto& p : pts) {
    o.put(p.out);
    o.put(p.in);
    o.put(p.bits);
    o.put(uint32_t(p.window_z.size()));
    o.buf.append(reinterpret_cast<const char*>(p.window_z.data()), p.window_z.size());
  }
  o.put(kEndMarker);
  return o.buf;
}

bool RawlogIndex::Impl::deserialize(const std::string& buf, std::string& why) {
  try {
    if (buf.size() < sizeof kMagic || std::memcmp(buf.data(), kMagic, sizeof kMagic) != 0) {
      why = "not a roadslam rawlog index";
      return false;
    }
    In in{buf, sizeof kMagic};
    if (in.get<uint32_t>() != kFormatVersion) {
      why = "index format version differs";
      return false;
    }
    detail::FileStamp s;
    s.size = in.get<uint64_t>();
    s.mtime_ns = in.get<int64_t>();
    if (!(s == stamp)) {
      why = "stale (the rawlog's size or modification time changed)";
      return false;
    }
    gzip = in.get<uint8_t>() != 0;
    complete = in.get<uint8_t>() != 0;
    uncompressed = in.get<uint64_t>();
    stop = in.str();
    for (auto* table : {&labels, &classes}) {
      const auto n = in.get<uint32_t>();
      if (n > buf.size()) throw std::runtime_error("bad name count");
      for (uint32_t k = 0; k < n; ++k)
        if (table->id(in.str()) != k) throw std::runtime_error("a name listed twice");
    }
    const auto n = in.get<uint64_t>();
    if (n > buf.size()) throw std::runtime_error("bad entry count");
    entries.resize(n);
    for (auto& e : entries) {
      e.offset = in.get<uint64_t>();
      e.size = in.get<uint32_t>();
      e.sub = in.get<int32_t>();
      e.stamp_s = in.get<double>();
      e.label = in.get<uint16_t>();
      e.cls = in.get<uint16_t>();
      e.known = in.get<uint8_t>() != 0;
      if (e.label >= std::max<std::size_t>(labels.names().size(), 1) ||
          e.cls >= std::max<std::size_t>(classes.names().size(), 1))
        throw std::runtime_error("bad name id");
    }
    const auto np = in.get<uint64_t>();
    if (np > buf.size()) throw std::runtime_error("bad access point count");
    std::vector<GzAccessPoint> pts(np);
    for (auto& p : pts) {
      p.out = in.get<uint64_t>();
      p.in = in.get<uint64_t>();
      p.bits = in.get<int32_t>();
      const auto len = in.get<uint32_t>();
      if (in.at + len > buf.size() || p.bits < 0 || p.bits > 7) throw std::runtime_error("bad access point");
      p.window_z.assign(buf.begin() + long(in.at), buf.begin() + long(in.at + len));
      in.at += len;
    }
    if (in.get<uint64_t>() != kEndMarker || in.at != buf.size()) throw std::runtime_error("no end marker");
    stream = std::make_unique<SeekableStream>(path);
    stream->setAccessPoints(std::move(pts));
    return true;
  } catch (const std::exception& e) {
    why = std::string("unreadable (") + e.what() + ")";
    entries.clear();
    labels.clear();
    classes.clear();
    return false;
  }
}


}  // namespace roadslam::rawlog
