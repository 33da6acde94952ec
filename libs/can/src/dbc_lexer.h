#pragma once
// Tokenizer of the DBC format (private to libs/can). Tokens carry their 1-based line and column so
// every parse error can name them.

#include <cstddef>
#include <string>
#include <vector>

namespace roadslam::can::detail {

enum class Tok { kIdent, kNumber, kString, kPunct, kEnd };

struct Token {
  Tok kind = Tok::kEnd;
  std::string text;  // strings: unescaped content
  std::size_t line = 0, col = 0;
  bool line_start = false;  // first token on its line
};

/// Splits \p text into tokens; throws DbcError (naming \p source) on an unterminated string or a
/// character no DBC token starts with.
std::vector<Token> tokenizeDbc(const std::string& text, const std::string& source);

}  // namespace roadslam::can::detail
