#include <roadslam/can/decode_report.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <vector>

namespace roadslam::can {

std::string DecodeCounts::summary() const {
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "%zu frames: %zu decoded, %zu unknown id, %zu DLC mismatch, %zu short, %zu remote/error", frames,
                decoded, unknown_id, dlc_mismatch, short_frame, not_data);
  return buf;
}

DecodeCounts decodeLog(CandumpReader& reader, const Decoder& decoder, DecodeFormat format, std::ostream& out) {
  DecodeCounts c;
  std::vector<double> values(512);
  CanFrame f;
  char buf[64];
  if (format == DecodeFormat::kCsv) out << "t_s,iface,id,message,signal,value,unit\n";
  while (reader.next(f)) {
    ++c.frames;
    const MessagePlan* plan = nullptr;
    const DecodeStatus st = decoder.decode(f, values.data(), &plan);
    switch (st) {
      case DecodeStatus::kUnknownId: ++c.unknown_id; continue;
      case DecodeStatus::kNotData: ++c.not_data; continue;
      case DecodeStatus::kDlcMismatch: ++c.dlc_mismatch; break;
      case DecodeStatus::kShortFrame: ++c.short_frame; break;
      case DecodeStatus::kOk: break;
    }
    ++c.decoded;
    const Message& m = *plan->message;
    std::snprintf(buf, sizeof(buf), "%lld.%06lld", static_cast<long long>(f.t_us / 1000000),
                  static_cast<long long>(f.t_us % 1000000));
    const std::string t = buf;
    std::snprintf(buf, sizeof(buf), f.extended() ? "%08X" : "%03X", f.id);
    const std::string id = buf;
    nlohmann::json sig = nlohmann::json::object();
    if (format == DecodeFormat::kText) out << '(' << t << ") " << f.iface.data() << ' ' << m.name;
    for (std::size_t i = 0; i < plan->signals.size(); ++i) {
      if (std::isnan(values[i])) continue;
      const Signal& s = m.signals[plan->signal_index[i]];
      std::snprintf(buf, sizeof(buf), "%.10g", values[i]);
      if (format == DecodeFormat::kText) {
        out << ' ' << s.name << '=' << buf << (s.unit.empty() ? "" : " ") << s.unit;
      } else if (format == DecodeFormat::kCsv) {
        out << t << ',' << f.iface.data() << ',' << id << ',' << m.name << ',' << s.name << ',' << buf << ','
            << s.unit << '\n';
      } else {
        sig[s.name] = values[i];
      }
    }
    if (format == DecodeFormat::kText) {
      out << (st == DecodeStatus::kOk ? "" : std::string("  [") + toString(st) + "]") << '\n';
    } else if (format == DecodeFormat::kJsonLines) {
      nlohmann::json j{{"t", f.timeSeconds()}, {"iface", f.iface.data()}, {"id", id}, {"message", m.name},
                       {"signals", sig}};
      if (st != DecodeStatus::kOk) j["status"] = toString(st);
      out << j.dump() << '\n';
    }
  }
  return c;
}

}  // namespace roadslam::can
