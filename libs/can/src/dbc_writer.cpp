// DBC writer: emits the subset parseDbc() reads, in Vector's statement order, so that
// parseDbc(writeDbc(db)) == db.

#include <roadslam/can/dbc.h>
#include <roadslam/common/atomic_file.h>

#include <charconv>
#include <cmath>
#include <sstream>

namespace roadslam::can {
namespace {

// Shortest text that reads back to the same double (C++17 to_chars round-trip guarantee).
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

std::string muxIndicator(const Signal& s) {
  switch (s.mux) {
    case MuxRole::kMultiplexor: return " M";
    case MuxRole::kMultiplexed: return " m" + std::to_string(s.mux_value) + (s.also_multiplexor ? "M" : "");
    case MuxRole::kNone: break;
  }
  return "";
}

void writeSignal(std::ostream& o, const Signal& s) {
  o << " SG_ " << s.name << muxIndicator(s) << " : " << s.start_bit << '|' << s.length << '@'
    << (s.little_endian ? '1' : '0') << (s.is_signed ? '-' : '+') << " (" << num(s.factor) << ','
    << num(s.offset) << ") [" << num(s.minimum) << '|' << num(s.maximum) << "] " << quoted(s.unit) << ' ';
  if (s.receivers.empty()) o << "Vector__XXX";
  for (std::size_t i = 0; i < s.receivers.size(); ++i) o << (i ? "," : "") << s.receivers[i];
  o << '\n';
}

void writeValues(std::ostream& o, const std::map<std::int64_t, std::string>& vals) {
  for (auto it = vals.rbegin(); it != vals.rend(); ++it) o << ' ' << it->first << ' ' << quoted(it->second);
  o << " ;\n";
}

void writeComments(std::ostream& o, const Database& db) {
  for (const auto& c : db.comments) o << "CM_ " << quoted(c) << ";\n";
  for (const auto& [node, c] : db.node_comments) o << "CM_ BU_ " << node << ' ' << quoted(c) << ";\n";
  for (const Message& m : db.messages) {
    if (!m.comment.empty()) o << "CM_ BO_ " << m.dbc_id << ' ' << quoted(m.comment) << ";\n";
    for (const Signal& s : m.signals) {
      if (!s.comment.empty()) o << "CM_ SG_ " << m.dbc_id << ' ' << s.name << ' ' << quoted(s.comment) << ";\n";
    }
  }
}

void writeAttributes(std::ostream& o, const Database& db) {
  for (const auto& d : db.attribute_defs) {
    o << "BA_DEF_ " << (d.object.empty() ? "" : d.object + " ") << quoted(d.name) << ' ' << d.type_spec << ";\n";
  }
  for (const auto& [name, v] : db.attribute_defaults) o << "BA_DEF_DEF_ " << quoted(name) << ' ' << v << ";\n";
  for (const auto& a : db.attributes) {
    o << "BA_ " << quoted(a.name) << ' ';
    if (!a.object.empty()) o << a.object << ' ' << a.target << ' ';
    o << a.value << ";\n";
  }
}

}  // namespace

std::string writeDbc(const Database& db) {
  std::ostringstream o;
  o << "VERSION " << quoted(db.version) << "\n\n\nNS_ :\n\tCM_\n\tBA_DEF_\n\tBA_\n\tVAL_\n\tBA_DEF_DEF_\n"
    << "\tVAL_TABLE_\n\tSIG_VALTYPE_\n\nBS_:\n\nBU_:";
  for (const auto& n : db.nodes) o << ' ' << n;
  o << "\n\n";
  for (const auto& [name, vals] : db.value_tables) {
    o << "VAL_TABLE_ " << name;
    writeValues(o, vals);
  }
  for (const Message& m : db.messages) {
    o << "\nBO_ " << m.dbc_id << ' ' << m.name << ": " << m.size << ' ' << m.transmitter << '\n';
    for (const Signal& s : m.signals) writeSignal(o, s);
  }
  o << '\n';
  writeComments(o, db);
  writeAttributes(o, db);
  for (const Message& m : db.messages) {
    for (const Signal& s : m.signals) {
      if (s.value_descriptions.empty()) continue;
      o << "VAL_ " << m.dbc_id << ' ' << s.name;
      writeValues(o, s.value_descriptions);
    }
  }
  for (const Message& m : db.messages) {
    for (const Signal& s : m.signals) {
      if (s.value_type != ValueType::kInteger) {
        o << "SIG_VALTYPE_ " << m.dbc_id << ' ' << s.name << " : " << static_cast<int>(s.value_type) << ";\n";
      }
    }
  }
  return o.str();
}

void saveDbcFile(const std::string& path, const Database& db) { writeFileAtomically(path, writeDbc(db)); }

bool Signal::operator==(const Signal& o) const {
  return name == o.name && start_bit == o.start_bit && length == o.length && little_endian == o.little_endian &&
         is_signed == o.is_signed && factor == o.factor && offset == o.offset && minimum == o.minimum &&
         maximum == o.maximum && unit == o.unit && receivers == o.receivers && mux == o.mux &&
         mux_value == o.mux_value && also_multiplexor == o.also_multiplexor && value_type == o.value_type &&
         value_descriptions == o.value_descriptions && comment == o.comment;
}

bool Message::operator==(const Message& o) const {
  return dbc_id == o.dbc_id && name == o.name && size == o.size && transmitter == o.transmitter &&
         signals == o.signals && comment == o.comment;
}

const Signal* Message::findSignal(const std::string& n) const {
  for (const Signal& s : signals) {
    if (s.name == n) return &s;
  }
  return nullptr;
}

bool Database::operator==(const Database& o) const {
  return version == o.version && nodes == o.nodes && messages == o.messages && comments == o.comments &&
         node_comments == o.node_comments && value_tables == o.value_tables &&
         attribute_defs == o.attribute_defs && attribute_defaults == o.attribute_defaults &&
         attributes == o.attributes;
}

const Message* Database::findMessage(std::uint32_t dbc_id) const {
  for (const Message& m : messages) {
    if (m.dbc_id == dbc_id) return &m;
  }
  return nullptr;
}

const Message* Database::findMessage(const std::string& n) const {
  for (const Message& m : messages) {
    if (m.name == n) return &m;
  }
  return nullptr;
}

}  // namespace roadslam::can
