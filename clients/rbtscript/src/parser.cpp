#include "robotd/rbtscript/parser.hpp"

#include <algorithm>
#include <span>
#include <string>
#include <utility>

#include "line_lexer.hpp"
#include "statement_binding.hpp"
#include "statement_call.hpp"

namespace robotd::rbtscript {
namespace detail {

std::string describe(const Argument& argument) { return "'" + std::string(argument.text) + "'"; }

namespace {

bool is_value(const Token& token) {
  return token.kind == TokenKind::kNumber || token.kind == TokenKind::kWord || token.kind == TokenKind::kString;
}

/// The text of `line` from the start of `first` to the end of `last`.
std::string_view span_of(std::string_view line, const Token& first, const Token& last) {
  return line.substr(first.column - 1, last.column - first.column + last.text.size());
}

/// `value` or `name=value` at tokens[at]; advances `at` past it.
std::variant<Argument, LineError> read_argument(std::string_view line, std::span<const Token> tokens, std::size_t& at) {
  const Token& first = tokens[at];
  if (!is_value(first)) return error_at(first, "an argument");
  Argument argument{std::nullopt, first, first.text, first.column};
  if (first.kind == TokenKind::kWord && tokens[at + 1].kind == TokenKind::kEquals) {
    const Token& value = tokens[at + 2];
    if (!is_value(value)) return error_at(value, "a value after '" + std::string(first.text) + "='");
    argument = Argument{first, value, span_of(line, first, value), first.column};
    at += 3;
  } else {
    at += 1;
  }
  return argument;
}

/// Name(argument, ...); `at` ends on the ')'. `tokens` ends with kEndOfLine.
std::variant<Call, LineError> read_call(std::string_view line, std::span<const Token> tokens, std::size_t& at) {
  Call call{tokens[0], {}, {}};
  if (call.name.kind != TokenKind::kWord) return error_at(call.name, expected_statement(call.name));
  if (tokens[1].kind != TokenKind::kOpenParen) {
    return error_at(tokens[1], "'(' after " + std::string(call.name.text));
  }
  at = 2;
  if (tokens[at].kind != TokenKind::kCloseParen) {
    while (true) {
      auto argument = read_argument(line, tokens, at);
      if (auto* error = std::get_if<LineError>(&argument)) return std::move(*error);
      call.arguments.push_back(std::get<Argument>(argument));
      if (tokens[at].kind == TokenKind::kCloseParen) break;
      if (tokens[at].kind != TokenKind::kComma) return error_at(tokens[at], "',' or ')'");
      ++at;
    }
  }
  call.close = tokens[at];
  return call;
}

/// The statement on one line, nothing for a blank or comment line, or the line's error.
std::variant<std::monostate, Statement, LineError> parse_line(std::string_view line) {
  auto lexed = tokenize_line(line);
  if (auto* error = std::get_if<LineError>(&lexed)) return std::move(*error);
  const auto& tokens = std::get<std::vector<Token>>(lexed);
  if (tokens.size() == 1) return std::monostate{};
  std::size_t close = 0;
  auto read = read_call(line, tokens, close);
  if (auto* error = std::get_if<LineError>(&read)) return std::move(*error);
  const Call& call = std::get<Call>(read);
  // The arguments first, so that a line's error is the leftmost one.
  auto bound = bind_statement(call);
  if (auto* error = std::get_if<LineError>(&bound)) return std::move(*error);
  if (tokens[close + 1].kind != TokenKind::kEndOfLine) {
    return error_at(tokens[close + 1], "the end of the line or a // comment: one statement per line");
  }
  return Statement{std::get<StatementKind>(std::move(bound)), SourceLocation{1, call.name.column},
                   std::string(span_of(line, call.name, call.close))};
}

}  // namespace
}  // namespace detail

std::string ParseError::message() const {
  return "line " + std::to_string(location.line) + ", column " + std::to_string(location.column) + ": found " + found +
         ", expected " + expected;
}

ParseResult parse_program(std::string_view text) {
  Program program;
  std::vector<ParseError> errors;
  std::size_t line_number = 0;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    ++line_number;
    start = end + 1;
    auto parsed = detail::parse_line(line);
    if (auto* statement = std::get_if<Statement>(&parsed)) {
      statement->location.line = line_number;
      program.statements.push_back(std::move(*statement));
    } else if (auto* error = std::get_if<detail::LineError>(&parsed)) {
      errors.push_back({{line_number, error->column}, std::move(error->found), std::move(error->expected)});
    }
  }
  if (!errors.empty()) return {std::nullopt, std::move(errors)};
  return {std::move(program), {}};
}

}  // namespace robotd::rbtscript
