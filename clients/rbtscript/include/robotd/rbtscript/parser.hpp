// Reading RBTscript text into a Program (docs/rbtscript.md). The whole text is read: a line with
// an error is reported and skipped, so one pass lists every error of the script.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "robotd/rbtscript/program.hpp"

namespace robotd::rbtscript {

struct ParseError {
  SourceLocation location;
  std::string found;     // what is there, e.g. "'MoveJ'", "')'", "end of line"
  std::string expected;  // what the language wants there
  /// "line 3, column 14: found ')', expected 6 pose values (x, y, z in mm, Rx, Ry, Rz in degrees)"
  std::string message() const;
};

struct ParseResult {
  std::optional<Program> program;  // set when there are no errors
  std::vector<ParseError> errors;  // in line order, at most one per line
};

ParseResult parse_program(std::string_view text);

}  // namespace robotd::rbtscript
