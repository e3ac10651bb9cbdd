// Ctrl-C in scripts (base/cancel.hpp, issue 35): a request made while a statement's built-in works
// stops the statement with "interrupted" and leaves every variable as it was; printing a solid
// whose tree is still to be merged does not merge it.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <string>
#include <thread>

#include "base/cancel.hpp"
#include "bsp/boundary.hpp"
#include "language/interpreter.hpp"
#include "language/solid_values.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::text_source;

class Interrupt : public ::testing::Test {
 protected:
  void SetUp() override { clear_cancel(); }
  void TearDown() override { clear_cancel(); }
  std::ostringstream out;
  Interpreter interpreter{{.out = &out, .interrupt = cancel_request_flag()}};
  const SolidValue* solid(const std::string& name) {
    const Value* v = interpreter.global(name);
    return v ? v->object<SolidValue>() : nullptr;
  }
};

TEST_F(Interrupt, StopsALargeUnionAndKeepsTheVariables) {
  interpreter.run(text_source("a = sphere(1, 400)\nb = translate(a, [0.5, 0, 0])\nc = 1"));
  const SolidValue* a = solid("a");
  ASSERT_NE(a, nullptr);
  const double a_volume = volume(a->solid);
  std::thread asker([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    request_cancel();
  });
  std::string error;
  try {
    interpreter.run(text_source("c = a | b\nprint(volume(c))"));
  } catch (const ScriptError& e) {
    error = format_error(e);
  }
  asker.join();
  clear_cancel();
  EXPECT_NE(error.find("error: interrupted"), std::string::npos) << error;
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(solid("a"), a);  // the same value, untouched
  EXPECT_EQ(volume(a->solid), a_volume);
  ASSERT_NE(interpreter.global("c"), nullptr);
  EXPECT_EQ(*interpreter.global("c")->get<double>(), 1.0);  // not assigned
  interpreter.run(text_source("d = a - translate(box([-2, -2, -2], [2, 2, 2]), [0, 0, 2.5])"));
  EXPECT_NE(solid("d"), nullptr);  // the session goes on
}

TEST_F(Interrupt, PrintingAPendingSolidDoesNotBuildItsTree) {
  interpreter.run(text_source("s = sphere(1, 64)\nu = s | translate(s, [0.5, 0, 0])\nprint(u)"));
  EXPECT_EQ(out.str(), "<solid: tree pending>\n");
  const SolidValue* u = solid("u");
  ASSERT_NE(u, nullptr);
  EXPECT_TRUE(u->solid.tree_deferred());
  EXPECT_EQ(u->repr(), "<solid: tree pending>");
  EXPECT_TRUE(u->solid.tree_deferred());
  (void)u->solid.nodes();  // built on first use; then shown as before
  EXPECT_EQ(u->repr().rfind("<solid: ", 0), 0u);
  EXPECT_NE(u->repr().find(" nodes, height "), std::string::npos);
}

}  // namespace
}  // namespace sculpt::language
