// DBC reader. Grammar after Vector's "DBC File Format Documentation" v1.0.5: sections 8 (BO_),
// 8.2 (SG_, multiplexer indicator), 12 (CM_), 13 (BA_DEF_/BA_), 14 (VAL_), SIG_VALTYPE_ (11.5).

#include "dbc_lexer.h"

#include <roadslam/can/dbc.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace roadslam::can {

DbcError::DbcError(const std::string& source, std::size_t l, std::size_t c, const std::string& what)
    : std::runtime_error(source + ":" + std::to_string(l) + ":" + std::to_string(c) + ": " + what),
      line(l),
      column(c) {}

namespace {
using detail::Tok;
using detail::Token;

class Parser {
 public:
  Parser(const std::string& text, const std::string& source)
      : toks_(detail::tokenizeDbc(text, source)), source_(source) {}

  Database run() {
    while (peek().kind != Tok::kEnd) statement();
    return std::move(db_);
  }

 private:
  std::vector<Token> toks_;
  std::size_t pos_ = 0;
  std::string source_;
  Database db_;
  Message* msg_ = nullptr;

  const Token& peek() const { return toks_[pos_]; }
  const Token& take() { return toks_[pos_ < toks_.size() - 1 ? pos_++ : pos_]; }
  [[noreturn]] void fail(const Token& t, const std::string& what) const {
    throw DbcError(source_, t.line, t.col,
                   what + (t.kind == Tok::kEnd ? " (found end of file)" : " (found '" + t.text + "')"));
  }
  const Token& expect(Tok kind, const char* what) {
    if (peek().kind != kind) fail(peek(), std::string("expected ") + what);
    return take();
  }
  void expectPunct(char c) {
    if (peek().kind != Tok::kPunct || peek().text[0] != c) fail(peek(), std::string("expected '") + c + "'");
    take();
  }
  bool acceptPunct(char c) {
    if (peek().kind == Tok::kPunct && peek().text[0] == c) {
      take();
      return true;
    }
    return false;
  }
  double number() {
    const Token& t = expect(Tok::kNumber, "a number");
    char* end = nullptr;
    const double v = std::strtod(t.text.c_str(), &end);
    if (*end != 0) fail(t, "malformed number");
    if (!std::isfinite(v)) fail(t, "number out of the double range");
    return v;
  }
  std::uint64_t unsignedInt() {
    const Token& t = expect(Tok::kNumber, "an unsigned integer");
    char* end = nullptr;
    const unsigned long long v = std::strtoull(t.text.c_str(), &end, 10);
    if (*end != 0 || t.text[0] == '-') fail(t, "expected an unsigned integer");
    return v;
  }
  std::int64_t signedInt() {
    const Token& t = expect(Tok::kNumber, "an integer");
    char* end = nullptr;
    const long long v = std::strtoll(t.text.c_str(), &end, 10);
    if (*end == 0) return v;
    const double d = std::strtod(t.text.c_str(), &end);  // "1.0" in some VAL_ tables
    if (*end != 0 || d != static_cast<double>(static_cast<long long>(d))) fail(t, "expected an integer");
    return static_cast<std::int64_t>(d);
  }
  // Skips to the end of a ';'-terminated statement.
  void skipStatement() {
    while (peek().kind != Tok::kEnd && !(peek().kind == Tok::kPunct && peek().text[0] == ';')) take();
    if (peek().kind == Tok::kEnd) fail(peek(), "expected ';' ending the statement");
    take();
  }
  // Skips to the next token that starts a line in column 1 (NS_ and BS_ blocks).
  void skipBlock() {
    while (peek().kind != Tok::kEnd && !(peek().line_start && peek().col == 1)) take();
  }

