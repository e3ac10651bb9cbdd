// render, plot and the session's :show: files written (decoded and checked), options, errors at
// the argument's position.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "language/session.hpp"
#include "mesh/mesh_io.hpp"
#include "render/camera.hpp"
#include "render/picture.hpp"
#include "render/png_image.hpp"
#include "splines/tessellate_surface.hpp"
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

// The picture is PNG (plot: SVG) whatever the name says: another extension is refused (render's
// before any work) and nothing is written.
TEST(RenderBuiltin, RefusesAFileNameOfAnotherFormat) {
  TempDir dir;
  const std::string jpg = dir.file("x.jpg");
  const std::string error = run_script("render(box([0,0,0],[1,1,1]), \"" + jpg + "\")").error;
  EXPECT_EQ(error.substr(0, error.find('\n')),
            "t.bsp:1:30: error: render: the picture is PNG: the file name must end in .png, not '.jpg'");
  EXPECT_FALSE(fs::exists(jpg));
  const std::string no_extension = run_script("render(box([0,0,0],[1,1,1]), \"" + dir.file("x") + "\")").error;
  EXPECT_NE(no_extension.find("must end in .png, not ''"), std::string::npos) << no_extension;
  EXPECT_EQ(run_script("render(box([0,0,0],[1,1,1]), \"" + dir.file("upper.PNG") + "\")").error, "");
  const std::string svg = run_script("plot([[0, 0], [1, 1]], \"" + dir.file("p.png") + "\")").error;
  EXPECT_NE(svg.find("plot: the picture is SVG: the file name must end in .svg, not '.png'"), std::string::npos) << svg;
  EXPECT_FALSE(fs::exists(dir.file("p.png")));
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
  EXPECT_NE(run_script("render([box([0,0,0],[1,1,1]), 2], " + f + ")").error.find("item 1 must be a solid, mesh, surface"),
            std::string::npos);
  EXPECT_NE(run_script("render(sphere_surface([0,0,0], 1), " + f + ")").error.find("cannot draw sphere"), std::string::npos);
  EXPECT_NE(run_script("render(box([0,0,0],[1,1,1]), " + f + ", tol=-1)")
                .error.find("argument 'tol' must be a finite number >= 0, got -1"),
            std::string::npos);
  EXPECT_NE(run_script("render([], " + f + ")").error.find("the list is empty"), std::string::npos);
  EXPECT_NE(run_script("render(box([0,0,0],[1,1,1]), " + f + ", view=[0, 0, 0])").error.find("nonzero"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.file("x.png")));
  InterpreterOptions no_files;
  no_files.allow_files = false;
  EXPECT_NE(run_script("render(box([0,0,0],[1,1,1]), \"a.png\")", no_files).error.find("disabled"), std::string::npos);
}

long count_colour(const render::Image& image, const std::array<std::uint8_t, 3>& c) {
  long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.pixel(x, y) == c;
  return n;
}

TEST(RenderBuiltin, SplineOnTheFarSideOfASphereIsHiddenOnTheNearSideDrawn) {
  // Splines on the sphere through points mirrored in the plane y = 0: seen from the front (from
  // -y) they project to the same place; the near one is drawn through its points, the far one
  // not at all.
  TempDir dir;
  const std::string points = "[[0.6, Y, 0], [0, Y, 0.6], [-0.6, Y, 0], [0, Y, -0.6]]";
  auto with = [&](const std::string& y) {
    std::string p = points;
    for (std::size_t k; (k = p.find('Y')) != std::string::npos;) p.replace(k, 1, y);
    return p;
  };
  const std::string options = ", view=\"front\", size=[200, 200], scale=80)\n";
  const auto r = run_script("s = sphere_surface([0, 0, 0], 1)\n"
                            "render([sphere(1, 64), surface_spline(s, " + with("-0.8") + ")], \"" + dir.file("near.png") + "\"" + options +
                            "render([sphere(1, 64), surface_spline(s, " + with("0.8") + ")], \"" + dir.file("far.png") + "\"" + options +
                            "render(sphere(1, 64), \"" + dir.file("alone.png") + "\"" + options);
  ASSERT_EQ(r.error, "");
  const render::Image near = render::read_png(dir.file("near.png"));
  const render::Image far = render::read_png(dir.file("far.png"));
  EXPECT_EQ(far.rgb, render::read_png(dir.file("alone.png")).rgb);
  const render::Camera camera = render::picture_camera_for_points(
      {}, {.view = render::view_direction("front"), .width = 200, .height = 200, .scale = 80});
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.6, -0.8, 0), Eigen::Vector3d(0, -0.8, 0.6), Eigen::Vector3d(-0.6, -0.8, 0)}) {
    const Eigen::Vector3d q = camera.project(p);
    EXPECT_EQ(near.pixel(static_cast<int>(q.x()), static_cast<int>(q.y())), render::curve_colour(1)) << p.transpose();
  }
  EXPECT_GT(count_colour(near, render::curve_colour(1)), 300);
}

