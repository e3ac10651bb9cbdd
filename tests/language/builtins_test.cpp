// Built-ins checked by independent references: analytic volumes and areas, set identities,
// invariants of linearizations (segment counts, monotone error, optimal <= heuristics), file
// round trips. Errors from the libraries below appear at the script position of the call.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "language/builtins.hpp"
#include "script_runner.hpp"
#include "support/scratch_path.hpp"
#include "support/source_paths.hpp"

namespace sculpt::language {
namespace {

using testing::first_error_line;
using testing::numbers;
using testing::run_script;

TEST(Builtins, TableEntriesAreComplete) {
  for (const auto& [name, b] : builtins().entries()) {
    EXPECT_FALSE(b.signature.empty()) << name;
    EXPECT_FALSE(b.doc.empty()) << name;
    EXPECT_EQ(b.signature.rfind(name, 0), 0u) << "signature starts with the name: " << name;
    EXPECT_TRUE(b.run || b.constant) << name;
  }
}

TEST(Builtins, CoreFunctions) {
  EXPECT_EQ(run_script("print(str(1.5) + \"x\", type([]), type(print), len(\"abc\"), range(0, 3), range(3, 0, -1))").out,
            "1.5x list function 3 [0, 1, 2] [3, 2, 1]\n");
  EXPECT_EQ(run_script("print(append([1], 2), concat([1], [2, 3]), min(3, 1, 2), max([4, 9]), abs(-2))").out,
            "[1, 2] [1, 2, 3] 1 9 2\n");
  const auto v = numbers("print(sqrt(2), floor(-1.5), ceil(-1.5), round(2.5), sin(pi / 2), cos(0), pow(2, 0.5), atan2(1, 1))");
  ASSERT_EQ(v.size(), 8u);
  EXPECT_EQ(v[0], std::sqrt(2.0));
  EXPECT_EQ(v[1], -2);
  EXPECT_EQ(v[2], -1);
  EXPECT_EQ(v[3], 3);
  EXPECT_EQ(v[4], 1);
  EXPECT_EQ(v[5], 1);
  EXPECT_EQ(v[6], std::sqrt(2.0));
  EXPECT_EQ(v[7], std::atan(1.0));
  EXPECT_EQ(run_script("print(dot([1, 2, 3], [4, 5, 6]), cross([1, 0, 0], [0, 1, 0]), norm([3, 4, 0]))").out,
            "32 [0, 0, 1] 5\n");
  const auto t = numbers("t0 = clock()\nt1 = clock()\nprint(t1 - t0)");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_GE(t[0], 0);
  EXPECT_EQ(first_error_line("assert(1 > 2, \"one is not above two\")"),
            "t.bsp:1:1: error: assert: one is not above two");
}

// Inverse trigonometric functions in radians (like sin and cos), logarithms and powers of 2,
// against values known in closed form.
TEST(Builtins, MathFunctionsHaveTheirAnalyticValues) {
  const auto v = numbers(
      "print(acos(0), acos(-1), asin(1), asin(-0.5), atan(1), atan2(-1, 0), log(exp(2)), exp2(10), exp2(-1), "
      "sign(-3), sign(0), sign(0.25), hypot(3, 4), hypot(1e200, 1e200))");
  ASSERT_EQ(v.size(), 14u);
  const double pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(v[0], pi / 2);
  EXPECT_DOUBLE_EQ(v[1], pi);
  EXPECT_DOUBLE_EQ(v[2], pi / 2);
  EXPECT_DOUBLE_EQ(v[3], -pi / 6);
  EXPECT_DOUBLE_EQ(v[4], pi / 4);
  EXPECT_DOUBLE_EQ(v[5], -pi / 2);
  EXPECT_DOUBLE_EQ(v[6], 2);
  EXPECT_EQ(v[7], 1024);
  EXPECT_EQ(v[8], 0.5);
  EXPECT_EQ(v[9], -1);
  EXPECT_EQ(v[10], 0);
  EXPECT_EQ(v[11], 1);
  EXPECT_EQ(v[12], 5);
  EXPECT_DOUBLE_EQ(v[13], 1e200 * std::sqrt(2.0));  // no overflow in between
}

TEST(Builtins, MathDomainErrorsAtTheArgument) {
  EXPECT_EQ(first_error_line("x = acos(2)"), "t.bsp:1:10: error: acos: argument 2 is outside [-1, 1]");
  EXPECT_EQ(first_error_line("x = 1 +  asin(-1.5)"), "t.bsp:1:15: error: asin: argument -1.5 is outside [-1, 1]");
  EXPECT_EQ(first_error_line("x = log(0)"), "t.bsp:1:9: error: log: logarithm of 0, which is not > 0");
  EXPECT_EQ(first_error_line("x = log(-2)"), "t.bsp:1:9: error: log: logarithm of -2, which is not > 0");
  EXPECT_EQ(first_error_line("x = sqrt(-1)"), "t.bsp:1:10: error: sqrt: square root of a negative number");
  EXPECT_EQ(first_error_line("x = exp2(2000)"), "t.bsp:1:10: error: exp2: result is not a finite number");
  EXPECT_EQ(first_error_line("x = hypot(1.5e308, 1.5e308)"), "t.bsp:1:5: error: hypot: result is not a finite number");
  EXPECT_EQ(first_error_line("x = atan(\"a\")"), "t.bsp:1:10: error: atan: argument 'x' must be a number, got string");
}

TEST(Builtins, BoxMeasuresAreAnalytic) {
  const auto v = numbers("b = box([0, 0, 0], [1, 2, 3])\nprint(volume(b), area(b))");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], 6.0, 1e-12);
  EXPECT_NEAR(v[1], 2 * (2.0 + 6.0 + 3.0), 1e-12);
}

TEST(Builtins, ClassifyInOutOn) {
  EXPECT_EQ(run_script("b = box([0, 0, 0], [2, 2, 2])\n"
                       "print(classify(b, [1, 1, 1]), classify(b, [3, 1, 1]), classify(b, [2, 1, 1]), classify(b, [0, 0, 0]))")
                .out,
            "in out on on\n");
}

TEST(Builtins, SetOperationIdentities) {
  const auto v = numbers(
      "a = box([0, 0, 0], [2, 2, 2])\nb = translate(sphere(1.3, 16), [2, 2, 2])\n"
      "print(volume(a), volume(b), volume(a | b), volume(a & b), volume(a - b), volume(b - a))");
  ASSERT_EQ(v.size(), 6u);
  const double a = v[0], b = v[1], u = v[2], i = v[3], ab = v[4], ba = v[5];
  EXPECT_NEAR(u + i, a + b, 1e-9);  // inclusion-exclusion
  EXPECT_NEAR(ab, a - i, 1e-9);
  EXPECT_NEAR(ba, b - i, 1e-9);
  EXPECT_GT(i, 0);
  EXPECT_LT(b, 4.0 / 3.0 * M_PI * std::pow(1.3, 3));  // inscribed polyhedron
}

TEST(Builtins, TransformsScaleVolumes) {
  const auto v = numbers(
      "c = cylinder(1, 2, 24)\nprint(volume(c), volume(translate(c, [5, -3, 1])), volume(scale(c, 2)), "
      "volume(scale(c, [1, 2, 3])), volume(rotate(c, [1, 0, 0], 90)), volume(cone(1, 2, 24)))");
  ASSERT_EQ(v.size(), 6u);
  // The cylinder's cross-section is the regular 24-gon of circumradius 1 with its vertices snapped
  // to the grid (step 2^-15; docs/kernel.md, "Primitives' vertices"): its shoelace area, exactly
  // (to rounding); within 1e-4 of the exact 24-gon's 12 sin(2 pi / 24).
  double snapped_area = 0;
  for (int k = 0; k < 24; ++k) {
    auto at = [](int i, bool y) {
      const double t = 2 * M_PI * (i % 24) / 24;
      return std::round((y ? std::sin(t) : std::cos(t)) * 32768) / 32768;
    };
    snapped_area += 0.5 * (at(k, false) * at(k + 1, true) - at(k + 1, false) * at(k, true));
  }
  const double tolerance = 1e-12 * v[0];
  EXPECT_NEAR(v[0], 2 * snapped_area, tolerance);
  EXPECT_NEAR(v[0], 2 * 12 * std::sin(2 * M_PI / 24), 1e-4);
  EXPECT_NEAR(v[1], v[0], tolerance);
  EXPECT_NEAR(v[2], 8 * v[0], 8 * tolerance);
  EXPECT_NEAR(v[3], 6 * v[0], 6 * tolerance);
  EXPECT_NEAR(v[4], v[0], tolerance);
  EXPECT_NEAR(v[5], v[0] / 3, tolerance);
}

