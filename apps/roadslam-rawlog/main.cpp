// roadslam-rawlog: summarise and convert Velodyne recordings (.pcap, MRPT .rawlog); regenerate
// the bundled box-room capture. All logic lives in libs/sources; see docs/apps/roadslam-rawlog.md.
#include <CLI/CLI.hpp>
#include <mrpt/config/CConfigFileMemory.h>
#include <fmt/core.h>

#include <exception>
#include <memory>
#include <string>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/cli.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/sources/boxroom.h"
#include "roadslam/rawlog/rawlog_writer.h"
#include "roadslam/sources/nmea_source.h"
#include "roadslam/sources/recorder.h"
#include "roadslam/sources/recording.h"
#include "roadslam/sources/udp_receiver.h"

namespace {
struct DecoderOptions {
  std::string model = "auto";
  std::string calibration;
  void addTo(CLI::App* cmd) {
    cmd->add_option("--model", model, "force the sensor model (some VLP-16s report 0x21)")
        ->check(CLI::IsMember({"auto", "vlp16", "hdl32"}));
    cmd->add_option("--calibration", calibration, "VeloView/Velodyne calibration XML");
  }
  roadslam::velodyne::DecoderParams params() const {
    roadslam::velodyne::DecoderParams p;
    p.model = roadslam::velodyne::parseModel(model);
    p.calibration_file = calibration;
    return p;
  }
};
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Summarise and convert Velodyne recordings (.pcap, MRPT .rawlog)"};
  roadslam::addVersionFlag(app, "roadslam-rawlog");
  app.require_subcommand(1);

  std::string info_in;
  bool json = false;
  DecoderOptions info_opt;
  auto* info = app.add_subcommand("info", "Sweeps, packets, points, duration, rates, GPS fixes");
  info->add_option("FILE,--input", info_in, ".pcap or .rawlog")->required();
  info->add_flag("--json", json, "machine-readable output");
  info_opt.addTo(info);

  std::string conv_in, conv_out;
  DecoderOptions conv_opt;
  auto* conv = app.add_subcommand("convert", "pcap -> MRPT rawlog (CObservationVelodyneScan per sweep)");
  conv->add_option("IN,--input", conv_in, "input .pcap (or .rawlog)")->required();
  conv->add_option("OUT,--out", conv_out, "output .rawlog")->required();
  bool conv_quiet = false;
  conv->add_flag("--quiet", conv_quiet, "nothing on stdout; errors and warnings on stderr");
  conv_opt.addTo(conv);

  std::string rec_out;
  roadslam::sources::UdpReceiver::Params udp;
  roadslam::sources::RecordLimits limits;
  auto* rec = app.add_subcommand("record", "Live capture from the sensor's UDP ports into a .pcap (Ctrl-C stops)");
  rec->add_option("OUT,--out", rec_out, "output .pcap")->required();
  rec->add_option("--duration,--seconds", limits.duration_s, "stop after this long [s] (0 = until Ctrl-C)");
  rec->add_option("--packets", limits.max_packets, "stop after this many packets (0 = no limit)");
  rec->add_option("--port", udp.ports.data_port, "data port")->capture_default_str();
  rec->add_option("--position-port", udp.ports.position_port, "position port")->capture_default_str();
  rec->add_option("--bind", udp.bind_address, "local IPv4 address to listen on (default: all)");
  rec->add_option("--source", udp.source_filter, "accept only this sensor IPv4 address");

  std::string nmea_in, nmea_out, nmea_label = "GPS";
  auto* nmea = app.add_subcommand("nmea", "NMEA 0183 log -> MRPT rawlog (CObservationGPS per receiver epoch)");
  nmea->add_option("IN", nmea_in, "NMEA log: one sentence per line, optionally after its receive time [s]")
      ->required()->check(CLI::ExistingFile);
  nmea->add_option("OUT", nmea_out, "output .rawlog")->required();
  nmea->add_option("--label", nmea_label, "sensorLabel of the observations")->capture_default_str();

  std::string gnss_out, gnss_device, gnss_replay, gnss_rawlog;
  int gnss_baud = 9600;
  std::size_t gnss_lines = 0;
  double gnss_speed = 0;
  auto* grec = app.add_subcommand("record-gnss", "NMEA 0183 receiver (serial port, or a log replayed) into an NMEA log "
                                                 "and optionally a rawlog (Ctrl-C stops)");
  grec->add_option("OUT", gnss_out, "output NMEA log (receive time + sentence per line)")->required();
  auto* dev_opt = grec->add_option("--device", gnss_device, "serial device, e.g. /dev/ttyUSB0");
  grec->add_option("--baud", gnss_baud, "serial baud rate")->capture_default_str();
  auto* rep_opt = grec->add_option("--replay", gnss_replay, "an NMEA log to replay instead of a device")->check(CLI::ExistingFile);
  grec->add_option("--speed", gnss_speed, "replay pace (1 = real time, 0 = at once)")->capture_default_str();
  grec->add_option("--rawlog", gnss_rawlog, "also write the valid epochs as CObservationGPS into this rawlog");
  grec->add_option("--lines", gnss_lines, "stop after this many lines (0 = until the source ends or Ctrl-C)");
  dev_opt->excludes(rep_opt);