  void warn(const Token& at, const std::string& what) {
    db_.warnings.push_back(source_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.col) + ": " + what);
  }
  // Message referenced by CM_/VAL_/SIG_VALTYPE_; nullptr (statement skipped, warning kept) if undefined.
  Message* messageRef() {
    const Token& at = peek();
    const auto id = static_cast<std::uint32_t>(unsignedInt());
    for (Message& m : db_.messages) {
      if (m.dbc_id == id) return &m;
    }
    warn(at, "reference to undefined message id " + at.text + " ignored");
    skipStatement();
    return nullptr;
  }
  Signal* signalRef(Message& m) {
    const Token& at = expect(Tok::kIdent, "a signal name");
    for (Signal& s : m.signals) {
      if (s.name == at.text) return &s;
    }
    warn(at, "reference to undefined signal " + m.name + "." + at.text + " ignored");
    skipStatement();
    return nullptr;
  }

  void statement();
  void message();
  void signal();
  void comment();
  void attributeDef();
  void attributeValue();
  void valueDescriptions();
  void valueTable();
  void sigValType();
  std::map<std::int64_t, std::string> valuePairs();
};

void Parser::statement() {
  const Token& kw = peek();
  if (kw.kind != Tok::kIdent) fail(kw, "expected a DBC keyword");
  const std::string k = take().text;
  if (k == "VERSION") {
    db_.version = expect(Tok::kString, "a quoted version string").text;
  } else if (k == "NS_" || k == "BS_") {
    expectPunct(':');
    skipBlock();
  } else if (k == "BU_") {
    expectPunct(':');
    while (peek().kind == Tok::kIdent && !(peek().line_start && peek().col == 1)) db_.nodes.push_back(take().text);
  } else if (k == "BO_") {
    message();
  } else if (k == "SG_") {
    signal();
  } else if (k == "CM_") {
    comment();
  } else if (k == "BA_DEF_") {
    attributeDef();
  } else if (k == "BA_DEF_DEF_") {
    const std::string name = expect(Tok::kString, "an attribute name").text;
    const Token& v = take();
    if (v.kind != Tok::kNumber && v.kind != Tok::kString) fail(v, "expected an attribute default value");
    db_.attribute_defaults.emplace_back(name, v.kind == Tok::kString ? '"' + v.text + '"' : v.text);
    expectPunct(';');
  } else if (k == "BA_") {
    attributeValue();
  } else if (k == "VAL_") {
    valueDescriptions();
  } else if (k == "VAL_TABLE_") {
    valueTable();
  } else if (k == "SIG_VALTYPE_") {
    sigValType();
  } else if (k == "EV_" || k == "SIG_GROUP_" || k == "BO_TX_BU_" || k == "BA_DEF_REL_" || k == "BA_REL_" ||
             k == "BA_DEF_DEF_REL_" || k == "SGTYPE_" || k == "SIG_TYPE_REF_" || k == "SG_MUL_VAL_" ||
             k == "ENVVAR_DATA_" || k == "CAT_DEF_" || k == "CAT_" || k == "FILTER" || k == "SIG_VALTYPE" ||
             k == "SGTYPE_VAL_" || k == "BA_SGTYPE_" || k == "SIG_TYPE_REF") {
    skipStatement();
    ++db_.skipped_statements;
  } else {
    fail(kw, "unknown DBC keyword");
  }
}

void Parser::message() {
  Message m;
  const Token& id_tok = peek();
  const std::uint64_t id = unsignedInt();
  // 29-bit ids carry bit 31; 0x40000000 is Vector's VECTOR__INDEPENDENT_SIG_MSG pseudo-message.
  const bool ext_ok = (id & 0x80000000ULL) != 0 && (id & 0x60000000ULL) == 0 && id <= 0xFFFFFFFFULL;
  if (id > 0xFFFFFFFFULL) fail(id_tok, "message id above 32 bits");
  if (!(id <= 0x7FF || ext_ok || id == 0x40000000ULL)) {  // kept (opendbc has some), never matches a frame
    db_.warnings.push_back(source_ + ":" + std::to_string(id_tok.line) + ":" + std::to_string(id_tok.col) +
                           ": message id " + id_tok.text + " is neither 11-bit nor 29-bit with bit 31");
  }
  m.dbc_id = static_cast<std::uint32_t>(id);
  m.name = expect(Tok::kIdent, "a message name").text;
  expectPunct(':');
  const Token& size_tok = peek();
  m.size = static_cast<std::uint32_t>(unsignedInt());
  if (m.size > 64) fail(size_tok, "message size above 64 bytes");
  m.transmitter = expect(Tok::kIdent, "a transmitter node name").text;
  db_.messages.push_back(std::move(m));
  msg_ = &db_.messages.back();
}