TEST(Builtins, SolidOperatorsNeedSolids) {
  EXPECT_EQ(first_error_line("x = box([0, 0, 0], [1, 1, 1]) | 3"), "t.bsp:1:31: error: cannot apply '|' to solid and number");
  EXPECT_EQ(first_error_line("b = box([0, 0, 0], [1, 1, 1])\nx = b + b"),
            "t.bsp:2:7: error: cannot apply '+' to solid and solid; the union of solids is 'a | b'");
  EXPECT_EQ(first_error_line("b = box([0, 0, 0], [1, 1, 1])\nx = b * box([0, 0, 0], [2, 2, 2])"),
            "t.bsp:2:7: error: cannot apply '*' to solid and solid; the intersection of solids is 'a & b'");
  EXPECT_EQ(first_error_line("x = 1 | 2"), "t.bsp:1:7: error: cannot apply '|' to number and number");
}

TEST(Builtins, LibraryErrorsAtTheCall) {
  EXPECT_EQ(first_error_line("b = 1\nx = box([0, 0, 0],\n  [0, 1, 1])").substr(0, 46), "t.bsp:2:5: error: box: invalid input: min must");
  EXPECT_EQ(first_error_line("x = sphere(1, 2)"),
            "t.bsp:1:15: error: sphere: argument 'segments' must be a whole number from 3 to 100000, got 2");
  EXPECT_EQ(first_error_line("x = box([0, 0], [1, 1, 1])"),
            "t.bsp:1:9: error: box: argument 'min' must be a vector of 3 numbers, got list");
  EXPECT_EQ(first_error_line("x = volume(3)"), "t.bsp:1:12: error: volume: argument 's' must be a solid, got number");
  EXPECT_EQ(first_error_line("x = linearize(cubic(), 5, method=\"best\")"),
            "t.bsp:1:27: error: linearize: unknown method \"best\"");
  EXPECT_EQ(first_error_line("x = linearize(cubic())"),
            "t.bsp:1:5: error: linearize: give either m (segments) or tol=, not both or neither");
  EXPECT_EQ(first_error_line("x = curve(\"/nonexistent/c.txt\")").substr(0, 45),
            "t.bsp:1:5: error: curve: /nonexistent/c.txt: ");
}

TEST(Builtins, LinearizationInvariants) {
  // m segments: m + 1 indices; the optimum never loses to a heuristic; error falls with m.
  const auto v = numbers(
      "c = folium()\n"
      "print(len(indices(linearize(c, 8))), len(points(linearize(c, 8))), error(linearize(c, 8)), "
      "error(linearize(c, 8, method=\"length\")), error(linearize(c, 8, method=\"iter\", alpha=0.2)), "
      "error(linearize(c, 16)), error(linearize(c, 8, method=\"douglas_peucker\")))");
  ASSERT_EQ(v.size(), 7u);
  EXPECT_EQ(v[0], 9);
  EXPECT_EQ(v[1], 9);
  EXPECT_LE(v[2], v[3]);
  EXPECT_LE(v[2], v[4]);
  EXPECT_LE(v[5], v[2]);
  EXPECT_LE(v[2], v[6]);
  const auto t = numbers("p = linearize(cubic(), tol=0.01)\nq = linearize(cubic(), len(indices(p)) - 2)\nprint(error(p), error(q))");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_LE(t[0], 0.01);
  EXPECT_GT(t[1], 0.01);  // one segment fewer cannot meet the tolerance (fewest segments)
}

TEST(Builtins, CurveFileRoundTrip) {
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "c.txt");
    f << "# a square's corners\n0 0\n1 0\n1 1\n0 1\n";
  }
  const auto r = run_script("c = curve(\"" + (dir / "c.txt").string() + "\")\nprint(points(c))\nprint(indices(linearize(c, 3)))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]\n[0, 1, 2, 3]\n");
}

TEST(Builtins, CurveFromAListOfPoints) {
  // The same square as a list: same points; closed joins the last point to the first, so the
  // closed square's two-segment optimum (a diagonal, error: half the diagonal) differs from the
  // open polyline's (exactly representable: error 0 with 3 segments).
  const auto r = run_script(
      "c = curve([[0, 0], [1, 0], [1, 1], [0, 1]])\nprint(points(c))\nprint(error(linearize(c, 3)))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]\n0\n");
  const auto v = numbers("d = curve([[0, 0], [1, 0], [1, 1], [0, 1]], closed=true)\n"
                         "print(len(indices(linearize(d, 2))), error(linearize(d, 2)))");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0], 3);
  EXPECT_NEAR(v[1], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(first_error_line("x = curve([[0, 0, 0], [1, 1]])"),
            "t.bsp:1:11: error: curve: point 2 has 2 coordinates, the first had 3 (all points must be 2D or all 3D)");
  EXPECT_EQ(first_error_line("x = curve([[0, 0], [1, \"a\"]])"),
            "t.bsp:1:11: error: curve: point 2 must be [x, y] or [x, y, z] with finite numbers");
  EXPECT_EQ(first_error_line("x = curve(5)"),
            "t.bsp:1:11: error: curve: argument 'source' must be a file name or a list of points, got number");
}

TEST(Builtins, ExportWritesAClosedMeshThatImportReads) {
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  for (const char* ext : {"off", "obj", "stl", "ply"}) {
    const std::string path = (dir / (std::string("cube.") + ext)).string();
    std::filesystem::remove(path);
    const auto r = run_script("export(box([0, 0, 0], [1, 2, 3]), \"" + path + "\")");
    EXPECT_EQ(r.error, "") << ext;
    EXPECT_TRUE(std::filesystem::exists(path)) << ext;
    const auto back = run_script("s = import(\"" + path + "\")\nprint(volume(s))");
    if (back.error.find("not available in this build") == std::string::npos) {
      EXPECT_EQ(back.error, "") << ext;
      EXPECT_EQ(back.out, "6\n") << ext;
    }
  }
  EXPECT_EQ(first_error_line("export(box([0, 0, 0], [1, 1, 1]), \"" + (dir / "x.xyz").string() + "\")").substr(0, 26),
            "t.bsp:1:1: error: export: ");
}

TEST(Builtins, ExportCreatesMissingFolders) {
  const auto dir = test::scratch_path("sculpt_language_test_folders");
  std::filesystem::remove_all(dir);
  const std::string path = (dir / "a" / "b" / "cube.stl").string();
  EXPECT_EQ(run_script("export(box([0, 0, 0], [1, 2, 3]), \"" + path + "\")").error, "");
  EXPECT_EQ(run_script("print(volume(import(\"" + path + "\")))").out, "6\n");
  // An unknown format is refused before any folder is made.
  const std::string bad = (dir / "c" / "cube.xyz").string();
  EXPECT_NE(run_script("export(box([0, 0, 0], [1, 1, 1]), \"" + bad + "\")").error.find("unknown mesh format"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "c"));
  std::filesystem::remove_all(dir);
}

