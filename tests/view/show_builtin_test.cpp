// show(x, name=, color=) (lib/language/builtins_view.cpp): what it collects, replacing by name,
// colours, refusals.
#include <gtest/gtest.h>

#include <sstream>

#include "language/interpreter.hpp"
#include "language/source.hpp"

namespace sculpt::language {
namespace {

SourcePtr code(const std::string& text) {
  auto source = std::make_shared<SourceFile>();
  source->name = "test.bsp";
  source->text = text;
  return source;
}

TEST(ShowBuiltin, CollectsNamedColouredParts) {
  std::ostringstream out;
  Interpreter interpreter({.out = &out});
  interpreter.run(
      code("a = show(box([0, 0, 0], [1, 1, 1]), name=\"base\", color=\"#ff8000\")\n"
           "show(sphere(1), color=[0, 0.5, 1])\n"
           "show([box([0, 0, 0], [1, 1, 1]), box([2, 0, 0], [3, 1, 1])], name=\"pair\", color=\"red\")\n"));
  const auto& shown = interpreter.shown();
  ASSERT_EQ(shown.size(), 4u);
  EXPECT_EQ(shown[0].name, "base");
  EXPECT_DOUBLE_EQ((*shown[0].color)[1], 128 / 255.0);
  EXPECT_EQ(shown[1].name, "part 2");
  EXPECT_DOUBLE_EQ((*shown[1].color)[2], 1.0);
  EXPECT_EQ(shown[2].name, "pair 1");
  EXPECT_EQ(shown[3].name, "pair 2");
  EXPECT_EQ(type_name(*interpreter.global("a")), "solid");  // show returns its argument
  // Showing a name again replaces it in place.
  interpreter.run(code("show(sphere(2), name=\"base\")"));
  ASSERT_EQ(interpreter.shown().size(), 4u);
  EXPECT_FALSE(interpreter.shown()[0].color);
}

TEST(ShowBuiltin, TakesWhatRenderDraws) {
  std::ostringstream out;
  Interpreter interpreter({.out = &out, .err = &out});
  interpreter.run(
      code("c = bspline([[0, 0], [1, 1], [2, 0]], degree=2)\n"
           "show(c, name=\"spline\")\n"
           "show([[0, 0], [1, 0], [1, 1]], name=\"points\")\n"
           "show([c, [[0, 0, 0], [0, 0, 1]]], name=\"two\")\n"
           "show(bspline_surface([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]], degree=1))\n"));
  const auto& shown = interpreter.shown();
  ASSERT_EQ(shown.size(), 5u);
  EXPECT_EQ(shown[1].name, "points");  // a list of points is one part
  EXPECT_EQ(shown[2].name, "two 1");
  EXPECT_EQ(shown[3].name, "two 2");
  EXPECT_EQ(type_name(shown[4].value), "surface");
}

TEST(ShowBuiltin, RefusesWhatItCannotShow) {
  std::ostringstream out;
  Interpreter interpreter({.out = &out});
  const char* bad[] = {"show(1)",
                       "show([[0, 0], [1, \"a\"]])",
                       "show([box([0, 0, 0], [1, 1, 1]), [1, 2]])",
                       "show([])",
                       "show([box([0, 0, 0], [1, 1, 1]), 2])",
                       "show(box([0, 0, 0], [1, 1, 1]), color=\"mauve\")",
                       "show(box([0, 0, 0], [1, 1, 1]), color=[2, 0, 0])",
                       "show(box([0, 0, 0], [1, 1, 1]), color=\"#12345g\")",
                       "show(box([0, 0, 0], [1, 1, 1]), name=\"\")"};
  for (const char* text : bad) {
    EXPECT_THROW(interpreter.run(code(text)), ScriptError) << text;
  }
  EXPECT_TRUE(interpreter.shown().empty());
}

}  // namespace
}  // namespace sculpt::language
