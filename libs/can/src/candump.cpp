#include <roadslam/can/candump.h>
#include <roadslam/common/atomic_file.h>

#include <algorithm>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <istream>
#include <sstream>
#include <stdexcept>

namespace roadslam::can {
namespace {

int hexValue(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

constexpr std::uint32_t kCanErrFlag = 0x20000000U;  // linux/can.h CAN_ERR_FLAG
constexpr std::uint32_t kCanErrMask = 0x1FFFFFFFU;

bool parseId(std::string_view s, CanFrame& out, const char** error) noexcept {
  if (s.size() != 3 && s.size() != 8) {
    *error = "CAN id must have 3 (11-bit) or 8 (29-bit) hex digits";
    return false;
  }
  std::uint32_t v = 0;
  for (char c : s) {
    const int h = hexValue(c);
    if (h < 0) {
      *error = "non-hex character in CAN id";
      return false;
    }
    v = (v << 4) | static_cast<std::uint32_t>(h);
  }
  if (s.size() == 3) {
    if (v > 0x7FF) {
      *error = "11-bit CAN id above 0x7FF";
      return false;
    }
    out.id = v;
    return true;
  }
  if (v & kCanErrFlag) {
    out.flags |= kError;
  } else if (v & ~kCanErrMask) {
    *error = "29-bit CAN id above 0x1FFFFFFF";
    return false;
  } else {
    out.flags |= kExtended;
  }
  out.id = v & kCanErrMask;
  return true;
}

// Hex bytes, optionally separated by '.', up to max_len bytes.
bool parseData(std::string_view s, CanFrame& out, std::size_t max_len, const char** error) noexcept {
  std::size_t n = 0;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] == '.') {
      ++i;
      continue;
    }
    if (i + 1 >= s.size()) {
      *error = "odd number of hex digits in payload";
      return false;
    }
    const int hi = hexValue(s[i]);
    const int lo = hexValue(s[i + 1]);
    if (hi < 0 || lo < 0) {
      *error = "non-hex character in payload";
      return false;
    }
    if (n >= max_len) {
      *error = "payload longer than the frame type allows";
      return false;
    }
    out.data[n++] = static_cast<std::uint8_t>((hi << 4) | lo);
    i += 2;
  }
  out.len = static_cast<std::uint8_t>(n);
  return true;
}

bool parseClassicBody(std::string_view body, CanFrame& out, const char** error) noexcept {
  if (!body.empty() && (body[0] == 'R' || body[0] == 'r')) {
    out.flags |= kRemote;
    if (body.size() == 1) return true;
    const int l = hexValue(body[1]);
    if (body.size() != 2 || l < 0 || l > 8) {
      *error = "remote frame length must be one digit 0..8";
      return false;
    }
    out.len = static_cast<std::uint8_t>(l);
    return true;
  }
  const std::size_t us = body.find('_');
  if (us != std::string_view::npos) {
    const std::string_view tail = body.substr(us + 1);
    const int d = tail.size() == 1 ? hexValue(tail[0]) : -1;
    if (d < 9) {
      *error = "len8_dlc suffix must be one hex digit 9..F";
      return false;
    }
    if (!parseData(body.substr(0, us), out, 8, error)) return false;
    if (out.len != 8) {
      *error = "len8_dlc suffix needs 8 data bytes";
      return false;
    }
    out.len8_dlc = static_cast<std::uint8_t>(d);
    return true;
  }
  return parseData(body, out, 8, error);
}

bool parseTimestamp(std::string_view s, std::int64_t& t_us, const char** error) noexcept {
  // "(sssssssss.uuuuuu)": the fraction may have 1..9 digits, kept to microseconds.
  if (s.size() < 3 || s.front() != '(' || s.back() != ')') {
    *error = "timestamp must be '(seconds.fraction)'";
    return false;
  }
  s = s.substr(1, s.size() - 2);
  const std::size_t dot = s.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot > 12 || s.size() - dot - 1 == 0 ||
      s.size() - dot - 1 > 9) {
    *error = "timestamp must be '(seconds.fraction)'";
    return false;
  }
  std::int64_t sec = 0;
  for (std::size_t i = 0; i < dot; ++i) {
    if (s[i] < '0' || s[i] > '9') {
      *error = "non-digit in timestamp";
      return false;
    }
    sec = sec * 10 + (s[i] - '0');
  }
  std::int64_t frac = 0;
  std::size_t digits = 0;
  for (std::size_t i = dot + 1; i < s.size(); ++i, ++digits) {
    if (s[i] < '0' || s[i] > '9') {
      *error = "non-digit in timestamp";
      return false;
    }
    if (digits < 6) frac = frac * 10 + (s[i] - '0');
  }
  for (; digits < 6; ++digits) frac *= 10;
  t_us = sec * 1000000 + frac;
  return true;
}

