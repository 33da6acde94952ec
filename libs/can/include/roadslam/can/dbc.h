#pragma once
/// \file dbc.h
/// A CAN database in the Vector DBC format: messages (BO_), signals (SG_) with Intel (@1) or
/// Motorola (@0) byte order, multiplexing (M / m<k>), value descriptions (VAL_), comments (CM_),
/// attributes (BA_DEF_, BA_DEF_DEF_, BA_), float signals (SIG_VALTYPE_) and 29-bit ids (bit 31 of the
/// BO_ id). parseDbc() then writeDbc() then parseDbc() gives an equal Database.

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace roadslam::can {

/// How the raw bits of a signal are read (SIG_VALTYPE_: 0 integer, 1 IEEE float, 2 IEEE double).
enum class ValueType : std::uint8_t { kInteger = 0, kFloat32 = 1, kFloat64 = 2 };

/// Multiplexing role of a signal (DBC "M", "m<k>", "m<k>M").
enum class MuxRole : std::uint8_t { kNone, kMultiplexor, kMultiplexed };

struct Signal {
  std::string name;
  std::uint32_t start_bit = 0;  ///< DBC start bit: LSB for Intel, MSB (sawtooth numbering) for Motorola
  std::uint32_t length = 0;     ///< [bits] 1..64
  bool little_endian = true;    ///< @1 Intel, @0 Motorola
  bool is_signed = false;       ///< '-' two's complement, '+' unsigned
  double factor = 1.0;          ///< physical = raw * factor + offset
  double offset = 0.0;          ///< [unit]
  double minimum = 0.0;         ///< [unit]
  double maximum = 0.0;         ///< [unit]
  std::string unit;
  std::vector<std::string> receivers;
  MuxRole mux = MuxRole::kNone;
  std::uint64_t mux_value = 0;   ///< for kMultiplexed: the multiplexor value selecting this signal
  bool also_multiplexor = false; ///< "m<k>M": multiplexed and itself a (nested) multiplexor
  ValueType value_type = ValueType::kInteger;
  std::map<std::int64_t, std::string> value_descriptions;  ///< VAL_
  std::string comment;                                      ///< CM_ SG_
  bool operator==(const Signal& o) const;
};

struct Message {
  std::uint32_t dbc_id = 0;  ///< id as written in the DBC (bit 31 set for 29-bit ids)
  std::string name;
  std::uint32_t size = 0;    ///< DLC in bytes as declared (0..64)
  std::string transmitter;
  std::vector<Signal> signals;
  std::string comment;       ///< CM_ BO_
  std::uint32_t id() const { return dbc_id & 0x1FFFFFFFU; }  ///< identifier without the flag
  bool extended() const { return (dbc_id & 0x80000000U) != 0; }
  const Signal* findSignal(const std::string& name) const;
  bool operator==(const Message& o) const;
};

/// BA_DEF_ / BA_DEF_DEF_ / BA_ are kept as text fields (object type, target, value), enough to
/// write them back unchanged; roadslam reads no attribute semantics.
struct AttributeDef {
  std::string object;     ///< "", "BU_", "BO_", "SG_", "EV_"
  std::string name;
  std::string type_spec;  ///< e.g. INT 0 65535, ENUM "a","b" (tokens joined by single spaces)
  bool operator==(const AttributeDef& o) const {
    return object == o.object && name == o.name && type_spec == o.type_spec;
  }
};
struct AttributeValue {
  std::string name;
  std::string object;  ///< "", "BU_", "BO_", "SG_", "EV_"
  std::string target;  ///< node name, message id, "id signal", env var name
  std::string value;   ///< number or quoted string, as a token
  bool operator==(const AttributeValue& o) const {
    return name == o.name && object == o.object && target == o.target && value == o.value;
  }
};

struct Database {
  std::string version;
  std::vector<std::string> nodes;  ///< BU_
  std::vector<Message> messages;
  std::vector<std::string> comments;  ///< network comments (CM_ "text";)
  std::map<std::string, std::string> node_comments;  ///< CM_ BU_ node "text";
  std::map<std::string, std::map<std::int64_t, std::string>> value_tables;  ///< VAL_TABLE_
  std::vector<AttributeDef> attribute_defs;
  std::vector<std::pair<std::string, std::string>> attribute_defaults;  ///< BA_DEF_DEF_ name, value
  std::vector<AttributeValue> attributes;
  std::size_t skipped_statements = 0;  ///< statements of kinds roadslam ignores (EV_, SIG_GROUP_, ...)
  /// Tolerated defects ("file:line:col: what"), e.g. a CM_ SG_ without signal name; not compared.
  std::vector<std::string> warnings;

  const Message* findMessage(std::uint32_t dbc_id) const;
  const Message* findMessage(const std::string& name) const;
  bool operator==(const Database& o) const;
};

/// Parse error naming the source, line and column (1-based).
class DbcError : public std::runtime_error {
 public:
  DbcError(const std::string& source, std::size_t line, std::size_t column, const std::string& what);
  std::size_t line, column;
};

Database parseDbc(const std::string& text, const std::string& source_name = "<string>");
Database loadDbcFile(const std::string& path);  ///< throws DbcError / std::runtime_error naming the file
std::string writeDbc(const Database& db);
void saveDbcFile(const std::string& path, const Database& db);

}  // namespace roadslam::can