void Parser::signal() {
  const Token& sg = toks_[pos_ - 1];
  if (!msg_) fail(sg, "SG_ before any BO_");
  Signal s;
  s.name = expect(Tok::kIdent, "a signal name").text;
  if (peek().kind == Tok::kIdent) {  // multiplexer indicator: M, m<k>, m<k>M
    const Token& mt = take();
    const std::string& t = mt.text;
    if (t == "M") {
      s.mux = MuxRole::kMultiplexor;
    } else if (t.size() >= 2 && t[0] == 'm' && std::isdigit(static_cast<unsigned char>(t[1]))) {
      s.mux = MuxRole::kMultiplexed;
      std::size_t used = 0;
      s.mux_value = std::stoull(t.substr(1), &used);
      const std::string tail = t.substr(1 + used);
      if (tail == "M") {
        s.also_multiplexor = true;
      } else if (!tail.empty()) {
        fail(mt, "bad multiplexer indicator");
      }
    } else {
      fail(mt, "bad multiplexer indicator (expected M or m<number>)");
    }
  }
  expectPunct(':');
  const Token& start_tok = peek();
  s.start_bit = static_cast<std::uint32_t>(unsignedInt());
  expectPunct('|');
  const Token& len_tok = peek();
  s.length = static_cast<std::uint32_t>(unsignedInt());
  if (s.length < 1 || s.length > 64) fail(len_tok, "signal length must be 1..64 bits");
  if (s.start_bit >= 512) fail(start_tok, "start bit beyond 64 bytes");
  expectPunct('@');
  const Token& order = expect(Tok::kNumber, "byte order 0 or 1");
  if (order.text != "0" && order.text != "1") fail(order, "byte order must be 0 (Motorola) or 1 (Intel)");
  s.little_endian = order.text == "1";
  if (acceptPunct('-')) {
    s.is_signed = true;
  } else {
    expectPunct('+');
  }
  expectPunct('(');
  s.factor = number();
  expectPunct(',');
  s.offset = number();
  expectPunct(')');
  expectPunct('[');
  s.minimum = number();
  expectPunct('|');
  s.maximum = number();
  expectPunct(']');
  s.unit = expect(Tok::kString, "a quoted unit").text;
  while (peek().kind == Tok::kIdent && !peek().line_start) {
    s.receivers.push_back(take().text);
    if (!acceptPunct(',')) break;
  }
  if (s.receivers.empty()) s.receivers.push_back("Vector__XXX");  // the format's "no receiver"
  msg_->signals.push_back(std::move(s));
}

void Parser::comment() {
  if (peek().kind == Tok::kString) {
    db_.comments.push_back(take().text);
  } else if (peek().kind == Tok::kNumber) {  // "CM_ 145 "..."" (opendbc): object keyword missing
    warn(peek(), "CM_ without BO_/SG_ keyword ignored");
    skipStatement();
    return;
  } else {
    const Token& obj = expect(Tok::kIdent, "BU_, BO_, SG_, EV_ or a string");
    if (obj.text == "BO_") {
      Message* m = messageRef();
      if (!m) return;
      m->comment = expect(Tok::kString, "a quoted comment").text;
    } else if (obj.text == "SG_") {
      Message* m = messageRef();
      if (!m) return;
      if (peek().kind == Tok::kString) {  // seen in opendbc: signal name missing; keep going
        warn(peek(), "CM_ SG_ without signal name ignored");
        take();
      } else {
        Signal* s = signalRef(*m);
        if (!s) return;
        s->comment = expect(Tok::kString, "a quoted comment").text;
      }
    } else if (obj.text == "BU_") {
      const std::string node = expect(Tok::kIdent, "a node name").text;
      db_.node_comments[node] = expect(Tok::kString, "a quoted comment").text;
    } else if (obj.text == "EV_") {
      skipStatement();
      ++db_.skipped_statements;
      return;
    } else {
      fail(obj, "expected BU_, BO_, SG_ or EV_ after CM_");
    }
  }
  expectPunct(';');
}