TEST(RenderBuiltin, RendersSurfacesAndEveryKindOfCurve) {
  TempDir dir;
  const auto r = run_script(
      "p = bspline_surface([[[-1,-1,1],[-1,0,-1],[-1,1,1]],[[0,-1,-1],[0,0,-3],[0,1,-1]],[[1,-1,1],[1,0,-1],[1,1,1]]], degree=2)\n"
      "c = curve([[-1,-1,2],[0,-1,2.5],[1,-1,2]])\n"
      "m = motion([[[-1, 1, 2], [0, 0, 1, 0]], [[1, 1, 2], [0, 0, 1, 90]]])\n"
      "items = [p, geodesic(p, [-0.8, -0.8, 0], [0.7, 0.8, 0]), c, linearize(curve([[-1,-1,-2],[0,-1,-2.5],[0.5,-1,-2.2],[1,-1,-2]]), 2), m, [[-1,0,3],[1,0,3]], surface_mesh(p, 0.01)]\n"
      "render(items, \"" + dir.file("all.png") + "\", size=[320, 240])\n"
      "render(items, \"" + dir.file("again.png") + "\", size=[320, 240])\n"
      "render(p, \"" + dir.file("coarse.png") + "\", size=[320, 240], tol=0.2, width=5)\n");
  ASSERT_EQ(r.error, "");
  const render::Image all = render::read_png(dir.file("all.png"));
  for (std::size_t k = 1; k <= 5; ++k) EXPECT_GT(count_colour(all, render::curve_colour(k)), 20) << k;
  EXPECT_EQ(all.rgb, render::read_png(dir.file("again.png")).rgb);
  EXPECT_EQ(covered(render::read_png(dir.file("coarse.png"))) > 0, true);
}

TEST(RenderBuiltin, ExportedSurfaceReadsBackAsItsTessellationBitExact) {
  TempDir dir;
  fs::create_directories(dir.path);
  const std::string rows = "[[[-1,-1,1],[-1,0,-1],[-1,1,1]],[[0,-1,-1],[0,0.3,-3],[0,1,-1]],[[1,-1,1],[1,0,-1],[1,1,1]]]";
  const auto r = run_script("p = bspline_surface(" + rows + ", degree=2)\n"
                            "export(p, \"" + dir.file("p.obj") + "\", tol=0.01)\n"
                            "export(p, \"" + dir.file("p.off") + "\", tol=0.01)\n"
                            "export(p, \"" + dir.file("p.ply") + "\", tol=0.01)\n"
                            "export(p, \"" + dir.file("default.obj") + "\")\n");
  ASSERT_EQ(r.error, "");
  // The reference: the splines layer's tessellation of the same surface (rows are u).
  const std::vector<Eigen::Vector3d> controls = {{-1, -1, 1}, {-1, 0, -1}, {-1, 1, 1}, {0, -1, -1}, {0, 0.3, -3},
                                                 {0, 1, -1},  {1, -1, 1},  {1, 0, -1}, {1, 1, 1}};
  const auto surface = splines::BSplineSurface::uniform({2, 2}, 3, 3, controls);
  for (const char* name : {"p.obj", "p.off", "p.ply"}) {
    const auto t = splines::tessellate(surface, {.tolerance = 0.01});
    const PolygonMesh mesh = read_mesh(dir.file(name));
    ASSERT_EQ(mesh.vertices.size(), t.points.size()) << name;
    for (std::size_t i = 0; i < t.points.size(); ++i) ASSERT_EQ(mesh.vertices[i], t.points[i]) << name << " " << i;
    ASSERT_EQ(mesh.faces.size(), t.triangles.size());
    for (std::size_t f = 0; f < t.triangles.size(); ++f)
      ASSERT_EQ(mesh.faces[f], (std::vector<int>{t.triangles[f][0], t.triangles[f][1], t.triangles[f][2]})) << name;
  }
  EXPECT_EQ(read_mesh(dir.file("default.obj")).vertices.size(), splines::tessellate(surface, {.tolerance = 1e-3}).points.size());
  EXPECT_NE(run_script("export(box([0,0,0],[1,1,1]), \"" + dir.file("b.obj") + "\", tol=0.1)").error.find("tol applies to surfaces only"),
            std::string::npos);
  EXPECT_NE(run_script("export(bspline_surface(" + rows + ", degree=2), \"" + dir.file("b.obj") + "\", tol=0)")
                .error.find("argument 'tol' must be a finite number > 0, got 0"),
            std::string::npos);
}

TEST(RenderBuiltin, PlotsCurvesLinearizationsSplinesAndPoints) {
  TempDir dir;
  const auto r = run_script(
      "c = curve([[0,0],[1,1],[2,0],[3,1],[4,0]])\n"
      "plot([c, linearize(curve([[-1,-1,-2],[0,-1,-2.5],[0.5,-1,-2.2],[1,-1,-2]]), 2), bspline([[0,0],[1,2],[2,0],[3,2]]), [[0,1],[4,1]]], \"" + dir.file("p.svg") +
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
  EXPECT_EQ(err.str(),
            "error: :show: 'n' must be a solid, mesh, surface, spline, curve, linearization, motion or list "
            "of points, not number\n");
  // What render draws, :show draws: a spline and a list of points, and a list mixing kinds.
  out.str("");
  session.feed("s = bspline([[0, 0], [1, 2], [2, -1], [3, 0]])");
  session.feed(":show s");
  EXPECT_EQ(out.str(), (dir.path / "s.png").string() + "\n");
  const render::Image spline = render::read_png(dir.path / "s.png");
  long drawn = 0;
  for (std::size_t i = 0; i < spline.rgb.size(); i += 3) drawn += spline.rgb[i] != 255 || spline.rgb[i + 1] != 255;
  EXPECT_GT(drawn, 500) << "the curve is drawn";
  out.str("");
  session.feed("mixed = [a, [[0, 0, 2], [1, 1, 2]], s]");
  session.feed(":show mixed");
  EXPECT_EQ(out.str(), (dir.path / "mixed.png").string() + "\n");
  err.str("");
  session.feed(":show nothing");
  EXPECT_NE(err.str().find("no variable named 'nothing'"), std::string::npos);
  err.str("");
  session.feed(":show a sideways");
  EXPECT_NE(err.str().find("unknown view"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::language