std::string_view nextField(std::string_view& rest) noexcept {
  std::size_t b = 0;
  while (b < rest.size() && (rest[b] == ' ' || rest[b] == '\t')) ++b;
  std::size_t e = b;
  while (e < rest.size() && rest[e] != ' ' && rest[e] != '\t') ++e;
  const std::string_view f = rest.substr(b, e - b);
  rest = rest.substr(e);
  return f;
}

}  // namespace

bool operator==(const CanFrame& a, const CanFrame& b) noexcept {
  return a.t_us == b.t_us && a.id == b.id && a.len == b.len && a.flags == b.flags &&
         a.fd_flags == b.fd_flags && a.len8_dlc == b.len8_dlc &&
         std::strncmp(a.iface.data(), b.iface.data(), kMaxInterfaceName) == 0 &&
         std::equal(a.data.begin(), a.data.begin() + a.len, b.data.begin());
}

void CanFrame::setInterface(const char* name) noexcept {
  iface.fill(0);
  std::memcpy(iface.data(), name, strnlen(name, kMaxInterfaceName - 1));
}

std::uint8_t fdDlcToLen(std::uint8_t dlc) noexcept {
  static constexpr std::uint8_t kLen[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};
  return kLen[dlc & 0x0F];
}

std::uint8_t fdPaddedLen(std::uint8_t len) noexcept {
  for (std::uint8_t dlc = 0; dlc < 16; ++dlc) {
    if (fdDlcToLen(dlc) >= len) return fdDlcToLen(dlc);
  }
  return 64;
}

bool parseFrameText(std::string_view text, CanFrame& out, const char** error) noexcept {
  const std::size_t hash = text.find('#');
  if (hash == std::string_view::npos) {
    *error = "missing '#' between id and data";
    return false;
  }
  if (!parseId(text.substr(0, hash), out, error)) return false;
  std::string_view body = text.substr(hash + 1);
  if (!body.empty() && body[0] == '#') {  // CAN FD: "##<flags nibble><data>"
    if (out.error()) {
      *error = "error frames cannot be CAN FD";
      return false;
    }
    const int fl = body.size() >= 2 ? hexValue(body[1]) : -1;
    if (fl < 0) {
      *error = "CAN FD frame needs a flags nibble after '##'";
      return false;
    }
    out.flags |= kFd;
    out.fd_flags = static_cast<std::uint8_t>(fl);
    return parseData(body.substr(2), out, 64, error);
  }
  return parseClassicBody(body, out, error);
}

bool parseCandumpLine(std::string_view line, CanFrame& out, const char** error) noexcept {
  out = CanFrame{};
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::string_view rest = line;
  const std::string_view ts = nextField(rest);
  const std::string_view ifc = nextField(rest);
  const std::string_view frame = nextField(rest);
  if (frame.empty()) {
    *error = "expected '(time) interface id#data'";
    return false;
  }
  if (!parseTimestamp(ts, out.t_us, error)) return false;
  if (ifc.size() >= kMaxInterfaceName) {
    *error = "interface name longer than 15 characters";
    return false;
  }
  for (char c : ifc) {
    if (c <= ' ' || c > '~') {
      *error = "non-printable character in interface name";
      return false;
    }
  }
  std::copy(ifc.begin(), ifc.end(), out.iface.begin());
  // candump -l may append " R"/" T" (rx/tx direction) with -x; accept and ignore a single char.
  const std::string_view extra = nextField(rest);
  if (!extra.empty() && !(extra.size() == 1 && (extra[0] == 'R' || extra[0] == 'T'))) {
    *error = "unexpected text after the frame";
    return false;
  }
  return parseFrameText(frame, out, error);
}

