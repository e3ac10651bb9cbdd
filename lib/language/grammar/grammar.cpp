// The one translation unit that includes Spirit X3: instantiates the grammar and runs it.
#include "language/grammar/grammar_def.hpp"
#include "language/parser.hpp"

namespace sculpt::language {
namespace x3 = boost::spirit::x3;
namespace grammar {
BOOST_SPIRIT_INSTANTIATE(program_type, iterator_type, context_type)
}  // namespace grammar

namespace {

/// Depth of bracket nesting at each bracket, skipping strings and comments. Calls `visit`
/// with (offset, depth after the bracket) and stops when it returns false.
template <typename Visit>
void scan_brackets(std::string_view text, Visit&& visit) {
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '"') {
      for (++i; i < text.size() && text[i] != '"' && text[i] != '\n'; ++i) {
        if (text[i] == '\\' && i + 1 < text.size() && text[i + 1] != '\n') ++i;
      }
    } else if (c == '(' || c == '[' || c == '{') {
      if (!visit(i, ++depth)) return;
    } else if (c == ')' || c == ']' || c == '}') {
      if (!visit(i, --depth)) return;
    }
  }
}

}  // namespace

bool is_unfinished(std::string_view text) {
  int depth = 0;
  scan_brackets(text, [&](std::size_t, int d) {
    depth = d;
    return true;
  });
  return depth > 0;
}

ast::Program parse(const SourcePtr& source) {
  const std::string& text = source->text;
  scan_brackets(text, [&](std::size_t offset, int depth) {
    if (depth > kMaxNesting) {
      throw ScriptError({source, offset},
                        "brackets nested deeper than " + std::to_string(kMaxNesting) + " levels");
    }
    return true;
  });
  if (text.find('\0') != std::string::npos) {
    throw ScriptError({source, text.find('\0')}, "unexpected NUL character");
  }

  const char* const begin = text.data();
  const char* const end = begin + text.size();
  grammar::PositionTracker tracker{begin};
  const auto parser = x3::with<grammar::position_tag>(std::ref(tracker))[program_rule()];
  ast::Program program;
  const char* position = begin;
  try {
    const bool ok = x3::phrase_parse(position, end, parser, skipper_rule(), program);
    if (!ok || position != end) {
      throw ScriptError({source, static_cast<std::size_t>(position - begin)}, "syntax error");
    }
  } catch (const x3::expectation_failure<grammar::iterator_type>& failure) {
    // Point at the next token, not at the blanks before it.
    const char* at = failure.where();
    while (at != end && (*at == ' ' || *at == '\t' || *at == '\r' || *at == '#')) {
      if (*at == '#') {
        while (at != end && *at != '\n') ++at;
      } else {
        ++at;
      }
    }
    // At the end, point just after the last thing written (not at a blank line below it).
    const bool at_end = at == end;
    while (at_end && at != begin && (at[-1] == ' ' || at[-1] == '\t' || at[-1] == '\r' || at[-1] == '\n')) --at;
    const auto offset = static_cast<std::size_t>(at - begin);
    std::string message = "expected " + failure.which();
    message += at_end ? " at end of input" : " here";
    if (failure.which() == "element assignment") {  // `x[0] = 5`, `f(x) = 1` (grammar_def.hpp)
      message =
          "only a name can be assigned: assignment to an element (x[i] = v) is not supported, lists are "
          "values; build a new list instead, e.g. xs = concat(xs[:i], concat([v], xs[i + 1:]))";
    }
    throw ScriptError({source, offset}, message);
  }
  return program;
}

}  // namespace sculpt::language
