#include "dbc_lexer.h"

#include <roadslam/can/dbc.h>

#include <cctype>

namespace roadslam::can::detail {
namespace {

bool identStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool identChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool digit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

std::vector<Token> tokenizeDbc(const std::string& s, const std::string& source) {
  std::vector<Token> out;
  std::size_t i = 0, line = 1, line_begin = 0;
  bool first_on_line = true;
  const std::size_t n = s.size();
  while (i < n) {
    const char c = s[i];
    if (c == '\n') {
      ++line;
      line_begin = ++i;
      first_on_line = true;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++i;
      continue;
    }
    Token t;
    t.line = line;
    t.col = i - line_begin + 1;
    t.line_start = first_on_line;
    first_on_line = false;
    if (c == '"') {
      t.kind = Tok::kString;
      ++i;
      while (i < n && s[i] != '"') {
        if (s[i] == '\\' && i + 1 < n && (s[i + 1] == '"' || s[i + 1] == '\\')) ++i;
        if (s[i] == '\n') {
          ++line;
          line_begin = i + 1;
        }
        t.text += s[i++];
      }
      if (i >= n) throw DbcError(source, t.line, t.col, "unterminated string");
      ++i;
    } else if (digit(c) || ((c == '-' || c == '+' || c == '.') && i + 1 < n &&
                            (digit(s[i + 1]) || (s[i + 1] == '.' && c != '.')))) {
      std::size_t j = i + 1;
      while (j < n && (digit(s[j]) || s[j] == '.' ||
                       ((s[j] == 'e' || s[j] == 'E') && j + 1 < n &&
                        (digit(s[j + 1]) || s[j + 1] == '-' || s[j + 1] == '+')) ||
                       ((s[j] == '-' || s[j] == '+') && (s[j - 1] == 'e' || s[j - 1] == 'E')))) {
        ++j;
      }
      t.kind = Tok::kNumber;
      if (j < n && identChar(s[j]) && c != '-' && c != '+') {  // "4WD": a name starting with a digit
        while (j < n && identChar(s[j])) ++j;
        t.kind = Tok::kIdent;
      }
      t.text = s.substr(i, j - i);
      i = j;
    } else if (identStart(c)) {
      std::size_t j = i + 1;
      while (j < n && identChar(s[j])) ++j;
      t.kind = Tok::kIdent;
      t.text = s.substr(i, j - i);
      i = j;
    } else if (c == ':' || c == '|' || c == '@' || c == '(' || c == ')' || c == '[' || c == ']' ||
               c == ',' || c == ';' || c == '+' || c == '-') {
      t.kind = Tok::kPunct;
      t.text = std::string(1, c);
      ++i;
    } else {
      throw DbcError(source, t.line, t.col,
                     std::string("unexpected character '") + c + "'");
    }
    out.push_back(std::move(t));
  }
  Token end;
  end.line = line;
  end.col = i - line_begin + 1;
  end.line_start = true;
  out.push_back(end);
  return out;
}

}  // namespace roadslam::can::detail
