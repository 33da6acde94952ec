#include "roadslam/viewer/live_feed.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <stdexcept>

namespace roadslam::viewer {

grabber::GrabParams liveParams(const LiveRequest& req) {
  if ((req.udp_port >= 0) == !req.grab_ini.empty())
    throw std::invalid_argument("a live view takes one of --udp PORT or --grab INI");
  if (!req.grab_ini.empty()) return grabber::GrabParams::fromFile(req.grab_ini);
  if (req.udp_port > 65535) throw std::runtime_error("--udp " + std::to_string(req.udp_port) + ": not a UDP port");
  // The factory's pair of ports (VLP-16 manual, 9.1): position packets come with data on 2368.
  const int position = req.udp_port == 2368 ? 8308 : 0;
  const std::string ini = "[grab]\nsensors = velodyne\ncan =\n[velodyne]\ndata_port = " +
                          std::to_string(req.udp_port) + "\nposition_port = " + std::to_string(position) +
                          "\nmodel = vlp16\nsensor_label = VELODYNE\ngps_label = VELODYNE_GPS\n";
  mrpt::config::CConfigFileMemory cfg(ini);
  grabber::GrabParams p;
  p.loadFromConfigFile(cfg);
  return p;
}

LiveFeed::LiveFeed(const LiveRequest& req, sources::LiveObservations& sink, grabber::ObservationTap also) {
  const auto params = liveParams(req);
  grabber_ = std::make_unique<grabber::Grabber>(params, req.record_dir);
  grabber_->setObservationTap([&sink, also](const std::shared_ptr<mrpt::obs::CObservation>& o) {
    sink.post(o);
    if (also) also(o);
  });
  if (req.grab_ini.empty()) name_ = "UDP port " + std::to_string(grabber_->dataPort(0));
  else name_ = "grab ini " + req.grab_ini;
  if (!req.record_dir.empty()) name_ += ", recording into " + req.record_dir;
  grabber_->start();
}

LiveFeed::~LiveFeed() {
  try {
    stop();
  } catch (...) {
  }
}

void LiveFeed::stop() { grabber_->stop(); }

std::string LiveFeed::statusLine() { return grabber::Grabber::formatStatus(grabber_->status()); }

}  // namespace roadslam::viewer
