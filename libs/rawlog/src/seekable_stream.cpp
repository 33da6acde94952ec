#include "seekable_stream.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace roadslam::rawlog::detail {

namespace {
constexpr std::size_t kChunk = 1 << 16;   // compressed bytes read from the file at a time
constexpr int kGzipAuto = 15 + 32;        // inflateInit2: zlib or gzip header, 32 KiB window
constexpr int kRaw = -15;                 // raw deflate (restart at an access point)
}  // namespace

SeekableStream::SeekableStream(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw std::runtime_error("cannot open '" + path + "'");
  std::fseek(file_, 0, SEEK_END);
  file_size_ = uint64_t(ftello(file_));
  std::fseek(file_, 0, SEEK_SET);
  unsigned char magic[2] = {0, 0};
  gzip_ = std::fread(magic, 1, 2, file_) == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
  std::fseek(file_, 0, SEEK_SET);
  if (gzip_) {
    in_buf_.resize(kChunk);
    win_.resize(kWindow);
    restartAt(nullptr);
  }
}

SeekableStream::~SeekableStream() {
  if (strm_init_) inflateEnd(&strm_);
  if (file_) std::fclose(file_);
}

uint64_t SeekableStream::compressedPosition() const {
  return gzip_ ? in_total_ - strm_.avail_in : out_total_;
}

void SeekableStream::restartAt(const GzAccessPoint* p) {
  if (strm_init_) inflateEnd(&strm_);
  strm_ = z_stream{};
  raw_mode_ = p != nullptr;
  if (inflateInit2(&strm_, raw_mode_ ? kRaw : kGzipAuto) != Z_OK)
    throw std::runtime_error("zlib: inflateInit2 failed");
  strm_init_ = true;
  at_end_ = false;
  have_ = rd_ = 0;
  const uint64_t in = p ? p->in - (p->bits ? 1 : 0) : 0;
  fseeko(file_, off_t(in), SEEK_SET);
  in_total_ = in;
  out_total_ = p ? p->out : 0;
    if (!p) return;
  if (p->bits) {
    const int c = std::fgetc(file_);
    if (c == EOF) throw std::runtime_error(path_ + ": access point beyond the end of the file");
    ++in_total_;
    inflatePrime(&strm_, p->bits, c >> (8 - p->bits));
  }
  std::vector<uint8_t> window(kWindow);
  uLongf len = kWindow;
  if (uncompress(window.data(), &len, p->window_z.data(), uLong(p->window_z.size())) != Z_OK ||
      len != kWindow)
    throw std::runtime_error(path_ + ": bad access point dictionary");
  inflateSetDictionary(&strm_, window.data(), kWindow);
}