// binary=true: binary STL is an 80-byte header, a 4-byte count and 50 bytes per triangle (the
// format's definition); a box's 6 faces are 12 triangles. It reads back as the same solid.
TEST(Builtins, ExportWritesBinaryStlWhenAsked) {
  const auto dir = test::scratch_path("sculpt_language_test_binary");
  std::filesystem::remove_all(dir);
  const std::string path = (dir / "box.stl").string();
  EXPECT_EQ(run_script("export(box([0, 0, 0], [1, 2, 3]), \"" + path + "\", binary=true)").error, "");
  EXPECT_EQ(std::filesystem::file_size(path), 80u + 4u + 12u * 50u);
  EXPECT_EQ(run_script("print(volume(import(\"" + path + "\")))").out, "6\n");
  const std::string off = (dir / "box.off").string();
  EXPECT_NE(run_script("export(box([0, 0, 0], [1, 1, 1]), \"" + off + "\", binary=true)")
                .error.find("applies to .stl and .ply"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(off));
  // Left out: ASCII up to 100,000 triangles (the box), binary above (a 360-segment sphere's
  // 360 x 180 rings make 360 * 2 * 179 = 128,880 triangles); binary=false keeps ASCII.
  const std::string small = (dir / "small.stl").string(), large = (dir / "large.stl").string();
  const std::string ascii = (dir / "ascii.stl").string();
  EXPECT_EQ(run_script("export(box([0, 0, 0], [1, 2, 3]), \"" + small + "\")\ns = sphere(1, 360)\nexport(s, \"" +
                       large + "\")\nexport(s, \"" + ascii + "\", binary=false)")
                .error,
            "");
  auto starts_with_solid = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    char head[5] = {};
    in.read(head, 5);
    return std::string(head, 5) == "solid";
  };
  EXPECT_TRUE(starts_with_solid(small));
  EXPECT_TRUE(starts_with_solid(ascii));
  EXPECT_FALSE(starts_with_solid(large));
  const auto triangles = (std::filesystem::file_size(large) - 84) / 50;
  EXPECT_EQ(std::filesystem::file_size(large), 84 + 50 * triangles);
  EXPECT_GT(triangles, 100'000u);
  std::filesystem::remove_all(dir);
}

/// The numbers of a printed box (brackets and commas dropped), compared within `tol` with `want`.
void expect_box(const std::string& script, const std::vector<double>& want, double tol) {
  std::string text = run_script(script).out;
  for (char& c : text)
    if (c == '[' || c == ']' || c == ',') c = ' ';
  std::istringstream in(text);
  std::vector<double> got;
  for (double v; in >> v;) got.push_back(v);
  ASSERT_EQ(got.size(), want.size()) << script << ": " << text;
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(got[i], want[i], tol) << script << " number " << i;
}

// Boxes of every kind of value with points, against corners known by construction.
TEST(Builtins, BoundsOfSolidsCurvesSplinesAndPoints) {
  EXPECT_EQ(run_script("print(bounds(translate(box([0, 0, 0], [1, 2, 3]), [1, 1, 1])))").out,
            "[[1, 1, 1], [2, 3, 4]]\n");
  // A square prism (4 segments, first vertex on +x) of circumradius 1: its vertices are (+-1, 0),
  // (0, +-1), up to the exact kernel's rounding of the side planes (far below the grid step).
  expect_box("print(bounds(cylinder(1, 2, 4)))", {-1, -1, 0, 1, 1, 2}, 1e-6);
  EXPECT_EQ(run_script("print(bounds(box([0, 0, 0], [1, 1, 1]) | box([2, -1, 0], [3, 0, 5])))").out,
            "[[0, -1, 0], [3, 1, 5]]\n");
  EXPECT_EQ(run_script("print(bounds(curve([[0, 0], [2, 1], [-1, 3]])), bounds([[0, 0, 1], [2, -1, 0]]))").out,
            "[[-1, 0], [2, 3]] [[0, -1, 0], [2, 0, 1]]\n");
  // One segment: the linearization's vertices are the end points.
  EXPECT_EQ(run_script("print(bounds(linearize(curve([[0, 0], [2, 1], [-1, 3]]), 1)))").out, "[[-1, 0], [0, 3]]\n");
  // A spline's box is its control points' (the curve itself reaches y = 1 only).
  EXPECT_EQ(run_script("print(bounds(bezier([[0, 0], [1, 2], [2, 0]])))").out, "[[0, 0], [2, 2]]\n");
  EXPECT_EQ(first_error_line("b = box([0, 0, 0], [1, 1, 1])\nx = bounds(b - b)"),
            "t.bsp:2:12: error: bounds: the solid is empty: it has no bounding box");
  EXPECT_EQ(first_error_line("x = bounds([])"), "t.bsp:1:12: error: bounds: no points: no bounding box");
  EXPECT_EQ(first_error_line("x = bounds(3)"),
            "t.bsp:1:12: error: bounds: argument 'x' must be a solid, a mesh, a curve, a linearization, a spline, a "
            "surface or a list of points, got number");
}

// center=true and d= as in OpenSCAD, checked by the bounding boxes they must have.
TEST(Builtins, PrimitivesTakeCenterAndDiameter) {
  EXPECT_EQ(run_script("print(bounds(box([2, 4, 6], center=true)), bounds(box(size=3)), bounds(box([1, 2, 3])))").out,
            "[[-1, -2, -3], [1, 2, 3]] [[0, 0, 0], [3, 3, 3]] [[0, 0, 0], [1, 2, 3]]\n");
  EXPECT_EQ(run_script("print(bounds(box([1, 1, 1], [3, 5, 7], center=true)))").out, "[[-1, -2, -3], [1, 2, 3]]\n");
  // Round primitives: their polygon's vertices on the circle, within the kernel's rounding.
  expect_box("print(bounds(cylinder(d=2, h=4, segments=4, center=true)))", {-1, -1, -2, 1, 1, 2}, 1e-6);
  expect_box("print(bounds(cone(1, 2, 4, center=true)))", {-1, -1, -1, 1, 1, 1}, 1e-6);
  expect_box("print(bounds(cone(d=4, h=2, segments=4)))", {-2, -2, 0, 2, 2, 2}, 1e-6);
  // A sphere of diameter 2 is the sphere of radius 1: the same solid, so the same volume.
  EXPECT_EQ(run_script("print(volume(sphere(d=2, segments=8)) == volume(sphere(1, 8)))").out, "true\n");
  EXPECT_EQ(first_error_line("x = cylinder(1, 2, d=2)"),
            "t.bsp:1:20: error: cylinder: give the radius r or the diameter d=, not both");
  EXPECT_EQ(first_error_line("x = cone(h=2)"), "t.bsp:1:5: error: cone: missing argument 'r' (or the diameter d=)");
  EXPECT_EQ(first_error_line("x = box([1, 1, 1], size=2)"),
            "t.bsp:1:20: error: box: give size= or the corners min and max, not both");
  EXPECT_EQ(first_error_line("x = box()"), "t.bsp:1:5: error: box: give the corners min and max, or a size");
  EXPECT_EQ(first_error_line("x = box([1, 1, 1], center=1)"),
            "t.bsp:1:20: error: box: argument 'center' must be true or false, got number");
}

// A mesh the output rounding cannot vouch for is written all the same, with a warning that says
// why; a clean one without a word. (A cap of more than 2048 corners is beyond what the
// self-intersection search triangulates: docs/mesh_io.md.)
TEST(Builtins, ExportWarnsWhenTheMeshIsNotKnownToBeClean) {
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "fine_cylinder.off").string();
  std::filesystem::remove(path);
  const auto quiet = run_script("export(box([0, 0, 0], [1, 2, 3]), \"" + path + "\")");
  EXPECT_EQ(quiet.error, "");
  EXPECT_EQ(quiet.out, "");
  std::filesystem::remove(path);
  const auto r = run_script("export(cylinder(1, 1, segments=2100), \"" + path + "\")");
  EXPECT_EQ(r.error, "");
  // The warning goes to standard error (issue 36: standard output is the script's prints).
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("export: warning: " + path + ": the mesh is not known to be clean for other tools (", 0), 0u)
      << r.err;
  EXPECT_TRUE(std::filesystem::exists(path));
}

TEST(Builtins, UnionAllOfAListOfSolids) {
  // Ten unit cubes in a row sharing faces, and one more overlapping two of them: volume 10.
  const auto r = run_script(
      "cubes = []\nfor i in range(0, 10) { cubes = append(cubes, box([i, 0, 0], [i + 1, 1, 1])) }\n"
      "cubes = append(cubes, box([2.5, 0, 0], [4.5, 1, 1]))\n"
      "u = union_all(cubes)\nprint(volume(u), classify(u, [5, 0.5, 0.5]), classify(u, [10, 0.5, 0.5]))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "10 in on\n");
  EXPECT_EQ(first_error_line("u = union_all([box([0, 0, 0], [1, 1, 1]), 3])"),
            "t.bsp:1:15: error: union_all: item 2 is number, not a solid");
}

// Two cubes 1e-6 apart form a valid mesh; snapped to the kernel's grid (step 2^-15) they share a
// face. import must refuse that with the faces and the place, not build a solid from it.
TEST(Builtins, ImportMovesApartFacesThatMeetOnceSnapped) {
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  auto write_two_cubes = [&](const std::string& name, double gap) {
    const std::string path = (dir / name).string();
    std::ofstream f(path);
    f.precision(17);
    f << "OFF\n16 12 0\n";
    for (double x0 : {0.0, 1.0 + gap})
      for (int k = 0; k < 8; ++k) f << x0 + (k & 1) << ' ' << ((k >> 1) & 1) << ' ' << ((k >> 2) & 1) << '\n';
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int c : {0, 8})
      for (const auto& q : quads) f << "4 " << q[0] + c << ' ' << q[1] + c << ' ' << q[2] + c << ' ' << q[3] + c << '\n';
    return path;
  };
  const std::string far = write_two_cubes("two_cubes_far.off", 0.5);
  const auto ok = run_script("print(volume(import(\"" + far + "\")))");
  if (ok.error.find("not available in this build") != std::string::npos) GTEST_SKIP();
  EXPECT_EQ(ok.error, "");
  EXPECT_NEAR(std::stod(ok.out), 2.0, 1e-12);  // two unit cubes
  // 1e-6 apart, far below the grid step 2^-15: snapped, the two cubes' facing sides meet. The
  // repair moves them apart (docs/mesh_io.md: features below 4 grid steps, with a warning that
  // says how far vertices moved); the volume stays 2 within the area times 4 steps.
  const std::string near = write_two_cubes("two_cubes_near.off", 1e-6);
  const auto moved = run_script("print(volume(import(\"" + near + "\")))");
  EXPECT_EQ(moved.error, "");
  ASSERT_EQ(moved.err.rfind("import: warning: ", 0), 0u) << moved.err;  // the warning on standard error
  EXPECT_NE(moved.err.find("were collapsed to fit the grid"), std::string::npos) << moved.err;
  EXPECT_NEAR(std::stod(moved.out), 2.0, 12 * 4 * std::ldexp(1.0, -15));  // the volume on standard output
}

