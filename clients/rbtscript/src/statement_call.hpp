// A statement line read as a call, Name(argument, ...), before its arguments are given meaning.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "line_lexer.hpp"

namespace robotd::rbtscript::detail {

/// `value` or `name=value`.
struct Argument {
  std::optional<Token> name;
  Token value;
  std::string_view text;  // as written, e.g. "v=50"
  std::size_t column = 1;
};

struct Call {
  Token name;
  std::vector<Argument> arguments;
  Token close;  // the ')'
};

/// How an error names an argument: "'v=50'".
std::string describe(const Argument& argument);

}  // namespace robotd::rbtscript::detail
