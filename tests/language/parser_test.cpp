// Parser: good inputs give the expected tree shape; bad inputs give the exact message and
// position ("file:line:col: error: ...", the line, a caret).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <string_view>

#include "language/parser.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::text_source;

// Joins parts with append: GCC 12 at -O3 warns falsely (-Warray-bounds) on chains of
// std::string operator+ with long temporaries (GCC bug 105329).
std::string cat(std::initializer_list<std::string_view> parts) {
  std::string s;
  for (std::string_view p : parts) s.append(p);
  return s;
}

std::string parse_error(const std::string& text) {
  try {
    parse(text_source(text));
  } catch (const ScriptError& e) {
    return format_error(e);
  }
  return "";
}

TEST(Parser, AcceptsTheLanguageSummary) {
  const char* good[] = {
      "",
      "\n\n# only a comment\n",
      "x = 1; y = 2\n",
      "x = -1.5e3 + .5 * 2 % 3 / 4",
      "s = \"a\\tb\\n\\\\\\\"\"",
      "v = [1, 2, [3, [4]]]\nw = []",
      "f(1, b = 2, c=[3])",
      "fn f(a, b) { return a + b }",
      "fn g() {}\nfn h(\n  a,\n  b\n) {\n  a\n}",
      "if a { b } else if c { d } else { e }",
      "if a {\n  b\n}\nelse {\n  c\n}",
      "for x in range(0, 10, 2) { print(x) }",
      "include \"other.bsp\"",
      "c = a | b & d - e",
      "c = not a and b or c == d != e < f <= g > h >= i",
      "x = f(1)(2)[3][4]",
      "x = (1 +\n 2 *\n 3)",
      "x = not - - + y",
      "return",
      "iffy = 1; format = 2; inside = 3",
      "x = 1 # trailing comment\n",
      "x = v[1:2] + v[:2] + v[1:] + v[:] + v[-2:-1]",
      "x = v[a[0]:b[1:][0]]\ny = v[\n  1 :\n  2\n]",
      "x[0] == 5",
  };
  for (const char* text : good) EXPECT_EQ(parse_error(text), "") << text;
}

TEST(Parser, FlatOperatorChainsAndPositions) {
  const ast::Program program = parse(text_source("x = 1 + 2 - 3\n  y = a(b)"));
  ASSERT_EQ(program.statements.size(), 2u);
  const auto& assignment = boost::get<ast::Assignment>(program.statements[0]);
  EXPECT_EQ(assignment.target.name, "x");
  EXPECT_EQ(assignment.where, 0u);
  EXPECT_EQ(assignment.value.where, 4u);
  const auto& second = boost::get<ast::Assignment>(program.statements[1]);
  EXPECT_EQ(second.where, 16u);  // after the indentation
  EXPECT_EQ(second.target.where, 16u);
}

TEST(Parser, LongChainsAreLoopsNotRecursion) {
  std::string sum = "x = 0";
  for (int i = 0; i < 100000; ++i) sum += "+1";
  EXPECT_EQ(parse_error(sum), "");
  EXPECT_EQ(parse_error(cat({"x = ", std::string(100000, '-'), "1"})), "");
  std::string chain = "if a {}";
  for (int i = 0; i < 20000; ++i) chain += " else if a {}";
  EXPECT_EQ(parse_error(chain), "");
}

TEST(Parser, NestingLimitIsACleanError) {
  const std::string ok = cat({"x = ", std::string(kMaxNesting, '('), "1", std::string(kMaxNesting, ')')});
  EXPECT_EQ(parse_error(ok), "");
  const std::string deep = cat({"x = ", std::string(100000, '(')});
  const std::string error = parse_error(deep);
  EXPECT_EQ(error.substr(0, error.find('\n')), "t.bsp:1:69: error: brackets nested deeper than 64 levels");
  // Brackets inside strings and comments do not count.
  EXPECT_EQ(parse_error(cat({"x = \"", std::string(1000, '('), "\" # ", std::string(1000, '[')})), "");
}

TEST(Parser, ExactMessagesForBadInput) {
  EXPECT_EQ(parse_error("x = (1 + 2"), "t.bsp:1:11: error: expected ')' at end of input\nx = (1 + 2\n          ^\n");
  EXPECT_EQ(parse_error("x = 1 2"), "t.bsp:1:7: error: expected newline or ';' here\nx = 1 2\n      ^\n");
  EXPECT_EQ(parse_error("y = 1\nprint(1 +)"), "t.bsp:2:10: error: expected expression here\nprint(1 +)\n         ^\n");
  EXPECT_EQ(parse_error("fn (a) {}"), "t.bsp:1:4: error: expected name here\nfn (a) {}\n   ^\n");
  EXPECT_EQ(parse_error("for x in xs print(x)"),
            "t.bsp:1:13: error: expected '{' here\nfor x in xs print(x)\n            ^\n");
  EXPECT_EQ(parse_error("for x xs {}"), "t.bsp:1:7: error: expected 'in' here\nfor x xs {}\n      ^\n");
  EXPECT_EQ(parse_error("s = \"abc"), "t.bsp:1:9: error: expected '\"' at end of input\ns = \"abc\n        ^\n");
  EXPECT_EQ(parse_error("s = \"a\\qb\""),
            "t.bsp:1:8: error: expected escape sequence (\\n, \\t, \\\\ or \\\") here\ns = \"a\\qb\"\n       ^\n");
  EXPECT_EQ(parse_error("f(1, )"), "t.bsp:1:6: error: expected argument here\nf(1, )\n     ^\n");
  EXPECT_EQ(parse_error(")"), "t.bsp:1:1: error: expected statement here\n)\n^\n");
  EXPECT_EQ(parse_error("if a { x = }"), "t.bsp:1:12: error: expected expression here\nif a { x = }\n           ^\n");
  EXPECT_EQ(parse_error("if a { b c }"), "t.bsp:1:10: error: expected newline or ';' here\nif a { b c }\n         ^\n");
  EXPECT_EQ(parse_error("x = [1, 2"), "t.bsp:1:10: error: expected ']' at end of input\nx = [1, 2\n         ^\n");
  EXPECT_EQ(parse_error("include x"), "t.bsp:1:9: error: expected string here\ninclude x\n        ^\n");
  EXPECT_EQ(parse_error("x = nan"), "");  // a name, not a number
  EXPECT_EQ(parse_error("fn = 3"), "t.bsp:1:4: error: expected name here\nfn = 3\n   ^\n");
}