// fuzz_geometry (tests/fuzz/regressions/import_inward_tetrahedron): a closed, consistently
// oriented mesh whose faces all point inwards passed import's checks, and from_mesh built a
// "solid" of volume -1/1024 from it. import must refuse it and say what to do.
TEST(Builtins, ImportRefusesAMeshOrientedInwards) {
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  auto write_tetrahedron = [&](const std::string& name, bool inwards) {
    const std::string path = (dir / name).string();
    std::ofstream f(path);
    f << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& t : faces)
      f << "3 " << t[0] << ' ' << (inwards ? t[2] : t[1]) << ' ' << (inwards ? t[1] : t[2]) << '\n';
    return path;
  };
  const auto ok = run_script("print(volume(import(\"" + write_tetrahedron("tetra_out.off", false) + "\")))");
  if (ok.error.find("not available in this build") != std::string::npos) GTEST_SKIP();
  EXPECT_EQ(ok.error, "");
  EXPECT_NEAR(std::stod(ok.out), 1.0 / 6, 1e-15);
  const std::string e = first_error_line("s = import(\"" + write_tetrahedron("tetra_in.off", true) + "\")");
  EXPECT_NE(e.find("t.bsp:1:5: error: import: "), std::string::npos) << e;
  EXPECT_NE(e.find("the faces of a shell are oriented the wrong way: misoriented shell: 1"), std::string::npos) << e;
  const std::string all = run_script("s = import(\"" + write_tetrahedron("tetra_in.off", true) + "\")").error;
  EXPECT_NE(all.find("faces inwards (signed volume -0.1666"), std::string::npos) << all;
}

// ---- hulls, strokes, extrusions, general maps (builtins_solids.cpp) ----

TEST(Builtins, HullOfPointsCurvesAndSolids) {
  // The unit cube's corners plus interior points; a cube and its translate (the swept box).
  const auto v = numbers(
      "pts = [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1],[0.5,0.5,0.5],[0.25,0,0]]\n"
      "print(volume(hull(pts)), volume(hull(curve(pts))), volume(hull([box([0,0,0],[1,1,1]), "
      "box([2,1,0],[3,2,1])])), volume(hull(box([0,0,0],[2,1,1]))), volume(hull([[0,0,0],[1,0,0],[0,1,0]])))");
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0], 1.0);
  EXPECT_EQ(v[1], 1.0);
  EXPECT_EQ(v[2], 1.0 + 2 + 1);  // 1 + |vx| + |vy| + |vz| for v = (2, 1, 0)
  EXPECT_EQ(v[3], 2.0);
  EXPECT_EQ(v[4], 0.0);  // coplanar: no volume
  EXPECT_NE(first_error_line("hull([box([0,0,0],[1,1,1]), 3])").find("item 2 is number, not a solid"), std::string::npos);
  EXPECT_NE(first_error_line("hull(3)").find("t.bsp:1:6: error: hull: "), std::string::npos);
}

TEST(Builtins, SweepCarveAndAddAlongPaths) {
  const auto v = numbers(
      "b = box([0,0,0],[1,1,1])\n"
      "path = [[0,0,0],[3,0,0],[3,2,0]]\n"
      "block = box([-1,-1,-1],[5,4,0.5])\n"
      "print(volume(sweep(b, path)), volume(carve(block, b, path)), volume(add(block, b, path)), "
      "volume(block))");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0], 6.0);                  // two slabs of 4 and 3 sharing the corner cube
  EXPECT_EQ(v[1], v[3] - 6.0 * 0.5);     // the stroke cuts the lower half of the swept slabs
  EXPECT_EQ(v[2], v[3] + 6.0 * 0.5);
  // A curve linearized within tol: a quarter circle of radius 2 swept by a small cube stays within
  // the annulus sector the exact sweep of the polyline covers.
  const auto w = numbers(
      "pts = []\nfor i in range(0, 101) { t = i * 3.14159265358979 / 200\n pts = append(pts, [2*cos(t), 2*sin(t), 0]) }\n"
      "c = curve(pts)\nprint(volume(sweep(box([0,0,0],[0.1,0.1,0.1]), c, tol=0.001)), "
      "volume(sweep(box([0,0,0],[0.1,0.1,0.1]), c)))");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NEAR(w[0], w[1], 0.01 * w[1]);
  EXPECT_NE(first_error_line("sweep(box([0,0,0],[1,1,1]), [])").find("the path has no points"), std::string::npos);
  // A straight spline path (a Bezier curve with collinear controls) gives the box's exact sweep;
  // a closed spline (a periodic cubic around a square) comes back to its start: the sweep is a ring.
  const auto s = numbers(
      "b = box([0,0,0],[1,1,1])\n"
      "print(volume(sweep(b, bezier([[0,0,0],[1,0,0],[3,0,0]]), tol=0.001)), "
      "volume(sweep(b, bspline([[0,0,0],[4,0,0],[4,4,0],[0,4,0]], closed=true), tol=0.01)))");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0], 4.0);
  EXPECT_GT(s[1], 4 * 2.0);  // a closed loop of the unit box around a curve of length > 8
  EXPECT_LT(s[1], 5.0 * 5.0);
}

TEST(Builtins, ExportAndImport3mf) {
  // A box with grid-point corners that are also float32 values with at most six decimals (exact
  // in 3MF): it comes back as the same solid. A carved one comes back closed, its volume within
  // what a micrometre on each coordinate can change.
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  const std::string a = (dir / "box.3mf").string(), b = (dir / "carved.3mf").string();
  const auto v = numbers("s = box([-1.5, 0, 0.25], [2, 3.125, 4])\nexport(s, \"" + a + "\")\nt = import(\"" + a +
                         "\")\nc = s - sphere(1, segments=12)\nexport(c, \"" + b + "\")\nd = import(\"" + b +
                         "\")\nprint(volume(s - t) + volume(t - s), volume(t), volume(c), volume(d), area(c))");
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_EQ(v[1], 3.5 * 3.125 * 3.75);
  EXPECT_NEAR(v[3], v[2], 2e-6 * v[4]);
}

TEST(Builtins, ExportAndImportGlb) {
  // A box whose corners are grid points and float32 values comes back as the same solid; a CSG
  // result comes back closed (import checks that), its volume within float32 and grid roundings.
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  const std::string a = (dir / "box.glb").string(), b = (dir / "carved.glb").string();
  const auto v = numbers("s = box([-1.5, 0, 0.25], [2, 3.125, 4])\nexport(s, \"" + a + "\")\nt = import(\"" + a +
                         "\")\nc = s - sphere(1, segments=12)\nexport(c, \"" + b + "\")\nd = import(\"" + b +
                         "\")\nprint(volume(s - t) + volume(t - s), volume(t), volume(c), volume(d), area(c))");
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_EQ(v[1], 3.5 * 3.125 * 3.75);
  EXPECT_NEAR(v[3], v[2], 2e-6 * v[4]);  // as for 3MF: float32 and the import's grid snapping
}

TEST(Builtins, ExportAndImportOpenMeshFormat) {
  // The same doubles through .om (OpenMesh) and .off (ours, shortest round-trip decimals): the
  // imported solids are the same (import snaps both to the grid the same way).
  const auto dir = test::scratch_path("sculpt_language_test");
  std::filesystem::create_directories(dir);
  const std::string om = (dir / "part.om").string(), off = (dir / "part.off").string();
  const auto v = numbers("s = sphere(1, segments=12) - box([0,0,0],[2,2,2])\nexport(s, \"" + om + "\")\nexport(s, \"" + off +
                         "\")\na = import(\"" + om + "\")\nb = import(\"" + off +
                         "\")\nprint(volume(a), volume(b), volume(a - b) + volume(b - a), volume(s))");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0], v[1]);
  EXPECT_EQ(v[2], 0.0);
  EXPECT_NEAR(v[0], v[3], 1e-4);  // the grid snapping on import
}

TEST(Builtins, ABallSweptAlongACircleIsATorusWithinTheLinearizationBound) {
  // A ball polytope (radius r, its faces at least r cos^2(pi/16) from the centre) swept along a
  // circle of radius R linearized within tol: every polyline point is within tol of the circle, so
  // the sweep lies between the tori of tube radius 0.96 r - tol and r + tol (2 pi^2 R rho^2).
  const double R = 2, r = 0.5, tol = 0.01;
  const auto v = numbers(
      "pts = []\nfor i in range(0, 400) { t = 2 * 3.141592653589793 * i / 400\n pts = append(pts, [2 * cos(t), 2 * sin(t), 0]) }\n"
      "path = linearize(curve(pts, closed=true), tol=0.01)\n"
      "print(volume(sweep(sphere(0.5, segments=16), path)), len(points(path)))");
  ASSERT_EQ(v.size(), 2u);
  const double torus = 2 * std::numbers::pi * std::numbers::pi * R;
  const double inner = r * std::cos(std::numbers::pi / 16) * std::cos(std::numbers::pi / 16) - tol;
  EXPECT_GT(v[0], torus * inner * inner);
  EXPECT_LT(v[0], torus * (r + tol) * (r + tol));
  EXPECT_LT(v[1], 60);  // the fewest segments within tol: far fewer than the 400 samples
}

