#include "roadslam/sources/nmea_source.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/gnss/nmea.h"
#include "roadslam/rawlog/rawlog_writer.h"

namespace roadslam::sources {
namespace {

double wallNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

speed_t baudConstant(int baud) {
  switch (baud) {
    case 4800: return B4800;
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
  }
  throw std::runtime_error("serial baud rate " + std::to_string(baud) +
                           " not supported (4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600)");
}

}  // namespace

SerialNmeaSource::SerialNmeaSource(const std::string& device, int baud) : device_(device) {
  const speed_t speed = baudConstant(baud);
  fd_ = ::open(device.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error("GNSS serial '" + device + "': " + std::strerror(errno));
  termios tio{};
  if (::tcgetattr(fd_, &tio) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error("GNSS serial '" + device + "': not a terminal (" + why + ")");
  }
  ::cfmakeraw(&tio);  // 8N1, no echo, no line editing: bytes as sent
  tio.c_cflag |= CLOCAL | CREAD;
  ::cfsetispeed(&tio, speed);
  ::cfsetospeed(&tio, speed);
  if (::tcsetattr(fd_, TCSANOW, &tio) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error("GNSS serial '" + device + "': cannot set " + std::to_string(baud) + " 8N1 (" + why + ")");
  }
}

SerialNmeaSource::~SerialNmeaSource() {
  if (fd_ >= 0) ::close(fd_);
}

NmeaRead SerialNmeaSource::read(NmeaLine& out, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const size_t lf = buffer_.find('\n');
    if (lf != std::string::npos) {
      out.text = buffer_.substr(0, lf);
      buffer_.erase(0, lf + 1);
      while (!out.text.empty() && out.text.back() == '\r') out.text.pop_back();
      out.receive_s = wallNow();
      if (out.text.empty()) continue;
      return NmeaRead::Line;
    }
    if (fd_ < 0) return NmeaRead::End;
    const int left = static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                          deadline - std::chrono::steady_clock::now())
                                          .count());
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, std::max(0, left));
    if (r < 0 && errno == EINTR) return NmeaRead::Timeout;
    if (r == 0) return NmeaRead::Timeout;
    char buf[512];
    const ssize_t n = r > 0 ? ::read(fd_, buf, sizeof buf) : -1;
    if (n > 0) {
      buffer_.append(buf, static_cast<size_t>(n));
      if (buffer_.size() > max_line_ && buffer_.find('\n') == std::string::npos) buffer_.clear();  // noise
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    error_ = n == 0 || (p.revents & POLLHUP) ? "GNSS serial '" + device_ + "': hung up"
                                              : "GNSS serial '" + device_ + "': " + std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    return NmeaRead::End;
  }
}

NmeaLogReplaySource::NmeaLogReplaySource(const std::string& path, double speed) : path_(path), speed_(speed) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open NMEA log '" + path + "'");
  std::string line;
  double last = 0;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
    if (line.empty()) continue;
    NmeaLine l{last, line};
    if (line[0] != '$') {
      char* end = nullptr;
      const double v = std::strtod(line.c_str(), &end);
      if (end != line.c_str() && *end == ' ') {
        l.receive_s = last = v;
        l.text = line.substr(static_cast<size_t>(end - line.c_str()) + 1);
      }
    }
    lines_.push_back(std::move(l));
  }
}

NmeaRead NmeaLogReplaySource::read(NmeaLine& out, int timeout_ms) {
  if (next_ >= lines_.size()) return NmeaRead::End;
  if (speed_ > 0) {
    if (wall0_ < 0) {
      wall0_ = wallNow();
      t0_ = lines_[next_].receive_s;
    }
    const double due = wall0_ + (lines_[next_].receive_s - t0_) / speed_;
    const double wait = due - wallNow();
    if (wait * 1000 > timeout_ms) {
      std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
      return NmeaRead::Timeout;
    }
    if (wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
  }
  out = lines_[next_++];
  return NmeaRead::Line;
}

NmeaRecordSummary recordNmea(NmeaSource& src, const std::string& log_path, const std::string& rawlog_path,
                             std::size_t max_lines, const std::string& label) {
  NmeaRecordSummary s;
  AtomicFile log(log_path);
  std::unique_ptr<rawlog::RawlogWriter> rawlog;
  if (!rawlog_path.empty()) {
    rawlog::RawlogWriter::Params p;
    p.gps_label = label;
    rawlog = std::make_unique<rawlog::RawlogWriter>(rawlog_path, p);
  }
  gnss::NmeaParser parser;
  auto take = [&](std::optional<gnss::GnssFix> f) {
    if (rawlog && f && f->valid() && f->has_position) rawlog->writeGnss(*f);
  };
  NmeaLine line;
  char stamp[32];
  while (!stopRequested() && (max_lines == 0 || s.lines < max_lines)) {
    const NmeaRead r = src.read(line, 100);
    if (r == NmeaRead::End) break;
    if (r != NmeaRead::Line) continue;
    std::snprintf(stamp, sizeof stamp, "%.6f ", line.receive_s);
    log.stream() << stamp << line.text << "\n";
    ++s.lines;
    take(parser.feed(line.text, line.receive_s));
  }
  take(parser.flush());
  s.error = src.errorMessage();
  log.commit();
  if (rawlog) {
    rawlog->close();
    s.epochs = rawlog->gpsWritten();
  }
  return s;
}

}  // namespace roadslam::sources
