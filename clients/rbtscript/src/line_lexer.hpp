// The tokens of one line of RBTscript: words, numbers, "strings", ( ) , = and the end of the
// line, with `//` comments left out. Statements never span lines, so the parser lexes line by line.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace robotd::rbtscript::detail {

enum class TokenKind { kWord, kNumber, kString, kOpenParen, kCloseParen, kComma, kEquals, kEndOfLine };

struct Token {
  TokenKind kind = TokenKind::kEndOfLine;
  std::string_view text;  // as written (a string with its quotes); empty at the end of the line
  std::size_t column = 1;
  double number = 0;  // kNumber's value
};

/// An error within one line: the parser adds the line number.
struct LineError {
  std::size_t column = 1;
  std::string found;
  std::string expected;
};

/// How an error names a token: "'MoveJ'", "')'", "end of line".
std::string describe(const Token& token);

/// An error at `token`, which is what was found there.
LineError error_at(const Token& token, std::string expected);

/// A string token's text without its quotes.
std::string_view string_content(const Token& token);

/// The line's tokens, the last one kEndOfLine; or the first thing that is not a token.
std::variant<std::vector<Token>, LineError> tokenize_line(std::string_view line);

}  // namespace robotd::rbtscript::detail