TEST(Builtins, ExtrudeMirrorAndTransform) {
  const auto v = numbers(
      "u = [[0,0],[3,0],[3,3],[2,3],[2,1],[1,1],[1,3],[0,3]]\n"
      "s = extrude(u, 2)\n"
      "print(volume(s), volume(extrude(u, -2) & s), volume(mirror(s, [1,0,0]) & s), "
      "volume(mirror(s, [1,1,0])), volume(transform(s, [[2,0,0,1],[0,1,0,0],[0,0,1,0]])), "
      "volume(transform(s, [[1,0,0,-1.5],[0,1,0,0],[0,0,1,0]]) & mirror(transform(s, [[1,0,0,-1.5],[0,1,0,0],[0,0,1,0]]), [1,0,0])))");
  ASSERT_EQ(v.size(), 6u);
  EXPECT_EQ(v[0], 14.0);
  EXPECT_EQ(v[1], 0.0);                     // below and above the plane: they only touch
  EXPECT_EQ(v[2], 0.0);                     // mirrored to x < 0: touches along x = 0
  EXPECT_NEAR(v[3], 14.0, 14.0 * 1e-4);     // a general mirror moves vertices to the grid
  EXPECT_EQ(v[4], 28.0);                    // x scaled by 2 (integer map: exact)
  EXPECT_EQ(v[5], 14.0);                    // the U centred on x = 0 is symmetric
  EXPECT_NE(first_error_line("extrude([[0,0],[1,1],[1,0],[0,1.5]], 1)").find("crosses or touches itself"), std::string::npos);
  EXPECT_NE(first_error_line("extrude([[0,0,0],[1,0,0],[0,1,1]], 1)").find("not in a plane z = constant"), std::string::npos);
  EXPECT_NE(first_error_line("transform(box([0,0,0],[1,1,1]), [[1,0,0,0],[0,1,0,0]])").find("3 rows of 4 numbers"), std::string::npos);
  EXPECT_NE(first_error_line("transform(box([0,0,0],[1,1,1]), [[1,0,0,0],[0,1,0,0],[0,0,0,0]])").find("error"), std::string::npos);
}

TEST(Builtins, ExtrudeWithTwistAndScale) {
  // A 2 x 2 square (area 4) extruded by 3: frustum A h (1 + s + s^2) / 3 = 7 for scale 0.5, the
  // rectangle sections' integral 4 h (1 + (a + b)/2 + ab/3) = 13 for [2, 0.5], the pyramid A h / 3
  // = 4 for scale 0; twisted, a little above A h = 12 (the sides bulge out, extrude.hpp), within 3 %.
  const auto v = numbers(
      "sq = [[-1,-1],[1,-1],[1,1],[-1,1]]\n"
      "print(volume(extrude(sq, 3, scale=0.5)), volume(extrude(sq, 3, scale=[2, 0.5])), "
      "volume(extrude(sq, 3, scale=0)), volume(extrude(sq, 3, twist=90)), volume(extrude(sq, 3, twist=90, "
      "slices=180)))");
  ASSERT_EQ(v.size(), 5u);
  EXPECT_NEAR(v[0], 7.0, 1e-9);
  EXPECT_NEAR(v[1], 13.0, 1e-9);
  EXPECT_NEAR(v[2], 4.0, 1e-9);
  EXPECT_GT(v[3], 12.0);
  EXPECT_LT(v[3], 12.0 * 1.03);
  EXPECT_GT(v[4], 12.0);
  EXPECT_LT(v[4] - 12.0, (v[3] - 12.0) / 5);  // converges with the slices
  EXPECT_NE(first_error_line("extrude([[0,0],[1,0],[0,1]], 1, scale=-1)").find("scale"), std::string::npos);
  EXPECT_NE(first_error_line("extrude([[0,0],[1,0],[0,1]], 1, scale=[1, 0])").find("apex"), std::string::npos);
  EXPECT_NE(first_error_line("extrude([[0,0],[1,0],[0,1]], 1, slices=0)").find("slices"), std::string::npos);
  EXPECT_NE(first_error_line("extrude([[-1,-1],[1,-1],[1,1],[-1,1]], 1, twist=180, slices=1)").find("more slices"),
            std::string::npos);
}

TEST(Builtins, OffsetOfAPolygonThenExtruded) {
  // A 2 x 2 square offset by 0.5: miter (a + 2r)^2 = 9; round a^2 + 4 a r + the 32-gon of radius
  // r; inwards (a - 2r)^2 = 1. Extruded by 2: twice that. A curve comes back (closed, 2D).
  const double a = 2, r = 0.5;
  const double round = a * a + 4 * a * r + 16 * r * r * std::sin(2 * std::numbers::pi / 32);
  const auto v = numbers(
      "sq = [[0,0],[2,0],[2,2],[0,2]]\n"
      "print(volume(extrude(offset(sq, 0.5, join=\"miter\"), 2)), volume(extrude(offset(sq, 0.5), 2)), "
      "volume(extrude(offset(curve(sq, closed=true), -0.5), 2)), len(points(offset(sq, 0.5, segments=8))))");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_NEAR(v[0], 2 * 9.0, 1e-6);
  EXPECT_NEAR(v[1], 2 * round, 2e-4);  // vertices on the default grid (step 3e-5)
  EXPECT_NEAR(v[2], 2 * 1.0, 1e-6);
  EXPECT_EQ(v[3], 4 * 3);  // two edges a corner: three arc vertices each
  EXPECT_NE(first_error_line("offset([[0,0],[2,0],[2,2],[0,2]], -1)").find("vanish"), std::string::npos);
  EXPECT_NE(
      first_error_line("offset([[0,0],[2,0],[2,0.75],[3,0.75],[3,0],[5,0],[5,2],[3,2],[3,1.25],[2,1.25],[2,2],[0,2]], "
                       "-0.4)")
          .find("2 polygons"),
      std::string::npos);
  EXPECT_NE(first_error_line("offset([[0,0],[2,0],[2,2]], 0.5, join=\"bevel\")").find("join"), std::string::npos);
  EXPECT_NE(first_error_line("offset([[0,0],[2,0],[2,2]], 0.5, tol=0.1)").find("spline"), std::string::npos);
  EXPECT_NE(first_error_line("offset(bspline([[0,0],[1,1],[2,0],[3,1]]), 0.1, join=\"miter\")").find("polygon"),
            std::string::npos);
}

// ---- the world range: grid(step) (builtins_solids.cpp; docs/kernel.md, "World range") ----

