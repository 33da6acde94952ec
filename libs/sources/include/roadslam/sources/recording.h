#pragma once
/// \file recording.h
/// Whole-recording operations behind the roadslam-rawlog app: open a .pcap or MRPT .rawlog as a
/// PacketSource, summarise it through the decoder and sweep assembler, convert it to a rawlog.
/// File-level problems (missing, empty, not a capture, no Velodyne data) throw std::runtime_error
/// with a one-line message naming the file. A recording damaged part way (a capture cut by a power
/// loss) is read up to the damage, which the result states in damageWarning()'s words.

#include <memory>
#include <string>
#include <vector>

#include "roadslam/sources/packet_source.h"
#include "roadslam/rawlog/rawlog_writer.h"
#include "roadslam/velodyne/decoder_params.h"

namespace roadslam::sources {

/// Opens \p path by content (pcap / pcapng magic, else an MRPT rawlog).
std::unique_ptr<PacketSource> openRecording(const std::string& path, const PortConfig& ports = {});

struct RecordingSummary {
  std::string path;
  std::string format;              ///< "pcap" or "rawlog"
  std::string model;               ///< decoder model of the first data packet (vlp16, hdl32)
  std::string lidar_model;         ///< the model decoded, "VLP-16" / "HDL-32E" / "unknown" (model_choice.h)
  std::string lidar_model_source;  ///< "ini" (here: --model), "packet layout" or "product byte"
  std::string lidar_layout;        ///< what the packets' layout says (velodyne::LayoutVerdict::describe)
  std::vector<std::string> warnings;  ///< the model choice's warning, when the layout disagrees
  uint64_t sweeps = 0;             ///< complete sweeps (one full turn, wrap to wrap) [count]
  uint64_t partial_sweeps = 0;     ///< first / last incomplete sweeps [count]
  uint64_t packets = 0;            ///< Velodyne data packets [count]
  uint64_t position_packets = 0;   ///< position packets or GPS records [count]
  uint64_t points = 0;             ///< decoded points in all sweeps [count]
  uint64_t gps_fixes = 0;          ///< decodable $GPRMC fixes [count]
  uint64_t malformed_packets = 0;  ///< wrong size on a Velodyne port, or undecodable [count]
  uint64_t skipped_packets = 0;    ///< other traffic / records [count]
  uint64_t missing_packets = 0;    ///< gaps in the sensor's packet clock [count]
  double duration_s = 0;           ///< first to last data packet stamp [s]
  double sweeps_per_s = 0;         ///< rotation rate from wrap-to-wrap sweep stamps [1/s]
  double packets_per_s = 0;        ///< data packet rate over duration_s [1/s]
  std::string damage;              ///< damageWarning() of the recording; empty when it read whole
};

/// Reads the whole recording once, up to its damage. Throws (naming the file) when no Velodyne data
/// packet comes before the end or the damage. \p force_setting: how the user forces the model, for
/// the warning's advice.
RecordingSummary summarizeRecording(const std::string& path, const velodyne::DecoderParams& params = {},
                                    const std::string& force_setting = "--model");

/// `--json` output: an object with the RecordingSummary field names as keys.
std::string toJson(const RecordingSummary& s);
/// Human-readable multi-line report.
std::string toText(const RecordingSummary& s);

struct ConvertSummary {
  uint64_t observations = 0;  ///< CObservationVelodyneScan records written (one per sweep) [count]
  uint64_t packets = 0;       ///< data packets stored [count]
  uint64_t gps = 0;           ///< CObservationGPS records written [count]
  std::string lidar_model;    ///< the model decoded and written as the calibration (RecordingSummary)
  std::string lidar_model_source;
  std::vector<std::string> warnings;  ///< the model choice's warning, when the layout disagrees
  std::string damage;         ///< damageWarning() of the input; empty when it read whole
};

/// Converts \p in (.pcap or .rawlog), up to its damage, to the MRPT rawlog \p out (throws naming \p in
/// when no Velodyne data packet comes before the end or the damage): one CObservationVelodyneScan per
/// sweep as cut by the assembler (a packet in which a sweep ends opens the next observation, so
/// every packet is stored exactly once, unchanged), one CObservationGPS per RMC position packet.
/// \p writer_params.model / calibration_file default from \p params when empty; the model written is
/// the one decoded (model_choice.h: the packet layout over a disagreeing product byte).
/// The configuration actually used is written next to the output as "<out>.ini" (sections
/// [velodyne] = DecoderParams, [rawlog] = RawlogWriter::Params), loadable by both Params.
ConvertSummary convertToRawlog(const std::string& in, const std::string& out,
                               const velodyne::DecoderParams& params = {},
                               rawlog::RawlogWriter::Params writer_params = {},
                               const std::string& force_setting = "--model");

}  // namespace roadslam::sources
