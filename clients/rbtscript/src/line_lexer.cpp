#include "line_lexer.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>
#include <utility>

namespace robotd::rbtscript::detail {
namespace {

bool is_word_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_'; }
bool is_word_char(char c) { return is_word_start(c) || std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool is_number_start(char c) { return is_digit(c) || c == '.' || c == '+' || c == '-'; }

/// A character as an error shows it: printable ones quoted, others as their byte value.
std::string describe_char(char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (byte >= 0x20 && byte < 0x7F) return std::string{'\''} + c + '\'';
  char text[16];
  std::snprintf(text, sizeof text, "byte 0x%02X", byte);
  return text;
}

std::size_t skip_digits(std::string_view line, std::size_t at) {
  while (at < line.size() && is_digit(line[at])) ++at;
  return at;
}

/// [+-]digits[.digits][(e|E)[+-]digits], at least one digit before the exponent. Returns the end.
std::size_t scan_number(std::string_view line, std::size_t start) {
  std::size_t at = start;
  if (line[at] == '+' || line[at] == '-') ++at;
  at = skip_digits(line, at);
  if (at < line.size() && line[at] == '.') at = skip_digits(line, at + 1);
  if (at < line.size() && (line[at] == 'e' || line[at] == 'E')) {
    std::size_t exponent = at + 1;
    if (exponent < line.size() && (line[exponent] == '+' || line[exponent] == '-')) ++exponent;
    if (exponent < line.size() && is_digit(line[exponent])) at = skip_digits(line, exponent);
  }
  return at;
}

constexpr std::string_view kNumberExpected = "a number such as 90, -12.5 or 0.25";

std::variant<Token, LineError> lex_number(std::string_view line, std::size_t start) {
  std::size_t end = scan_number(line, start);
  // "12abc" or "1.2.3" is one wrong thing, not a number followed by something else.
  while (end < line.size() && (is_word_char(line[end]) || line[end] == '.')) ++end;
  const std::string_view text = line.substr(start, end - start);
  const std::string_view digits = text.front() == '+' ? text.substr(1) : text;
  Token token{TokenKind::kNumber, text, start + 1};
  const auto [rest, status] = std::from_chars(digits.data(), digits.data() + digits.size(), token.number);
  const bool whole_text = rest == digits.data() + digits.size();
  if (status == std::errc::result_out_of_range && whole_text) {
    return LineError{start + 1, "'" + std::string(text) + "'", "a number of a sensible size"};
  }
  if (status != std::errc{} || !whole_text || !std::isfinite(token.number)) {
    return LineError{start + 1, "'" + std::string(text) + "'", std::string(kNumberExpected)};
  }
  return token;
}

std::variant<Token, LineError> lex_string(std::string_view line, std::size_t start) {
  const std::size_t close = line.find('"', start + 1);
  if (close == std::string_view::npos) {
    return LineError{line.size() + 1, "end of line",
                     "the closing '\"' of the string at column " + std::to_string(start + 1)};
  }
  return Token{TokenKind::kString, line.substr(start, close + 1 - start), start + 1};
}

std::variant<Token, LineError> lex_one(std::string_view line, std::size_t start) {
  const char c = line[start];
  switch (c) {
    case '(':
      return Token{TokenKind::kOpenParen, line.substr(start, 1), start + 1};
    case ')':
      return Token{TokenKind::kCloseParen, line.substr(start, 1), start + 1};
    case ',':
      return Token{TokenKind::kComma, line.substr(start, 1), start + 1};
    case '=':
      return Token{TokenKind::kEquals, line.substr(start, 1), start + 1};
    case '"':
      return lex_string(line, start);
    default:
      break;
  }
  if (is_number_start(c)) return lex_number(line, start);
  if (is_word_start(c)) {
    std::size_t end = start + 1;
    while (end < line.size() && is_word_char(line[end])) ++end;
    return Token{TokenKind::kWord, line.substr(start, end - start), start + 1};
  }
  return LineError{start + 1, describe_char(c),
                   "a statement, a number, a word, a \"string\", one of ( ) , = or a // comment"};
}

}  // namespace

std::string describe(const Token& token) {
  if (token.kind == TokenKind::kEndOfLine) return "end of line";
  return "'" + std::string(token.text) + "'";
}

LineError error_at(const Token& token, std::string expected) {
  return {token.column, describe(token), std::move(expected)};
}

std::string_view string_content(const Token& token) { return token.text.substr(1, token.text.size() - 2); }

std::variant<std::vector<Token>, LineError> tokenize_line(std::string_view line) {
  std::vector<Token> tokens;
  std::size_t at = 0;
  while (true) {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r')) ++at;
    if (at == line.size() || line.substr(at).starts_with("//")) break;
    auto lexed = lex_one(line, at);
    if (auto* error = std::get_if<LineError>(&lexed)) return std::move(*error);
    const auto& token = std::get<Token>(lexed);
    at = token.column - 1 + token.text.size();
    tokens.push_back(token);
  }
  tokens.push_back(Token{TokenKind::kEndOfLine, {}, at + 1});
  return tokens;
}

}  // namespace robotd::rbtscript::detail
