// Giving a call's arguments their meaning: which statement it is, the argument order and
// defaults, and the ranges the language itself defines (docs/rbtscript.md).
#pragma once

#include <string>
#include <variant>

#include "robotd/rbtscript/program.hpp"
#include "statement_call.hpp"

namespace robotd::rbtscript::detail {

std::variant<StatementKind, LineError> bind_statement(const Call& call);

/// What an error expects where `found` stands instead of a statement name: the statement names,
/// or the one `found` misspells in case only.
std::string expected_statement(const Token& found);

}  // namespace robotd::rbtscript::detail
