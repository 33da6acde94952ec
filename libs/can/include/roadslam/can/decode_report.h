#pragma once
/// \file decode_report.h
/// Decoded signals of a log as text, CSV or JSON lines (`roadslam-can decode`).

#include <roadslam/can/candump.h>
#include <roadslam/can/decoder.h>

#include <iosfwd>
#include <string>

namespace roadslam::can {

enum class DecodeFormat { kText, kCsv, kJsonLines };

/// Counts of a decode run, per DecodeStatus.
struct DecodeCounts {
  std::size_t frames = 0, decoded = 0, unknown_id = 0, dlc_mismatch = 0, short_frame = 0, not_data = 0;
  std::string summary() const;  ///< one line
};

/// Decodes every frame of \p reader with \p decoder and writes one record per decoded frame:
///  text: "(t) iface MESSAGE SIG=value unit ..."; CSV: header t_s,iface,id,message,signal,value,unit
///  (one row per signal); JSON lines: {"t":..,"iface":..,"id":"0AA","message":..,"signals":{..}}.
/// NaN (multiplexed away, beyond the payload) signals are omitted.
DecodeCounts decodeLog(CandumpReader& reader, const Decoder& decoder, DecodeFormat format, std::ostream& out);

}  // namespace roadslam::can
