// render, plot and the session's :show: files written (decoded and checked), options, errors at
// the argument's position.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "language/session.hpp"
#include "render/png_image.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::run_script;
namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("sculpt_render_builtin_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                               "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  TempDir() { fs::remove_all(path); }
  ~TempDir() { fs::remove_all(path); }
  [[nodiscard]] std::string file(const std::string& name) const { return (path / name).string(); }
};

long covered(const render::Image& image) {
  long n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) n += !(image.rgb[i] == 255 && image.rgb[i + 1] == 255 && image.rgb[i + 2] == 255);
  return n;
}

TEST(RenderBuiltin, WritesAPictureOfTheRequestedSize) {
  TempDir dir;
  const auto r = run_script("render(box([0,0,0],[1,1,1]), \"" + dir.file("sub/b.png") + "\", size=[64, 48])\n"
                            "render([sphere(1), translate(box([0,0,0],[1,1,1]), [2,0,0])], \"" + dir.file("two.png") +
                            "\", view=[1, 2, 3], edges=false)\n"
                            "render(box([-1,-1,-1],[1,1,1]), \"" + dir.file("top.png") +
                            "\", view=\"top\", size=[40, 40], scale=10)\n");
  ASSERT_EQ(r.error, "");
  const render::Image b = render::read_png(dir.file("sub/b.png"));
  EXPECT_EQ(b.width, 64);
  EXPECT_EQ(b.height, 48);
  EXPECT_GT(covered(b), 0);
  const render::Image two = render::read_png(dir.file("two.png"));
  EXPECT_EQ(two.width, 800);
  EXPECT_EQ(two.height, 600);
  // A 2 x 2 square at 10 px per unit, centred: exactly 20 x 20 pixels.
  EXPECT_EQ(covered(render::read_png(dir.file("top.png"))), 400);
}

TEST(RenderBuiltin, ErrorsPointAtTheArgument) {
  TempDir dir;
  std::string f = "\"";
  f += dir.file("x.png");
  f += "\"";
  const std::string bad_view = run_script("render(box([0,0,0],[1,1,1]), \"x.png\", view=\"sideways\")").error;
  EXPECT_EQ(bad_view.rfind("t.bsp:1:", 0), 0u) << bad_view;
  EXPECT_NE(bad_view.find("error: render: unknown view 'sideways'"), std::string::npos) << bad_view;
  EXPECT_NE(run_script("render(box([0,0,0],[1,1,1]), " + f + ", size=[0, 10])").error.find("size must be"), std::string::npos);
  EXPECT_NE(run_script("render(1, " + f + ")").error.find("t.bsp:1:8: error"), std::string::npos);
  EXPECT_NE(run_script("render([box([0,0,0],[1,1,1]), 2], " + f + ")").error.find("item 1 of the list is not a solid"),
            std::string::npos);
  EXPECT_NE(run_script("render(box([0,0,0],[1,1,1]), " + f + ", view=[0, 0, 0])").error.find("nonzero"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.file("x.png")));
  InterpreterOptions no_files;
  no_files.allow_files = false;
  EXPECT_NE(run_script("render(box([0,0,0],[1,1,1]), \"a.png\")", no_files).error.find("disabled"), std::string::npos);
}

TEST(RenderBuiltin, PlotsCurvesLinearizationsSplinesAndPoints) {
  TempDir dir;
  const auto r = run_script(
      "c = curve([[0,0],[1,1],[2,0],[3,1],[4,0]])\n"
      "plot([c, linearize(c, 2), bspline([[0,0],[1,2],[2,0],[3,2]]), [[0,1],[4,1]]], \"" + dir.file("p.svg") +
      "\", title=\"a & b\")\n"
      "plot([[0,0,0],[1,1,1]], \"" + dir.file("q.svg") + "\")\n");
  ASSERT_EQ(r.error, "");
  std::ifstream in(dir.file("p.svg"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string svg = text.str();
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("a &amp; b"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);  // the control polygon
  EXPECT_TRUE(fs::exists(dir.file("q.svg")));
  EXPECT_NE(run_script("plot(box([0,0,0],[1,1,1]), \"" + dir.file("r.svg") + "\")").error.find("not solid"), std::string::npos);
}

TEST(RenderBuiltin, SessionShowRendersANamedOrTheLastSolid) {
  TempDir dir;
  std::ostringstream out, err;
  Session session(out, err);
  session.set_show_directory(dir.path);
  session.feed(":show");
  EXPECT_NE(err.str().find("no solid made yet"), std::string::npos);
  session.feed("a = box([0,0,0],[1,1,1])");
  session.feed("n = 3");
  session.feed("b = sphere(1)");
  session.feed(":show a");
  EXPECT_EQ(out.str(), (dir.path / "a.png").string() + "\n");
  EXPECT_TRUE(fs::exists(dir.path / "a.png"));
  out.str("");
  session.feed(":show");  // b was bound last
  EXPECT_EQ(out.str(), (dir.path / "b.png").string() + "\n");
  out.str("");
  session.feed("a | b");  // an expression value is newer
  session.feed(":show");
  EXPECT_NE(out.str().find((dir.path / "last.png").string()), std::string::npos);
  out.str("");
  session.feed(":show a top");
  EXPECT_EQ(out.str(), (dir.path / "a.png").string() + "\n");
  out.str("");
  session.feed("parts = [a, translate(b, [3, 0, 0])]");
  session.feed(":show parts front");
  EXPECT_EQ(out.str(), (dir.path / "parts.png").string() + "\n");
  const render::Image parts = render::read_png(dir.path / "parts.png");
  EXPECT_EQ(parts.width, 800);
  err.str("");
  session.feed(":show n");
  EXPECT_NE(err.str().find("'n' is a number, not a solid"), std::string::npos) << err.str();
  err.str("");
  session.feed(":show nothing");
  EXPECT_NE(err.str().find("no variable named 'nothing'"), std::string::npos);
  err.str("");
  session.feed(":show a sideways");
  EXPECT_NE(err.str().find("unknown view"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::language