TEST(Builtins, GridSetsTheWorldRangeOfSolidsMadeAfterIt) {
  // 3 m in millimetres at step 2^-13 (range 4096): volumes exact against the analytic values.
  EXPECT_EQ(numbers("grid(pow(2, -13))\n"
                    "part = box([0, 0, 0], [3000, 400, 50]) | box([0, 0, 0], [200, 400, 1200])\n"
                    "print(volume(part), volume(part - box([1000, 100, -1], [1500, 300, 51])))"),
            (std::vector<double>{3000.0 * 400 * 50 + 200.0 * 400 * 1150, 3000.0 * 400 * 50 + 200.0 * 400 * 1150 - 500.0 * 200 * 50}));
  // 10 um in metres at step 2^-20: ten steps wide.
  EXPECT_EQ(numbers("grid(pow(2, -20))\nprint(volume(box([0, 0, 0], [0.00001, 1, 1])))"),
            (std::vector<double>{10 * std::ldexp(1.0, -20)}));
  // grid() reads the step; grid(step) returns it; printing a solid names a grid that is not the default.
  EXPECT_EQ(numbers("print(grid(), grid(0.125), grid())"), (std::vector<double>{std::ldexp(1.0, -15), 0.125, 0.125}));
  EXPECT_EQ(run_script("print(box([0, 0, 0], [1, 1, 1]))").out, "<solid: 6 nodes, height 6>\n");
  EXPECT_EQ(run_script("grid(pow(2, -13))\nprint(box([0, 0, 0], [1, 1, 1]))").out, "<solid: 6 nodes, height 6, grid 2^-13>\n");
  // stats names a grid that is not the default.
  const std::string report = run_script("grid(pow(2, -13))\nstats(box([0, 0, 0], [3000, 10, 10]), samples=0)").err;
  EXPECT_NE(report.find("grid step                               2^-13\n"), std::string::npos) << report;
  EXPECT_EQ(run_script("stats(box([0, 0, 0], [3, 1, 1]), samples=0)").err.find("grid step"), std::string::npos);
  // revolve, cylinder, sphere and cone follow the grid too.
  const auto r = run_script("grid(pow(2, -13))\nprint(revolve([[0, 0], [2000, 0], [2000, 100], [0, 100]], circle(4)), "
                            "cylinder(2000, 10), sphere(2500), cone(2500, 3000))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '^'), 4) << r.out;
}

// stats returns what it prints as a record (issue 36). The unit cube sampled in itself is one
// in-cell at the end of its chain of six planes: expected depth 6, entropy 0 (sec. 6's measures).
TEST(Builtins, StatsReturnsARecord) {
  EXPECT_EQ(numbers("r = stats(box([0, 0, 0], [1, 1, 1]), samples=0, quiet=true)\n"
                    "print(r[\"nodes\"], r[\"leaves\"], r[\"in_leaves\"], r[\"out_leaves\"], r[\"height\"], "
                    "r[\"expected_depth\"], r[\"entropy_bound\"], r[\"in_volume\"], r[\"sample_volume\"])"),
            (std::vector<double>{6, 7, 1, 6, 6, 6, 0, 1, 1}));
  // In a box of volume 27 around it: the cells' probabilities sum to 1, the in-cell's is 1/27, and
  // no tree beats the entropy bound (Kraft's inequality).
  const auto r = numbers(
      "r = stats(box([0, 0, 0], [1, 1, 1]), box=[[-1, -1, -1], [2, 2, 2]], samples=0, quiet=true)\n"
      "p = 0\nq = 0\nfor b in r[\"histogram\"] {\n  p = p + b[\"in_probability\"] + b[\"out_probability\"]\n"
      "  q = q + b[\"in_probability\"]\n}\n"
      "print(p, q, r[\"sample_volume\"], r[\"expected_depth\"] - r[\"entropy_bound\"], "
      "r[\"ratio\"] * r[\"entropy_bound\"] - r[\"expected_depth\"])");
  ASSERT_EQ(r.size(), 5u);
  EXPECT_NEAR(r[0], 1.0, 1e-12);
  EXPECT_NEAR(r[1], 1.0 / 27, 1e-12);
  EXPECT_EQ(r[2], 27.0);
  EXPECT_GE(r[3], 0.0);
  EXPECT_NEAR(r[4], 0.0, 1e-12);
  // A list gives a list of records, named; the query costs are records by shape.
  EXPECT_EQ(
      run_script("s = box([0, 0, 0], [1, 1, 1])\n"
                 "l = stats([s, s], names=[\"a\", \"b\"], samples=20, quiet=true)\n"
                 "print(len(l), l[1][\"name\"], l[0][\"queries\"][\"point\"][\"samples\"], keys(l[0][\"queries\"]))")
          .out,
      "2 b 20 [\"point\", \"segment\", \"box\"]\n");
  // quiet=true prints nothing; without it the report still goes to standard error.
  EXPECT_EQ(run_script("r = stats(box([0, 0, 0], [1, 1, 1]), samples=0, quiet=true)").err, "");
  EXPECT_NE(run_script("r = stats(box([0, 0, 0], [1, 1, 1]), samples=0)").err.find("expected depth"),
            std::string::npos);
  // A misspelt field names the closest one and lists them all.
  EXPECT_EQ(first_error_line("r = stats(box([0, 0, 0], [1, 1, 1]), samples=0, quiet=true)\nprint(r[\"hieght\"])"),
            "t.bsp:2:9: error: the record has no field \"hieght\" (did you mean \"height\"?); its fields: name, nodes, "
            "leaves, in_leaves, out_leaves, height, expected_depth, entropy_bound, ratio, cells_in_box, in_volume, "
            "sample_box, sample_volume, histogram, queries");
  EXPECT_NE(first_error_line("print(keys([1]))").find("keys: argument 'r' must be a record, got list"),
            std::string::npos);
}

TEST(Builtins, GridErrorsSayWhatFits) {
  EXPECT_EQ(first_error_line("s = box([0, 0, 0], [3000, 1, 1])"),
            "t.bsp:1:5: error: box: out of range: coordinate 3000 is outside the exact kernel's range [-1024, 1024] world units "
            "(grid step 2^-15); a grid of step 2^-13 would fit coordinates up to 4096");
  const std::string e = first_error_line("grid(0.001)");
  EXPECT_NE(e.find("t.bsp:1:6: error: grid: grid step must be a power of two"), std::string::npos) << e;
  EXPECT_NE(e.find("the nearest is 2^-10"), std::string::npos) << e;
  // Solids of different grids do not combine; the message names both grids.
  EXPECT_EQ(first_error_line("a = box([0, 0, 0], [1, 1, 1])\ngrid(pow(2, -13))\nb = box([0, 0, 0], [1, 1, 1])\nc = a | b"),
            "t.bsp:4:7: error: invalid input: solids made at different grids (step 2^-15 and step 2^-13) cannot be combined: "
            "make every solid of a model at one grid");
  EXPECT_NE(first_error_line("a = box([0, 0, 0], [1, 1, 1])\ngrid(pow(2, -13))\nc = union_all([a, box([0, 0, 0], [1, 1, 1])])")
                .find("different grids"),
            std::string::npos);
  // A later grid() says which solids keep the old grid.
  EXPECT_EQ(run_script("a = box([0, 0, 0], [1, 1, 1])\ngrid(pow(2, -13))").err,
            "note: grid(2^-13): 1 solid (a) made at another grid cannot be combined with solids made from now on\n");
  EXPECT_EQ(run_script("grid(pow(2, -13))\na = box([0, 0, 0], [1, 1, 1])\ngrid(pow(2, -13))").out, "");
}

// ---- splines (builtins_splines.cpp) ----

/// Every number in `text`, in order (lists included).
std::vector<double> all_numbers(const std::string& text) {
  static const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?)");
  std::vector<double> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

/// Distance from x to the closed polygon through `ring` (an independent check of foot points).
double polygon_distance(const Eigen::Vector2d& x, const std::vector<Eigen::Vector2d>& ring) {
  double best = INFINITY;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d a = ring[i], b = ring[(i + 1) % ring.size()];
    const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - x).norm());
  }
  return best;
}

const char* kCircleData =
    "c = []\nfor i in range(0, 400) { t = 2 * pi * i / 400\n c = append(c, [cos(t), sin(t)]) }\n"
    "data = curve(c, closed=true)\n";

TEST(Builtins, SplineFromControlPoints) {
  const auto r = run_script(
      "s = bspline([[0, 0], [1, 1], [2, 0], [3, 1]])\nprint(s)\nprint(degree(s), knots(s), control_points(s))\n"
      "print(bspline([[0, 0, 1], [1, 0, 1], [1, 1, 1]], degree=2, closed=true))\n"
      "b = bezier([[0, 0], [1, 2], [2, 0]])\nprint(b, type(b))\nprint(points(sample(b, 3)))\n"
      "print(knots(bspline([[0, 0], [1, 1], [2, 0], [3, 1]], degree=2, knots=[0, 0, 0, 0.3, 1, 1, 1])))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out,
            "<spline: degree 3, open, 2D, 4 controls, domain [0, 1]>\n"
            "3 [0, 0, 0, 0, 1, 1, 1, 1] [[0, 0], [1, 1], [2, 0], [3, 1]]\n"
            "<spline: degree 2, closed, 3D, 3 controls, domain [0, 3]>\n"
            "<spline: degree 2, open, 2D, 3 controls, domain [0, 1]> spline\n"
            "[[0, 0, 0], [1, 1, 0], [2, 0, 0]]\n"
            "[0, 0, 0, 0.3, 1, 1, 1]\n");
}

// 400 points of the unit circle, a closed cubic with 8 control points started from a circle of
// radius 0.7 (the closed flag comes from the start). The fitted curve, sampled densely, stays within 1e-3 of the circle (|p| = 1), and
// distance() agrees with the distance to the polygon of the samples computed here.
TEST(Builtins, FitSampledCircleIsCloseByAnIndependentMeasure) {
  const auto r = run_script(std::string(kCircleData) +
                            "start = []\nfor i in range(0, 8) { start = append(start, [0.7 * cos(pi * i / 4), 0.7 * sin(pi * i / 4)]) }\n"
                            "s = fit(data, start=bspline(start, closed=true), smoothing=0.001)\nprint(s)\nprint(distance(s, data))\n"
                            "print(points(sample(s, 2000)))\nprint(len(fit_history(s)), fit_history(s)[0])");
  ASSERT_EQ(r.error, "");
  std::istringstream lines(r.out);
  std::string repr, dist, samples, history;
  std::getline(lines, repr);
  std::getline(lines, dist);
  std::getline(lines, samples);
  std::getline(lines, history);
  EXPECT_EQ(repr.rfind("<spline: degree 3, closed, 2D, 8 controls, domain [0, 8], fitted in ", 0), 0u) << repr;
  const auto d = all_numbers(dist);
  ASSERT_EQ(d.size(), 2u);
  const auto xyz = all_numbers(samples);
  ASSERT_EQ(xyz.size(), 3u * 2000u);
  std::vector<Eigen::Vector2d> ring;
  double radial = 0;
  for (std::size_t i = 0; i < xyz.size(); i += 3) {
    ring.emplace_back(xyz[i], xyz[i + 1]);
    EXPECT_EQ(xyz[i + 2], 0.0);
    radial = std::max(radial, std::abs(ring.back().norm() - 1));
  }
  EXPECT_LT(radial, 1e-3);
  double max = 0, sum = 0;
  for (int i = 0; i < 400; ++i) {
    const double t = 2 * M_PI * i / 400;
    const double e = polygon_distance({std::cos(t), std::sin(t)}, ring);
    max = std::max(max, e);
    sum += e * e;
  }
  // The polygon of 2000 samples lies within h^2 / 8 (h ~ 0.0035) of the curve.
  EXPECT_NEAR(d[0], max, 2e-6);
  EXPECT_NEAR(d[1], std::sqrt(sum / 400), 2e-6);
  EXPECT_LT(d[0], 1e-3);
  const auto h = all_numbers(history);
  ASSERT_EQ(h.size(), 4u);
  EXPECT_GE(h[0], 2);            // the start and at least one step
  EXPECT_LE(h[0], 51);           // at most 50 steps
  EXPECT_GT(h[3], 0.2);          // the start: rms about 0.3
  EXPECT_NEAR(d[1], 4.03e-4, 0.02 * 4.03e-4);  // the optimum of docs/benchmarks (issue 15)
}

