// Reading a script in a test: the program (failing the test on any error), its only statement,
// or its only error.
#pragma once

#include <ostream>
#include <string_view>
#include <variant>

#include <gtest/gtest.h>

#include "robotd/rbtscript/parser.hpp"

namespace robotd::rbtscript {

/// How GoogleTest shows a location in a failure.
inline void PrintTo(const SourceLocation& location, std::ostream* out) {
  *out << "line " << location.line << ", column " << location.column;
}

}  // namespace robotd::rbtscript

namespace robotd::rbtscript::test {

inline Program parse_ok(std::string_view text) {
  auto result = parse_program(text);
  for (const auto& error : result.errors) ADD_FAILURE() << error.message();
  return result.program.value_or(Program{});
}

/// The script's one statement, which must be an S (a default S, with a failure, otherwise).
template <class S>
S only_statement(std::string_view text) {
  const Program program = parse_ok(text);
  if (program.statements.size() != 1) {
    ADD_FAILURE() << text << ": " << program.statements.size() << " statements";
    return S{};
  }
  const S* statement = std::get_if<S>(&program.statements[0].kind);
  if (statement == nullptr) {
    ADD_FAILURE() << text << ": another statement kind";
    return S{};
  }
  return *statement;
}

inline ParseError only_error(std::string_view text) {
  const auto result = parse_program(text);
  EXPECT_FALSE(result.program.has_value()) << text;
  if (result.errors.size() != 1) {
    ADD_FAILURE() << text << ": " << result.errors.size() << " errors";
    return ParseError{};
  }
  return result.errors[0];
}

}  // namespace robotd::rbtscript::test
