// Built-ins are declarations (builtins.hpp, Param): the signature is made from the parameters,
// defaults come from the libraries' option structs, arguments are read by name, and the shared
// checks are made once, before the built-in runs, with the error at the argument. The expected
// texts below are written out by hand from the declarations, not taken from the code's output.
#include <gtest/gtest.h>

#include <sstream>

#include "bsp/primitives.hpp"
#include "implicit/trace.hpp"
#include "language/builtins.hpp"
#include "language/session.hpp"
#include "language/suggest.hpp"
#include "script_runner.hpp"
#include "splines/fit.hpp"

namespace sculpt::language {
namespace {

using testing::run_script;

Builtin probe() {
  return {.name = "probe",
          .doc = "A built-in of this test.",
          .params = {arg("r").positive(), arg("n").integer(3, 10).defaults(5.0), arg("tol").positive().optional("e"),
                     arg("mode").string().defaults("fast"), arg("file").string().shown_as("\"f.txt\"").optional()},
          .run = [](const Arguments&) -> Value { return {}; }};
}

TEST(Declarations, SignatureFollowsFromTheParameters) {
  BuiltinTable table;
  table.add(probe());
  EXPECT_EQ(table.find("probe")->signature, "probe(r, n=5, tol=e, mode=\"fast\", \"f.txt\")");
  table.add({.name = "many", .doc = "d", .variadic = true, .run = [](const Arguments&) -> Value { return {}; }});
  EXPECT_EQ(table.find("many")->signature, "many(a, b, ...)");
  table.add({.name = "k", .doc = "d", .constant = Value(2.0)});
  EXPECT_EQ(table.find("k")->signature, "k");
}

TEST(Declarations, EveryBuiltinSignatureShowsItsParametersInOrder) {
  for (const auto& [name, b] : builtins().entries()) {
    if (name == "circle") continue;  // two forms, circle(n) or circle(r, n): written by hand
    std::size_t at = name.size();
    for (const Param& p : b.params) {
      const std::size_t found = b.signature.find(p.signature(), at);
      EXPECT_NE(found, std::string::npos) << name << ": " << p.signature() << " in " << b.signature;
      if (found != std::string::npos) at = found + p.signature().size();
    }
  }
}

TEST(Declarations, DefaultsComeFromTheLibrariesOptions) {
  EXPECT_EQ(builtins().find("sphere")->signature, "sphere(r, segments=32, d=diameter)");
  const std::string segments = "segments=" + std::to_string(CircularOptions{}.segments);
  for (const char* name : {"sphere", "cylinder", "cone"})
    EXPECT_NE(builtins().find(name)->signature.find(segments), std::string::npos) << name;
  EXPECT_NE(builtins().find("fit")->signature.find("degree=" + std::to_string(splines::FitOptions{}.degree)),
            std::string::npos);
  EXPECT_NE(builtins().find("trace")->signature.find("steps=" + std::to_string(implicit::TraceOptions{}.max_steps)),
            std::string::npos);
}

/// Binds `values` (null: left out) to probe's parameters as the interpreter would.
Arguments bind(const Builtin& b, const std::vector<const Value*>& values, const RunSettings& settings) {
  const SourcePtr source = testing::text_source("probe(...)");
  std::vector<SourceRef> positions;
  for (std::size_t i = 0; i < values.size(); ++i) positions.push_back({source, 10 * (i + 1)});
  return Arguments(b, {source, 0}, values, positions, {}, {}, settings);
}

TEST(Declarations, ArgumentsAreReadByNameWithTheirDefaults) {
  const Builtin b = probe();
  const RunSettings settings;
  const Value r = 2.5;
  const Arguments args = bind(b, {&r, nullptr, nullptr, nullptr, nullptr}, settings);
  EXPECT_TRUE(args.has("r"));
  EXPECT_FALSE(args.has("n"));
  EXPECT_EQ(args.number("r"), 2.5);
  EXPECT_EQ(args.integer("n"), 5);
  EXPECT_EQ(args.string("mode"), "fast");
  EXPECT_TRUE(args.value("tol").is_none());
  EXPECT_THROW((void)args.has("radius"), std::logic_error);  // not declared: a programming error
}

TEST(Declarations, ChecksAreMadeOnceAtTheArgument) {
  const Builtin b = probe();
  const RunSettings settings;
  const auto error = [&](const std::vector<const Value*>& values) {
    try {
      (void)bind(b, values, settings);
    } catch (const ScriptError& e) {
      return std::to_string(e.where().offset) + " " + e.what();
    }
    return std::string("no error");
  };
  const Value zero = 0.0, two = 2.0, half = 3.5, eleven = 11.0, text = "x";
  EXPECT_EQ(error({&zero, nullptr, nullptr, nullptr, nullptr}),
            "10 probe: argument 'r' must be a finite number > 0, got 0");
  EXPECT_EQ(error({&two, &half, nullptr, nullptr, nullptr}),
            "20 probe: argument 'n' must be a whole number from 3 to 10, got 3.5");
  EXPECT_EQ(error({&two, &eleven, nullptr, nullptr, nullptr}),
            "20 probe: argument 'n' must be a whole number from 3 to 10, got 11");
  EXPECT_EQ(error({&two, nullptr, &text, nullptr, nullptr}),
            "30 probe: argument 'tol' must be a finite number > 0, got string");
  EXPECT_EQ(error({&two, nullptr, nullptr, &two, nullptr}), "40 probe: argument 'mode' must be a string, got number");
  EXPECT_EQ(error({&two, nullptr, nullptr, nullptr, nullptr}), "no error");
}

TEST(Declarations, ScriptErrorsPointAtTheArgument) {
  const auto first_line = [](const std::string& text) {
    const std::string e = run_script(text).error;
    return e.substr(0, e.find('\n'));
  };
  // Columns counted by hand: the -1 of sphere(-1) is at 12, the 2 of sphere(1, 2) at 15.
  EXPECT_EQ(first_line("x = sphere(-1)"),
            "t.bsp:1:12: error: sphere: argument 'r' must be a finite number > 0, got -1");
  EXPECT_EQ(first_line("x = sphere(1, 2)"),
            "t.bsp:1:15: error: sphere: argument 'segments' must be a whole number from 3 to 100000, got 2");
  EXPECT_EQ(first_line("s = sphere_surface([0, 0, 0], 0)"),
            "t.bsp:1:31: error: sphere_surface: argument 'r' must be a finite number > 0, got 0");
  EXPECT_EQ(first_line("x = range(0, 1, \"a\")"),
            "t.bsp:1:17: error: range: argument 'step' must be a number, got string");
}

TEST(Declarations, HelpListsWhatEachParameterTakes) {
  EXPECT_EQ(help_text("norm"), "norm(v)\n  Euclidean length of a 3-vector.\n    v: a vector of 3 numbers\n");
  const std::string sphere = help_text("sphere");
  EXPECT_NE(sphere.find("\n    r: a finite number > 0\n"), std::string::npos) << sphere;
  EXPECT_NE(sphere.find("\n    segments: a whole number from 3 to 100000\n"), std::string::npos) << sphere;
}

TEST(Suggestions, SharedPrefixOrLettersInOrderRankAboveShortEditDistances) {
  const std::vector<std::string> names = {"round", "bounds", "box", "cylinder", "cone", "sqrt", "linearize", "line_x"};
  // Without bounds among the names, "bounds" is two edits from "round" but shares nothing else.
  EXPECT_EQ(closest_name("bounds", {"round", "box", "sphere"}), std::nullopt);
  EXPECT_EQ(closest_name("bound", names), "bounds");      // a prefix, though "round" is as near
  EXPECT_EQ(closest_name("cylnder", names), "cylinder");  // a prefix of three letters
  EXPECT_EQ(closest_name("linrz", names), "linearize");   // letters in order
  EXPECT_EQ(closest_name("sqtr", names), "sqrt");         // one swap
  EXPECT_EQ(closest_name("x", names), std::nullopt);
  EXPECT_EQ(help_text("bounds").rfind("bounds(x)\n", 0), 0u);
}

}  // namespace
}  // namespace sculpt::language