TEST(Builtins, FitMethodsAndOptions) {
  // A list of points is open unless closed=true; pdm and tdm run; a start curve sets the count.
  const auto r = run_script(std::string(kCircleData) +
                            "for m in [\"sdm\", \"pdm\", \"tdm\"] { print(distance(fit(data, controls=10, method=m), data)[0] < 0.01) }\n"
                            "print(fit(c, controls=6))\nprint(fit(c, controls=6, closed=true))\n"
                            "print(fit(data, start=bspline([[1, 0], [0, 1], [-1, 0], [0, -1]], degree=2, closed=true), iterations=3))");
  EXPECT_EQ(r.error, "");
  const std::string out = r.out;
  EXPECT_EQ(out.substr(0, 15), "true\ntrue\ntrue\n") << out;
  EXPECT_NE(out.find("<spline: degree 3, open, 2D, 6 controls"), std::string::npos) << out;
  EXPECT_NE(out.find("<spline: degree 3, closed, 2D, 6 controls"), std::string::npos) << out;
  EXPECT_NE(out.find("<spline: degree 2, closed, 2D, 4 controls, domain [0, 4], fitted in 3 steps (not converged)>"),
            std::string::npos) << out;
}

TEST(Builtins, SplineDegreeReductionKeepsTheEnds) {
  const auto v = numbers(
      "b = bezier([[0, 0], [1, 2], [2, -1], [3, 3], [4, -1], [5, 2], [6, 0]])\nr = reduce_degree(b, 4)\n"
      "p = control_points(r)\nprint(degree(r), len(p), p[0][0], p[0][1], p[4][0], p[4][1], distance(r, sample(b, 200))[0])");
  ASSERT_EQ(v.size(), 7u);
  EXPECT_EQ(v[0], 4);
  EXPECT_EQ(v[1], 5);
  EXPECT_EQ(v[2], 0);
  EXPECT_EQ(v[3], 0);
  EXPECT_EQ(v[4], 6);
  EXPECT_EQ(v[5], 0);
  EXPECT_GT(v[6], 0);
  EXPECT_LT(v[6], 0.5);
  // Eck's L2 reduction keeps the ends too and is farther from b as a point set (the seed's claim).
  const auto e = numbers(
      "b = bezier([[0, 0], [1, 2], [2, -1], [3, 3], [4, -1], [5, 2], [6, 0]])\ne = reduce_degree(b, 4, method=\"l2\")\n"
      "p = control_points(e)\nprint(p[0][0], p[0][1], p[4][0], p[4][1], distance(e, sample(b, 200))[0])");
  ASSERT_EQ(e.size(), 5u);
  EXPECT_NEAR(e[0], 0, 1e-12);
  EXPECT_NEAR(e[1], 0, 1e-12);
  EXPECT_NEAR(e[2], 6, 1e-12);
  EXPECT_NEAR(e[3], 0, 1e-12);
  EXPECT_GT(e[4], v[6]);
  EXPECT_EQ(first_error_line("r = reduce_degree(bezier([[0, 0], [1, 1], [2, 0]]), 1, method=\"best\")"),
            "t.bsp:1:56: error: reduce_degree: method must be \"active\" or \"l2\"");
}

TEST(Builtins, SampledSplineIsAProfileForRevolve) {
  // A profile from r = 1 at z = 0 to r = 1 at z = 2 bulging to r = 1.5: sampled, linearized, revolved.
  const auto v = numbers(
      "s = bspline([[1, 0], [2, 1], [1, 2]], degree=2)\nc = sample(s, 50)\n"
      "print(volume(revolve(c, circle(16))), volume(revolve(linearize(c, 8), circle(16))), len(points(c)))");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_GT(v[0], 2 * M_PI * 0.9);  // more than the unit cylinder of height 2 inscribed in 16-gons
  EXPECT_LT(v[0], 2 * M_PI * 1.5 * 1.5);
  EXPECT_LE(v[1], v[0] + 1e-9);     // the linearization cuts the convex bulge
  EXPECT_EQ(v[2], 50);
}

TEST(Builtins, SplineFileRoundTrip) {
  const auto dir = test::scratch_path("sculpt_language_test") / "splines";
  std::filesystem::remove_all(dir);
  const std::string path = (dir / "s.spline").string();
  const auto r = run_script(std::string(kCircleData) + "s = fit(data, controls=7, iterations=5)\nsave_spline(s, \"" +
                            path + "\")\nt = load_spline(\"" + path +
                            "\")\nprint(control_points(t) == control_points(s), knots(t) == knots(s), t)");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "true true <spline: degree 3, closed, 2D, 7 controls, domain [0, 7]>\n");
  for (const auto& entry : std::filesystem::directory_iterator(dir))  // no temporary left behind
    EXPECT_EQ(entry.path().filename().string(), "s.spline");
  {
    std::ofstream f(dir / "bad.spline");
    f << "# hand-written\ndegree 2\nclosed maybe\n";
  }
  const std::string e = first_error_line("t = load_spline(\"" + (dir / "bad.spline").string() + "\")");
  EXPECT_EQ(e.rfind("t.bsp:1:5: error: load_spline: invalid input: ", 0), 0u) << e;
  EXPECT_NE(e.find("bad.spline:3:"), std::string::npos) << e;
}

TEST(Builtins, OffsetOfACircleIsTheConcentricCircle) {
  // A closed spline close to the unit circle (fitted to 400 points; its direction is the fit's);
  // its offsets at +0.2 and -0.2 lie on the circles of radius 0.8 and 1.2, one each, measured from
  // the sampled points' distances to the origin, independently of the offset code.
  const auto v = numbers(
      "c = []\nfor i in range(0, 400) {\n  t = 2 * 3.141592653589793 * i / 400\n  c = append(c, [cos(t), sin(t)])\n}\n"
      "s = fit(c, controls=12, closed=true)\n"
      "for d in [0.2, -0.2] {\n  o = offset(s, d)\n  lo = 10\n  hi = 0\n"
      "  for p in points(sample(o, 500)) {\n    r = sqrt(p[0] * p[0] + p[1] * p[1])\n"
      "    if r < lo { lo = r }\n    if r > hi { hi = r }\n  }\n  print(lo, hi)\n}");
  ASSERT_EQ(v.size(), 4u);
  const bool outwards_first = v[0] > 1;
  EXPECT_NEAR(v[0], outwards_first ? 1.2 : 0.8, 2e-3);
  EXPECT_NEAR(v[1], outwards_first ? 1.2 : 0.8, 2e-3);
  EXPECT_NEAR(v[2], outwards_first ? 0.8 : 1.2, 2e-3);
  EXPECT_NEAR(v[3], outwards_first ? 0.8 : 1.2, 2e-3);
  // Positive d is to the right of the direction of travel: outwards for a counter-clockwise curve.
  const auto w = numbers(
      "s = bspline([[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1]], closed=true)\n"
      "far = 0\nfor p in points(sample(offset(s, 0.1), 200)) { far = max(far, sqrt(p[0] * p[0] + p[1] * p[1])) }\n"
      "near = 0\nfor p in points(sample(s, 200)) { near = max(near, sqrt(p[0] * p[0] + p[1] * p[1])) }\nprint(far - near)");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], 0.1, 0.02);
  const auto r = run_script("s = bspline([[0, 0, 0], [1, 1, 1], [2, 0, 1], [3, 1, 0]])\noffset(s, 0.1)");
  EXPECT_NE(r.error.find("offset"), std::string::npos) << r.error;  // a 3D curve has no offset
}