std::size_t formatCandumpLine(const CanFrame& f, char* buf, std::size_t cap) noexcept {
  static constexpr char kHex[] = "0123456789ABCDEF";
  if (cap < 220) return 0;
  const long long sec = static_cast<long long>(f.t_us / 1000000);
  const long long usec = static_cast<long long>(f.t_us % 1000000);
  int n = std::snprintf(buf, cap, "(%010lld.%06lld) %s ", sec, usec, f.iface.data());
  if (n < 0) return 0;
  auto p = static_cast<std::size_t>(n);
  if (f.error()) {
    p += static_cast<std::size_t>(std::snprintf(buf + p, cap - p, "%08X#", f.id | kCanErrFlag));
  } else if (f.extended()) {
    p += static_cast<std::size_t>(std::snprintf(buf + p, cap - p, "%08X#", f.id));
  } else {
    p += static_cast<std::size_t>(std::snprintf(buf + p, cap - p, "%03X#", f.id));
  }
  if (f.fd()) {
    buf[p++] = '#';
    buf[p++] = kHex[f.fd_flags & 0x0F];
  } else if (f.remote()) {
    buf[p++] = 'R';
    if (f.len > 0) buf[p++] = kHex[f.len & 0x0F];
    buf[p++] = '\n';
    return p;
  }
  for (std::size_t i = 0; i < f.len; ++i) {
    buf[p++] = kHex[f.data[i] >> 4];
    buf[p++] = kHex[f.data[i] & 0x0F];
  }
  if (!f.fd() && f.len == 8 && f.len8_dlc > 8) {
    buf[p++] = '_';
    buf[p++] = kHex[f.len8_dlc & 0x0F];
  }
  buf[p++] = '\n';
  return p;
}

std::string formatCandumpLine(const CanFrame& frame) {
  char buf[256];
  return std::string(buf, formatCandumpLine(frame, buf, sizeof(buf)));
}

CandumpReader::CandumpReader(const std::string& path, std::size_t max_issues)
    : file_(std::make_unique<std::ifstream>(path, std::ios::binary)),
      in_(file_.get()),
      name_(path),
      max_issues_(max_issues) {
  if (!*file_) throw std::runtime_error("cannot open candump log '" + path + "'");
}

CandumpReader::CandumpReader(std::istream& in, std::string name, std::size_t max_issues)
    : in_(&in), name_(std::move(name)), max_issues_(max_issues) {}

CandumpReader::~CandumpReader() = default;

bool CandumpReader::next(CanFrame& frame) {
  while (std::getline(*in_, line_)) {
    ++stats_.lines;
    const bool no_newline = in_->eof();
    std::string_view v(line_);
    while (!v.empty() && (v.back() == '\r' || v.back() == ' ' || v.back() == '\t')) v.remove_suffix(1);
    std::size_t b = 0;
    while (b < v.size() && (v[b] == ' ' || v[b] == '\t')) ++b;
    v.remove_prefix(b);
    if (v.empty() || v[0] == '#') {
      ++stats_.empty;
      continue;
    }
    const char* err = nullptr;
    if (parseCandumpLine(v, frame, &err)) {
      ++stats_.frames;
      return true;
    }
    ++stats_.bad;
    if (no_newline) stats_.truncated_tail = true;
    if (stats_.issues.size() < max_issues_) {
      stats_.issues.push_back({stats_.lines, no_newline ? std::string(err) + " (truncated last line)" : err,
                               std::string(v.substr(0, 80))});
    }
  }
  return false;
}

std::vector<CanFrame> readCandumpFile(const std::string& path, CandumpStats* stats) {
  CandumpReader reader(path);
  std::vector<CanFrame> frames;
  CanFrame f;
  while (reader.next(f)) frames.push_back(f);
  if (stats) *stats = reader.stats();
  return frames;
}

void writeCandumpFile(const std::string& path, const std::vector<CanFrame>& frames) {
  AtomicFile out(path, std::ios::out | std::ios::trunc | std::ios::binary);
  char buf[256];
  for (const CanFrame& f : frames) {
    out.stream().write(buf, static_cast<std::streamsize>(formatCandumpLine(f, buf, sizeof(buf))));
  }
  out.commit();
}

std::optional<CandumpSpan> candumpSpan(const std::string& path) {
  CandumpReader reader(path);
  CanFrame f;
  if (!reader.next(f)) return std::nullopt;
  CandumpSpan span{static_cast<double>(f.t_us) * 1e-6, static_cast<double>(f.t_us) * 1e-6};
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 64 * 1024);  // many lines of 30-200 bytes
  std::string text(static_cast<size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(text.data(), tail);
  for (size_t end = text.size(); end > 0;) {  // the last line that parses, from the end
    const size_t begin = text.rfind('\n', end - 1);
    const size_t from = begin == std::string::npos ? 0 : begin + 1;
    const char* error = nullptr;
    if (from < end && parseCandumpLine(std::string_view(text).substr(from, end - from), f, &error)) {
      span.last_s = std::max(span.first_s, static_cast<double>(f.t_us) * 1e-6);
      break;
    }
    if (begin == std::string::npos) break;
    end = begin;
  }
  return span;
}

}  // namespace roadslam::can
