// The REPL session without a terminal: echo of values, errors that keep bindings, multi-line
// entries, commands, completion, line numbers that run on across entries.
#include <gtest/gtest.h>

#include <atomic>
#include <sstream>

#include "language/builtins.hpp"
#include "language/session.hpp"
#include "language/solid_values.hpp"

namespace sculpt::language {
namespace {

struct Fixture {
  std::ostringstream out, err;
  Session session{out, err};
};

TEST(Session, EchoesExpressionsNotAssignments) {
  Fixture f;
  f.session.feed("x = 6");
  f.session.feed("x * 7");
  f.session.feed("\"text\"");
  f.session.feed("print(1)");
  EXPECT_EQ(f.out.str(), "42\n\"text\"\n1\n");
  EXPECT_EQ(f.err.str(), "");
}

// A later grid(step) in a session (docs/language.md, "World range"): a note names the solids that
// keep the old grid, and combining one of them with a new solid is an error naming both grids;
// the session goes on and new solids combine.
TEST(Session, ChangingTheGridLaterSaysWhichSolidsKeepTheOldOne) {
  Fixture f;
  f.session.feed("a = box([0, 0, 0], [1, 1, 1])");
  f.session.feed("b = a | box([0, 0, 0], [2, 1, 1])");
  f.session.feed("grid(pow(2, -13))");
  EXPECT_EQ(f.out.str(), "0.0001220703125\n");
  EXPECT_EQ(
      f.err.str(),
      "note: grid(2^-13): 2 solids (a, b) made at another grid cannot be combined with solids made from now on\n");
  f.err.str("");
  f.session.feed("c = box([0, 0, 0], [3000, 1, 1])");
  f.session.feed("d = a | c");
  EXPECT_NE(f.err.str().find("<stdin>:5:7: error: invalid input: solids made at different grids (step 2^-15 and step 2^-13)"),
            std::string::npos) << f.err.str();
  f.session.feed("volume(c | box([1000, 0, 0], [3500, 1, 1]))");
  EXPECT_NE(f.out.str().find("\n3500\n"), std::string::npos) << f.out.str();
}

TEST(Session, InterruptStopsARunAndDiscardDropsAnUnfinishedEntry) {
  std::ostringstream out, err;
  std::atomic<bool> flag{false};
  Session session(out, err, &flag);
  session.feed("a = 1");
  flag = true;
  session.feed("a = 2");  // stopped before its first step: a keeps its value
  EXPECT_NE(err.str().find("<stdin>:2:1: error: interrupted"), std::string::npos) << err.str();
  flag = false;
  session.feed("b = [a,");
  EXPECT_TRUE(session.continuing());
  EXPECT_TRUE(session.discard_pending());
  EXPECT_FALSE(session.continuing());
  EXPECT_FALSE(session.discard_pending());
  session.feed("a");
  EXPECT_EQ(out.str(), "1\n");
}

TEST(Session, ErrorsKeepBindingsAndNumberLinesOn) {
  Fixture f;
  f.session.feed("a = 1");
  f.session.feed("b = a + )");
  f.session.feed("a + 1");
  f.session.feed("b = a +");  // ends with an operator: the entry goes on
  EXPECT_TRUE(f.session.continuing());
  f.session.feed("  1");
  f.session.feed("b");
  f.session.feed("c = 1 -");
  f.session.feed("");  // an empty line ends it
  EXPECT_FALSE(f.session.continuing());
  EXPECT_EQ(f.err.str(),
            "<stdin>:2:9: error: expected expression here\nb = a + )\n        ^\n"
            "<stdin>:7:8: error: expected expression at end of input\nc = 1 -\n       ^\n");
  EXPECT_EQ(f.out.str(), "2\n2\n");
}

TEST(Session, MultiLineEntries) {
  Fixture f;
  EXPECT_TRUE(f.session.feed("fn twice(x) {"));
  EXPECT_TRUE(f.session.continuing());
  f.session.feed("  2 * x");
  f.session.feed("}");
  EXPECT_FALSE(f.session.continuing());
  f.session.feed("twice(21)");
  EXPECT_EQ(f.out.str(), "42\n");
}

TEST(Session, Commands) {
  Fixture f;
  f.session.feed("r = 2");
  f.session.feed(":vars");
  f.session.feed(":help sqrt");
  f.session.feed(":help sqtr");
  f.session.feed(":halp");
  EXPECT_EQ(f.out.str(),
            "r : number = 2\nsqrt(x)\n  Square root of x >= 0.\n    x: a number\nno built-in or keyword named 'sqtr'; "
            "did you mean 'sqrt'?\n");
  EXPECT_EQ(f.err.str(), "error: unknown command ':halp'; did you mean ':help'? (commands: :help, :load, :vars, :show, :quit)\n");
  EXPECT_FALSE(f.session.feed(":quit"));
}

TEST(Session, HelpOverviewListsEveryBuiltin) {
  const std::string overview = help_text("");
  for (const auto& [name, _] : builtins().entries()) EXPECT_NE(overview.find(" " + name), std::string::npos) << name;
}

TEST(Session, Completion) {
  Fixture f;
  f.session.feed("cylinder_height = 3");
  EXPECT_EQ(f.session.complete("cyl"), (std::vector<std::string>{"cylinder", "cylinder_height", "cylinder_surface"}));
  EXPECT_EQ(f.session.complete("for"), (std::vector<std::string>{"for"}));
  EXPECT_EQ(f.session.complete(":l"), (std::vector<std::string>{":load"}));
}

// Inside a call's parentheses the parameters not yet given are offered as `name=` (issue 36),
// beside the names a positional argument could use.
TEST(Session, CompletionOffersParameterNamesInsideACall) {
  Fixture f;
  f.session.feed("fn plate(width, wall) { box([0, 0, 0], [width, width, wall]) }");
  f.session.feed("seg = 5");
  EXPECT_EQ(f.session.complete("seg", "s = sphere(1, "), (std::vector<std::string>{"seg", "segments="}));
  const auto inside = f.session.complete("", "cylinder(1, 2, segments=8, ");
  EXPECT_EQ(std::count(inside.begin(), inside.end(), "segments="), 0) << "already given";
  EXPECT_EQ(std::count(inside.begin(), inside.end(), "center="), 1);
  EXPECT_EQ(std::count(inside.begin(), inside.end(), "d="), 1);
  // A script's own fn; a nested call completes the inner function; after the call closes, none.
  EXPECT_EQ(f.session.complete("wi", "plate("), (std::vector<std::string>{"width="}));
  EXPECT_EQ(f.session.complete("wa", "plate(3, "), (std::vector<std::string>{"wall="}));
  EXPECT_EQ(f.session.complete("seg", "plate(width=norm([1, 2, 3]), wall=sphere(1, "),
            (std::vector<std::string>{"seg", "segments="}));
  EXPECT_EQ(f.session.complete("seg", "x = sphere(1, 2) | "), (std::vector<std::string>{"seg"}));
  // Parentheses and brackets inside strings do not count.
  EXPECT_EQ(f.session.complete("seg", "print(\"(\", sphere(1, \")\", "),
            (std::vector<std::string>{"seg", "segments="}));
}

TEST(Session, LoadRunsAFile) {
  Fixture f;
  f.session.feed(":load /nonexistent/file.bsp");
  EXPECT_EQ(f.err.str(), "error: /nonexistent/file.bsp: cannot open for reading\n");
}

// A command the layer above adds (the executable's :view): run with its argument, listed by :help,
// suggested for a near miss, completed.
TEST(Session, CommandsAddedFromAbove) {
  Fixture f;
  std::string got = "none";
  f.session.add_command(":view", [&got](const std::string& argument) { got = "ran with '" + argument + "'"; });
  f.session.feed(":view  now ");
  EXPECT_EQ(got, "ran with 'now'");
  f.session.feed(":help");
  EXPECT_NE(f.out.str().find("More commands: :view\n"), std::string::npos);
  f.session.feed(":veiw");
  EXPECT_EQ(
      f.err.str(),
      "error: unknown command ':veiw'; did you mean ':view'? (commands: :help, :load, :vars, :show, :quit, :view)\n");
  const auto names = f.session.complete(":v");
  EXPECT_EQ(names, (std::vector<std::string>{":vars", ":view"}));
}

// The last solid made: the latest solid entry or the global most recently bound to a solid.
TEST(Session, LastSolidFollowsEntriesAndAssignments) {
  Fixture f;
  EXPECT_FALSE(f.session.last_solid());
  f.session.feed("a = box([0, 0, 0], [1, 1, 1])");
  ASSERT_TRUE(f.session.last_solid());
  EXPECT_EQ(f.session.last_solid()->object<SolidValue>(), f.session.interpreter().global("a")->object<SolidValue>());
  f.session.feed("box([0, 0, 0], [2, 2, 2])");
  EXPECT_NE(f.session.last_solid()->object<SolidValue>(), f.session.interpreter().global("a")->object<SolidValue>());
  f.session.feed("b = sphere(1)");
  EXPECT_EQ(f.session.last_solid()->object<SolidValue>(), f.session.interpreter().global("b")->object<SolidValue>());
}

}  // namespace
}  // namespace sculpt::language