// scripts/smooth_goblet.bsp: the bowl's inner surface is at the wall thickness from the outer
// surface, and the hollow goblet's volume is the outer solid's minus the cavity's part inside it,
// both computed here from the printed profiles by the frustum formula (not by the BSP code).
TEST(Builtins, SmoothGobletHasAWallOfConstantThickness) {
  const std::string script = sculpt::test::source_dir() + "/scripts/smooth_goblet.bsp";
  const auto r = run_script("include \"" + script + "\"\nprint(\"@\")\nprint(points(line))\nprint(cavity_points)\n"
                            "print([wall, error(line), error(inner_line), volume(goblet)])\n");
  ASSERT_EQ(r.error, "");
  const std::string tail = r.out.substr(r.out.rfind("\n@\n") + 3);
  std::istringstream lines(tail);
  std::string outer_text, cavity_text, figures_text;
  std::getline(lines, outer_text);
  std::getline(lines, cavity_text);
  std::getline(lines, figures_text);
  const auto pairs = [](const std::vector<double>& v, int stride) {
    std::vector<Eigen::Vector2d> p;
    for (std::size_t i = 0; i + stride <= v.size(); i += stride) p.emplace_back(v[i], v[i + 1]);
    return p;
  };
  const std::vector<Eigen::Vector2d> outer = pairs(all_numbers(outer_text), 3);  // points() gives [x, y, 0]
  const std::vector<Eigen::Vector2d> cavity = pairs(all_numbers(cavity_text), 2);
  const std::vector<double> figures = all_numbers(figures_text);
  ASSERT_EQ(figures.size(), 4u);
  const double wall = figures[0], outer_error = figures[1], inner_error = figures[2], volume = figures[3];
  ASSERT_GT(outer.size(), 10u);
  ASSERT_GT(cavity.size(), 10u);
  // Distance to the outer profile polyline (open).
  const auto to_outer = [&outer](const Eigen::Vector2d& x) {
    double best = INFINITY;
    for (std::size_t i = 0; i + 1 < outer.size(); ++i) {
      const Eigen::Vector2d a = outer[i], b = outer[i + 1];
      const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      best = std::min(best, (a + t * (b - a) - x).norm());
    }
    return best;
  };
  // The inner offset's vertices (all but the floor point on the axis and the point above the rim)
  // lie on the offset curve at `wall` from the fitted profile, which the outer polyline follows
  // within its linearization error; the offset's own tolerance is 1e-3, and the trimmed copy of the
  // bowl that is offset is within 5e-4 of the fitted profile (the script prints 2.1e-4).
  for (std::size_t i = 1; i + 1 < cavity.size(); ++i)
    EXPECT_NEAR(to_outer(cavity[i]), wall, outer_error + 1e-3 + 5e-4) << "cavity vertex " << i;
  // Between the vertices the inner polyline is within its own linearization error of the offset.
  for (std::size_t i = 1; i + 2 < cavity.size(); ++i)
    for (double t : {0.25, 0.5, 0.75}) {
      const Eigen::Vector2d x = (1 - t) * cavity[i] + t * cavity[i + 1];
      EXPECT_NEAR(to_outer(x), wall, outer_error + inner_error + 1e-3 + 5e-4) << "cavity edge " << i;
    }
  // Volume: a profile polygon (r, z) revolved along the regular 32-gon inscribed in the unit circle
  // has cross-sections r^2 A with A = 16 sin(2 pi / 32): frusta A dz (r0^2 + r0 r1 + r1^2) / 3.
  const double A = 16 * std::sin(2 * std::numbers::pi / 32);
  const auto revolved = [A](const std::vector<Eigen::Vector2d>& p, double z_max) {
    double v = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      Eigen::Vector2d a = p[i], b = p[i + 1];
      if (a.y() >= z_max) break;
      if (b.y() > z_max) b = a + (b - a) * ((z_max - a.y()) / (b.y() - a.y()));  // clip at the rim
      v += A * (b.y() - a.y()) * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) / 3;
    }
    return v;
  };
  const double rim = outer.back().y();
  const double expected = revolved(outer, rim) - revolved(cavity, rim);
  EXPECT_NEAR(volume, expected, 1e-6 * expected);
  // The wall is thin: the goblet keeps well under the outer solid's volume.
  EXPECT_LT(volume, revolved(outer, rim) - 50.0);
}

TEST(Builtins, SplineErrorsAtTheCall) {
  EXPECT_EQ(first_error_line("s = fit([[0, 0], [1, 1], [2, 0]], controls=5)"),
            "t.bsp:1:5: error: fit: invalid input: 5 control points need at least as many data points, got 3");
  EXPECT_EQ(first_error_line("s = fit(cubic(), controls=3)"),
            "t.bsp:1:5: error: fit: invalid input: degree 3 needs at least 4 control points, got 3");
  EXPECT_EQ(first_error_line("s = fit(cubic(), controls=8, degree=0)"),
            "t.bsp:1:30: error: fit: argument 'degree' must be a whole number from 1 to 50, got 0");
  EXPECT_EQ(first_error_line("s = fit(cubic())"),
            "t.bsp:1:5: error: fit: give controls=n (the number of control points) or start=s");
  EXPECT_EQ(first_error_line("s = fit(cubic(), controls=8, method=\"best\")"),
            "t.bsp:1:5: error: fit: invalid input: unknown fitting method 'best' (expected sdm, pdm or tdm)");
  EXPECT_EQ(first_error_line("s = fit(cubic(), controls=8, closed=\"yes\")"),
            "t.bsp:1:30: error: fit: closed must be true, false or \"auto\"");
  EXPECT_EQ(first_error_line("s = fit([[1, 1], [1, 1], [1, 1], [1, 1], [1, 1]], controls=4)"),
            "t.bsp:1:5: error: fit: invalid input: all data points coincide");
  EXPECT_EQ(first_error_line("s = fit([[0, 0], [1, 1, 0]], controls=4)"),
            "t.bsp:1:9: error: fit: point 2 has 3 coordinates, the first had 2 (all points must be 2D or all 3D)");
  EXPECT_EQ(first_error_line("s = fit(cubic(), controls=8, smoothing=-1)"),
            "t.bsp:1:30: error: fit: argument 'smoothing' must be a finite number >= 0, got -1");
  EXPECT_EQ(first_error_line("s = fit(cubic(), controls=8, start=bspline([[0, 0], [1, 1], [2, 0], [3, 1]], closed=true))")
                .substr(0, 46),
            "t.bsp:1:5: error: fit: invalid input: the star");
  EXPECT_EQ(first_error_line("s = bspline([[0, 0], [1, 1]])").substr(0, 42), "t.bsp:1:5: error: bspline: invalid input: ");
  EXPECT_EQ(first_error_line("s = bspline([[0, 0], [1, 1], [2, 0]], degree=2, knots=[0, 0, 0, 1, 1])").substr(0, 42),
            "t.bsp:1:5: error: bspline: invalid input: ");
  EXPECT_EQ(first_error_line("s = bspline([])"), "t.bsp:1:13: error: bspline: the list of points is empty");
  EXPECT_EQ(first_error_line("s = reduce_degree(bspline([[0, 0], [1, 1], [2, 0], [3, 1], [4, 0]]), 2)"),
            "t.bsp:1:5: error: reduce_degree: invalid input: degree reduction: the curve is not a Bezier curve");
  EXPECT_EQ(first_error_line("s = reduce_degree(bezier([[0, 0], [1, 1], [2, 0]]), 2)").substr(0, 48),
            "t.bsp:1:5: error: reduce_degree: invalid input: ");
  EXPECT_EQ(first_error_line("h = fit_history(bezier([[0, 0], [1, 1]]))"),
            "t.bsp:1:17: error: fit_history: this spline was not made by fit or reduce_degree");
  EXPECT_EQ(first_error_line("c = sample(bezier([[0, 0], [1, 1]]), 1)").substr(0, 41),
            "t.bsp:1:5: error: sample: invalid input: ");
  EXPECT_EQ(first_error_line("d = degree(cubic())"), "t.bsp:1:12: error: degree: argument 's' must be a spline, got curve");
  EXPECT_EQ(first_error_line("s = load_spline(\"/nonexistent/s.spline\")").substr(0, 52),
            "t.bsp:1:5: error: load_spline: /nonexistent/s.spline");
}

// fit keeps the order of its points (issue 36): an open fit starts at the first point (a clamped
// spline's first control point is its start), also for the same points given the other way, and a
// closed 2D fit turns the way its points do. The points of a half circle from (1, 0) to (-1, 0).
TEST(Builtins, FitKeepsTheOrderOfItsPoints) {
  const std::string half = "fn at(k) { return [cos(pi * k / 40), sin(pi * k / 40)] }\npts = map(at, range(0, 41))\n";
  auto v = numbers(half + "c = control_points(fit(pts, controls=6))\nprint(c[0][0], c[0][1])");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], 1.0, 1e-3);
  EXPECT_NEAR(v[1], 0.0, 1e-3);
  v = numbers(half + "c = control_points(fit(reverse(pts), controls=6))\nprint(c[0][0], c[0][1])");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], -1.0, 1e-3);
  EXPECT_NEAR(v[1], 0.0, 1e-3);
  // A circle given clockwise: the closed fit's samples turn clockwise too (negative area).
  const std::string circle =
      "fn at(k) { return [cos(-2 * pi * k / 60), sin(-2 * pi * k / 60)] }\npts = map(at, range(0, 60))\n";
  v = numbers(
      circle +
      "p = points(sample(fit(curve(pts, closed=true), controls=8), 100))\n"
      "a = 0\nfor i in range(0, 100) { a = a + p[i][0] * p[(i + 1) % 100][1] - p[(i + 1) % 100][0] * p[i][1] }\n"
      "print(a)");
  ASSERT_EQ(v.size(), 1u);
  EXPECT_LT(v[0], 0.0);
}

// fit says "converged" when it has fitted exact data: points of a cubic Bezier curve fitted with
// four control points are matched to rounding, where the relative stopping test cannot hold.
TEST(Builtins, FitOfExactDataConverges) {
  const auto r = run_script(
      "b = bezier([[0, 0], [1, 2], [3, 2], [4, 0]])\ns = fit(sample(b, 60), controls=4)\n"
      "print(str(s))\nprint(distance(s, sample(b, 60))[0] < 1e-6)");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out.find("not converged"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("true"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace sculpt::language
