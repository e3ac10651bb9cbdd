// docs/language.md documents every built-in and keyword: each has a heading line "### name"
// (built-ins) or appears in backquotes (keywords), so the reference cannot drift from the table.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "language/builtins.hpp"
#include "script_runner.hpp"
#include "support/source_paths.hpp"

namespace sculpt::language {
namespace {

std::string read_doc(const std::string& name) {
  std::ifstream in(sculpt::test::source_dir() + "/docs/" + name);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string reference() { return read_doc("language.md"); }

TEST(Docs, ReferenceCoversEveryBuiltin) {
  const std::string doc = reference();
  ASSERT_FALSE(doc.empty()) << "docs/language.md is missing";
  for (const auto& [name, b] : builtins().entries()) {
    EXPECT_NE(doc.find("\n### `" + b.signature + "`"), std::string::npos)
        << "docs/language.md needs a heading ### `" << b.signature << "`";
  }
}

TEST(Docs, ReferenceMentionsEveryKeyword) {
  const std::string doc = reference();
  for (const char* k : keywords()) EXPECT_NE(doc.find(std::string("`") + k), std::string::npos) << k;
}

TEST(Docs, ReferenceHasNoStaleBuiltins) {
  // Every "### `name(...)`" heading in the built-in sections names an existing built-in.
  const std::string doc = reference();
  std::istringstream lines(doc);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("### `", 0) != 0) continue;
    const std::string signature = line.substr(5, line.rfind('`') - 5);
    const std::string name = signature.substr(0, signature.find('('));
    EXPECT_NE(builtins().find(name), nullptr) << "docs/language.md documents unknown built-in " << name;
  }
}

// The examples of docs/from_openscad.md (its ```sculpt blocks) run without error, each on its own.
TEST(Docs, OpenScadPageExamplesRun) {
  const std::string doc = read_doc("from_openscad.md");
  ASSERT_FALSE(doc.empty()) << "docs/from_openscad.md is missing";
  const std::string open = "```sculpt\n", close = "```";
  int blocks = 0;
  for (std::size_t at = doc.find(open); at != std::string::npos; at = doc.find(open, at)) {
    const std::size_t begin = at + open.size(), end = doc.find(close, begin);
    ASSERT_NE(end, std::string::npos) << "an unclosed ```sculpt block";
    const auto result = testing::run_script(doc.substr(begin, end - begin));
    EXPECT_EQ(result.error, "") << doc.substr(begin, end - begin);
    EXPECT_FALSE(result.out.empty()) << "each example prints what it made";
    ++blocks;
    at = end + close.size();
  }
  EXPECT_GE(blocks, 3);
}

}  // namespace
}  // namespace sculpt::language
