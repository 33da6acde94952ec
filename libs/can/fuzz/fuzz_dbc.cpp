// libFuzzer target: the DBC parser must never crash or hang, and whatever it accepts must survive
// write -> parse unchanged and be decodable.
#include <roadslam/can/dbc.h>
#include <roadslam/can/decoder.h>

#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  roadslam::can::Database db;
  try {
    db = roadslam::can::parseDbc(text, "fuzz.dbc");
  } catch (const std::runtime_error&) {
    return 0;  // rejected with a message: fine
  }
  const std::string written = roadslam::can::writeDbc(db);
  roadslam::can::Database again;
  try {
    again = roadslam::can::parseDbc(written, "rewritten.dbc");
  } catch (const std::exception&) {
    std::abort();  // the writer produced text the parser rejects
  }
  if (!(again == db)) std::abort();
  const roadslam::can::Decoder dec(std::move(db));
  roadslam::can::CanFrame f;
  f.len = 64;
  for (std::size_t i = 0; i < 64 && i < size; ++i) f.data[i] = data[i];
  double out[1024];
  for (const auto& plan : dec.plans()) {
    if (plan.signals.size() > 1024) continue;
    f.id = plan.message->id();
    f.flags = plan.message->extended() ? roadslam::can::kExtended : 0;
    (void)dec.decode(plan, f, out);
  }
  return 0;
}