  std::string box_out;
  auto* box = app.add_subcommand("make-boxroom", "Write the deterministic box-room VLP-16 capture");
  box->add_option("OUT", box_out, "output .pcap (bundled: rawlogs/boxroom-vlp16.pcap)")->required();

  roadslam::warnOldSpellings(argc, argv, "roadslam-rawlog", {{"--seconds", "--duration"}});
  CLI11_PARSE(app, argc, argv);
  using namespace roadslam::sources;
  using namespace roadslam::rawlog;
  try {
    if (*info) {
      const RecordingSummary s = summarizeRecording(info_in, info_opt.params());
      fmt::print("{}", json ? toJson(s) + "\n" : toText(s));
      for (const auto& w : s.warnings) fmt::print(stderr, "roadslam-rawlog: warning: {}\n", w);
      if (!s.damage.empty()) fmt::print(stderr, "roadslam-rawlog: warning: {}\n", s.damage);
    } else if (*conv) {
      const ConvertSummary s = convertToRawlog(conv_in, conv_out, conv_opt.params());
      if (!conv_quiet)
        fmt::print("{}: {} sweeps ({} packets), {} GPS records; lidar model {} (by {})\n", conv_out, s.observations,
                   s.packets, s.gps, s.lidar_model, s.lidar_model_source);
      for (const auto& w : s.warnings) fmt::print(stderr, "roadslam-rawlog: warning: {}\n", w);
      if (!s.damage.empty()) fmt::print(stderr, "roadslam-rawlog: warning: {}\n", s.damage);
    } else if (*rec) {
      roadslam::installStopSignalHandlers();  // Ctrl-C ends the recording cleanly; a second one at once
      UdpReceiver rx(udp);
      const RecordSummary r = recordToPcap(rx, rec_out, limits);
      mrpt::config::CConfigFileMemory used;  // the configuration used, next to the output
      udp.saveToConfigFile(used, "udp");
      roadslam::writeFileAtomically(rec_out + ".ini", used.getContent());
      fmt::print("{}: {} packets ({} data, {} position); kernel drops {}, missing {}, malformed {}, "
                 "SO_RCVBUF granted {} bytes\n",
                 rec_out, r.packets, r.source.data_packets, r.source.position_packets,
                 r.source.kernel_drops, r.source.missing_packets, r.source.malformed_packets,
                 rx.grantedRcvbufBytes());
    } else if (*nmea) {
      const NmeaImportSummary s = nmeaLogToRawlog(nmea_in, nmea_out, nmea_label);
      std::string counts;
      for (const auto& [name, n] : s.counters.named())
        if (n > 0 && name != "lines" && name != "sentences" && name != "epochs" && name != "fixes")
          counts += fmt::format(", {} {}", n, name);
      fmt::print("{}: {} GNSS epochs from {} lines{}\n", nmea_out, s.epochs, s.counters.lines, counts);
      for (const auto& p : s.problems) fmt::print(stderr, "roadslam-rawlog: warning: {}\n", p);
    } else if (*grec) {
      if (gnss_device.empty() && gnss_replay.empty()) throw std::runtime_error("record-gnss needs --device or --replay");
      roadslam::installStopSignalHandlers();
      std::unique_ptr<NmeaSource> src;
      if (!gnss_device.empty()) src = std::make_unique<SerialNmeaSource>(gnss_device, gnss_baud);
      else src = std::make_unique<NmeaLogReplaySource>(gnss_replay, gnss_speed);
      const NmeaRecordSummary r = recordNmea(*src, gnss_out, gnss_rawlog, gnss_lines);
      fmt::print("{}: {} lines from {}{}\n", gnss_out, r.lines, src->describe(),
                 gnss_rawlog.empty() ? "" : fmt::format(", {} GNSS epochs in {}", r.epochs, gnss_rawlog));
      if (!r.error.empty()) fmt::print(stderr, "roadslam-rawlog: warning: {}\n", r.error);
    } else if (*box) {
      const BoxRoomSummary s = writeBoxRoomPcap(box_out);
      fmt::print("{}: {} data packets, {} position packets, {} points, {} complete sweeps\n",
                 box_out, s.data_packets, s.position_packets, s.points, s.complete_sweeps);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "roadslam-rawlog: {}\n", e.what());
    return 1;
  }
  return 0;
}
