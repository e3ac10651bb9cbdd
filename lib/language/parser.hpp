#pragma once
/// \file parser.hpp
/// Parsing sculpt scripts (the grammar lives in grammar_def.hpp; this header needs no X3).

#include <string_view>

#include "language/ast.hpp"
#include "language/source.hpp"

namespace sculpt::language {

/// Brackets `(`, `[` and `{` may nest at most this deep. The parser is recursive descent, so
/// the limit is what keeps hostile input (100000 `(`) from exhausting the stack; it is checked
/// before parsing and reported as an error at the offending bracket.
inline constexpr int kMaxNesting = 64;

/// Parses a whole script.
/// \throw ScriptError "expected X here" at the first position where the text cannot go on,
///        or a nesting error (kMaxNesting).
ast::Program parse(const SourcePtr& source);

/// For the REPL: true when `text` has more opening than closing brackets (outside strings and
/// comments), so that the user is still typing a multi-line construct.
bool is_unfinished(std::string_view text);

}  // namespace sculpt::language