void Parser::attributeDef() {
  AttributeDef d;
  if (peek().kind == Tok::kIdent) d.object = take().text;
  d.name = expect(Tok::kString, "an attribute name").text;
  std::string spec;
  while (peek().kind != Tok::kEnd && !(peek().kind == Tok::kPunct && peek().text[0] == ';')) {
    const Token& t = take();
    if (!spec.empty() && !(t.kind == Tok::kPunct && t.text[0] == ',') && spec.back() != ',') spec += ' ';
    spec += t.kind == Tok::kString ? '"' + t.text + '"' : t.text;
  }
  expectPunct(';');
  d.type_spec = spec;
  db_.attribute_defs.push_back(std::move(d));
}

void Parser::attributeValue() {
  AttributeValue a;
  a.name = expect(Tok::kString, "an attribute name").text;
  if (peek().kind == Tok::kIdent) {
    a.object = take().text;
    if (a.object == "SG_") {
      a.target = expect(Tok::kNumber, "a message id").text;
      a.target += ' ' + expect(Tok::kIdent, "a signal name").text;
    } else if (a.object == "BO_") {
      a.target = expect(Tok::kNumber, "a message id").text;
    } else {
      a.target = expect(Tok::kIdent, "a node or variable name").text;
    }
  }
  const Token& v = take();
  if (v.kind == Tok::kNumber || v.kind == Tok::kIdent) {
    a.value = v.text;
  } else if (v.kind == Tok::kString) {
    a.value = '"' + v.text + '"';
  } else {
    fail(v, "expected an attribute value");
  }
  expectPunct(';');
  db_.attributes.push_back(std::move(a));
}

std::map<std::int64_t, std::string> Parser::valuePairs() {
  std::map<std::int64_t, std::string> vals;
  while (!acceptPunct(';')) {
    const std::int64_t v = signedInt();
    vals[v] = expect(Tok::kString, "a quoted value description").text;
  }
  return vals;
}

void Parser::valueDescriptions() {
  if (peek().kind == Tok::kIdent) {  // VAL_ of an environment variable: not used by roadslam
    skipStatement();
    ++db_.skipped_statements;
    return;
  }
  Message* m = messageRef();
  if (!m) return;
  Signal* s = signalRef(*m);
  if (!s) return;
  s->value_descriptions = valuePairs();
}

void Parser::valueTable() {
  const std::string name = expect(Tok::kIdent, "a value table name").text;
  db_.value_tables[name] = valuePairs();
}

void Parser::sigValType() {
  Message* m = messageRef();
  if (!m) return;
  Signal* sp = signalRef(*m);
  if (!sp) return;
  Signal& s = *sp;
  acceptPunct(':');
  const Token& vt = peek();
  const std::uint64_t t = unsignedInt();
  if (t > 2) fail(vt, "SIG_VALTYPE_ must be 0, 1 (float) or 2 (double)");
  s.value_type = static_cast<ValueType>(t);
  if ((s.value_type == ValueType::kFloat32 && s.length != 32) ||
      (s.value_type == ValueType::kFloat64 && s.length != 64)) {
    fail(vt, "float signal " + s.name + " needs length 32 (float) or 64 (double)");
  }
  expectPunct(';');
}

}  // namespace

Database parseDbc(const std::string& text, const std::string& source_name) {
  return Parser(text, source_name).run();
}

Database loadDbcFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open DBC file '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parseDbc(ss.str(), path);
}

}  // namespace roadslam::can