// Inflates into the circular 32 KiB window (zran.c's scheme: the window is the output buffer, so
// at a block boundary its content is the dictionary). Returns false at the end or on damage.
bool SeekableStream::inflateMore() {
  if (at_end_) return false;
  if (have_ == kWindow) have_ = rd_ = 0;
  for (;;) {
    if (strm_.avail_in == 0) {
      const std::size_t n = std::fread(in_buf_.data(), 1, kChunk, file_);
      if (n == 0) {
        if (damage_.empty())
          damage_ = "compressed stream cut short at compressed byte " + std::to_string(in_total_);
        at_end_ = true;
        return false;
      }
      in_total_ += n;
      strm_.next_in = in_buf_.data();
      strm_.avail_in = uInt(n);
    }
    strm_.next_out = win_.data() + have_;
    strm_.avail_out = uInt(kWindow - have_);
    const int ret = inflate(&strm_, Z_BLOCK);
    const std::size_t produced = (kWindow - have_) - strm_.avail_out;
    have_ += produced;
    out_total_ += produced;
    if (ret == Z_NEED_DICT || ret == Z_DATA_ERROR || ret == Z_MEM_ERROR) {
      damage_ = "corrupt compressed data at compressed byte " + std::to_string(compressedPosition()) +
                " (" + (strm_.msg ? strm_.msg : "zlib error") + ")";
      at_end_ = true;
      return produced > 0;
    }
    if (ret == Z_STREAM_END) {
      if (raw_mode_) {  // skip the member's 8-byte trailer; the next member has a gzip header
        uint8_t trailer[8];
        std::size_t need = 8;
        while (need > 0) {
          if (strm_.avail_in == 0) {
            const std::size_t n = std::fread(in_buf_.data(), 1, kChunk, file_);
            if (n == 0) break;
            in_total_ += n;
            strm_.next_in = in_buf_.data();
            strm_.avail_in = uInt(n);
          }
          const std::size_t k = std::min<std::size_t>(need, strm_.avail_in);
          std::memcpy(trailer, strm_.next_in, k);
          strm_.next_in += k;
          strm_.avail_in -= uInt(k);
          need -= k;
        }
        inflateReset2(&strm_, kGzipAuto);
        raw_mode_ = false;
      } else {
        inflateReset(&strm_);
      }
      // another member follows only when bytes are left
      if (strm_.avail_in == 0) {
        const std::size_t n = std::fread(in_buf_.data(), 1, kChunk, file_);
        in_total_ += n;
        strm_.next_in = in_buf_.data();
        strm_.avail_in = uInt(n);
        if (n == 0) {
          at_end_ = true;
          return produced > 0;
        }
      }
    } else if (span_ > 0 && (strm_.data_type & 128) && !(strm_.data_type & 64) &&
               out_total_ >= kWindow &&  // the window holds a full history
               (points_.empty() || out_total_ > points_.back().out) &&  // not re-reading after a seek back
               out_total_ - (points_.empty() ? 0 : points_.back().out) >= span_) {
      // a block boundary (not the last block): an access point (zran.c addpoint)
      GzAccessPoint p;
      p.out = out_total_;
      p.in = in_total_ - strm_.avail_in;
      p.bits = strm_.data_type & 7;
      std::vector<uint8_t> window(kWindow);
      const std::size_t left = strm_.avail_out;  // window bytes after the newest output
      if (left) std::memcpy(window.data(), win_.data() + kWindow - left, left);
      if (left < kWindow) std::memcpy(window.data() + left, win_.data(), kWindow - left);
      uLongf zlen = compressBound(kWindow);
      p.window_z.resize(zlen);
      compress2(p.window_z.data(), &zlen, window.data(), kWindow, 1);
      p.window_z.resize(zlen);
      points_.push_back(std::move(p));
    }
    if (produced > 0 || have_ == kWindow) return true;
  }
}

size_t SeekableStream::Read(void* buffer, size_t count) {
  if (!gzip_) {
    const std::size_t n = std::fread(buffer, 1, count, file_);
    out_total_ += n;
    return n;
  }
  auto* dst = static_cast<uint8_t*>(buffer);
  std::size_t done = 0;
  while (done < count) {
    if (rd_ == have_ && !inflateMore()) break;
    const std::size_t k = std::min(count - done, have_ - rd_);
    std::memcpy(dst + done, win_.data() + rd_, k);
    rd_ += k;
    done += k;
  }
  return done;
}

void SeekableStream::skipForward(uint64_t n) {
  uint8_t scratch[8192];
  while (n > 0) {
    const std::size_t k = Read(scratch, std::size_t(std::min<uint64_t>(n, sizeof scratch)));
    if (k == 0) return;
    n -= k;
  }
}

uint64_t SeekableStream::Seek(int64_t offset, CStream::TSeekOrigin origin) {
  uint64_t target = origin == sFromCurrent ? uint64_t(int64_t(getPosition()) + offset)
                                           : uint64_t(offset);
  if (origin == sFromEnd) throw std::runtime_error("SeekableStream: sFromEnd is not supported");
  if (!gzip_) {
    fseeko(file_, off_t(target), SEEK_SET);
    out_total_ = target;
    return target;
  }
  const uint64_t pos = getPosition();
  // the last access point at or before the target, else the start of the file
  const auto it = std::upper_bound(points_.begin(), points_.end(), target,
                                   [](uint64_t t, const GzAccessPoint& p) { return t < p.out; });
  const GzAccessPoint* p = it == points_.begin() ? nullptr : &*(it - 1);
  const bool read_on = target >= pos && (!p || p->out <= pos);  // no closer restart point
  if (!read_on) {
    restartAt(p);
    damage_.clear();
  }
  skipForward(target - getPosition());
  return getPosition();
}

}  // namespace roadslam::rawlog::detail