// Names are ASCII; a byte >= 128 outside a string or comment is a clean error, never passed to
// the C library's character classes (undefined for a negative char).
TEST(Parser, SlicesAndIndexes) {
  const ast::Program program = parse(text_source("a = v[2]\nb = v[1:]\nc = v[:-1]\nd = v[:]"));
  ASSERT_EQ(program.statements.size(), 4u);
  const auto subscript = [&](std::size_t k) {
    const auto& postfix = boost::get<ast::Postfix>(boost::get<ast::Assignment>(program.statements[k]).value.first);
    return boost::get<ast::Subscript>(postfix.ops.at(0));
  };
  EXPECT_FALSE(subscript(0).slice);
  EXPECT_EQ(subscript(0).where, 5u);  // the '[' of "a = v[2]"
  EXPECT_TRUE(subscript(1).slice);
  EXPECT_TRUE(subscript(1).start && !subscript(1).stop);
  EXPECT_TRUE(subscript(2).slice);
  EXPECT_TRUE(!subscript(2).start && subscript(2).stop);
  EXPECT_TRUE(subscript(3).slice);
  EXPECT_TRUE(!subscript(3).start && !subscript(3).stop);
}

TEST(Parser, SliceAndElementAssignmentErrors) {
  EXPECT_EQ(parse_error("x = v[]"), "t.bsp:1:7: error: expected expression here\nx = v[]\n      ^\n");
  EXPECT_EQ(parse_error("x = v[1:2:3]"), "t.bsp:1:10: error: expected ']' here\nx = v[1:2:3]\n         ^\n");
  const std::string element =
      "error: only a name can be assigned: assignment to an element (x[i] = v) is not supported, lists are values; "
      "build a new list instead, e.g. xs = concat(xs[:i], concat([v], xs[i + 1:]))";
  EXPECT_EQ(parse_error("x = [1, 2]\nx[0] = 5"), "t.bsp:2:6: " + element + "\nx[0] = 5\n     ^\n");
  EXPECT_EQ(parse_error("f(x) = 1"), "t.bsp:1:6: " + element + "\nf(x) = 1\n     ^\n");
}

TEST(Parser, NonAsciiBytesAreErrorsOutsideStringsAndComments) {
  EXPECT_EQ(parse_error("x = \xc3\xa9"), "t.bsp:1:5: error: expected expression here\nx = \xc3\xa9\n    ^\n");
  EXPECT_NE(parse_error("caf\xc3\xa9 = 1"), "");
  EXPECT_EQ(parse_error("s = \"caf\xc3\xa9\"  # \xff\xfe"), "");
}

TEST(Parser, CaretKeepsTabs) {
  EXPECT_EQ(parse_error("\tx = 1 2"), "t.bsp:1:8: error: expected newline or ';' here\n\tx = 1 2\n\t      ^\n");
}

TEST(Parser, UnfinishedInputForTheRepl) {
  EXPECT_TRUE(is_unfinished("fn f(a) {"));
  EXPECT_TRUE(is_unfinished("x = [1,"));
  EXPECT_TRUE(is_unfinished("f(\n  1"));
  EXPECT_FALSE(is_unfinished("fn f(a) { a }"));
  EXPECT_FALSE(is_unfinished("x = \"{\""));
  EXPECT_FALSE(is_unfinished("x = 1 # {"));
  EXPECT_FALSE(is_unfinished("x = )"));
}

}  // namespace
}  // namespace sculpt::language

namespace sculpt::language {
namespace {

TEST(Parser, NumberLiterals) {
  const auto r = testing::run_script("print(1, 2.5, .5, 1., 1e3, 2.5E-2, 1e+2, 007)");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "1 2.5 0.5 1 1000 0.025 100 7\n");
  EXPECT_EQ(testing::run_script("x = 1e400").error, "t.bsp:1:5: error: number too large for a double\nx = 1e400\n    ^\n");
  EXPECT_EQ(testing::run_script("print(1e-400)").out, "0\n");
}

}  // namespace
}  // namespace sculpt::language
