// gpsd client over libgps (gps.h, API 11 in Debian 12's gpsd 3.22): WATCH_NMEA makes gpsd relay each
// receiver sentence as one line ("NMEA" in gpsd_json(5)); the JSON lines it also sends (VERSION,
// DEVICES, WATCH, ERROR) start with '{'.
#include <gps.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "roadslam/sources/nmea_source.h"

namespace roadslam::sources {

struct GpsdNmeaSource::Impl {
  gps_data_t data{};
  bool open = false;
};

GpsdNmeaSource::GpsdNmeaSource(const std::string& host, int port, const std::string& device)
    : impl_(std::make_unique<Impl>()), where_(host + ":" + std::to_string(port) + (device.empty() ? "" : " " + device)) {
  const std::string port_text = std::to_string(port);
  if (gps_open(host.c_str(), port_text.c_str(), &impl_->data) != 0)
    throw std::runtime_error("gpsd at " + host + ":" + port_text + ": " + gps_errstr(errno) +
                             " (is gpsd running? systemctl status gpsd)");
  impl_->open = true;
  unsigned flags = WATCH_ENABLE | WATCH_NMEA;
  if (!device.empty()) flags |= WATCH_DEVICE;
  if (gps_stream(&impl_->data, flags, device.empty() ? nullptr : const_cast<char*>(device.c_str())) != 0) {
    gps_close(&impl_->data);
    impl_->open = false;
    throw std::runtime_error("gpsd at " + host + ":" + port_text + ": cannot start the NMEA watch");
  }
}

GpsdNmeaSource::~GpsdNmeaSource() {
  if (impl_->open) {
    gps_stream(&impl_->data, WATCH_DISABLE, nullptr);
    gps_close(&impl_->data);
  }
}

NmeaRead GpsdNmeaSource::read(NmeaLine& out, int timeout_ms) {
  if (!impl_->open) return NmeaRead::End;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const auto left_us =
        std::chrono::duration_cast<std::chrono::microseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (!gps_waiting(&impl_->data, static_cast<int>(std::max<long long>(0, left_us)))) return NmeaRead::Timeout;
    char msg[1024];
    errno = 0;
    if (gps_read(&impl_->data, msg, sizeof msg) < 0) {  // gpsd gone (or its socket closed)
      error_ = "gpsd at " + where_ + ": connection lost" + (errno ? std::string(" (") + std::strerror(errno) + ")" : "");
      gps_close(&impl_->data);
      impl_->open = false;
      return NmeaRead::End;
    }
    out.receive_s =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    out.text = msg;
    while (!out.text.empty() && (out.text.back() == '\n' || out.text.back() == '\r')) out.text.pop_back();
    if (out.text.empty()) continue;
    if (out.text[0] == '{') {
      ++json_lines_;
      continue;
    }
    return NmeaRead::Line;
  }
}

}  // namespace roadslam::sources
