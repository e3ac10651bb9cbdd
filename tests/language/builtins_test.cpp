// Built-ins checked by independent references: analytic volumes and areas, set identities,
// invariants of linearizations (segment counts, monotone error, optimal <= heuristics), file
// round trips. Errors from the libraries below appear at the script position of the call.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "language/builtins.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::run_script;

/// Runs `text` and returns the numbers it printed, one per print() argument.
std::vector<double> numbers(const std::string& text) {
  const auto r = run_script(text);
  EXPECT_EQ(r.error, "") << text;
  std::vector<double> out;
  std::istringstream in(r.out);
  for (std::string word; in >> word;) out.push_back(std::stod(word));
  return out;
}

std::string first_error_line(const std::string& text) {
  const auto r = run_script(text);
  return r.error.substr(0, r.error.find('\n'));
}

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
  // A regular 24-gon of circumradius 1 has area 12 sin(2 pi / 24); vertices are snapped to the
  // kernel grid, hence the relative tolerance.
  const double tolerance = 1e-7 * v[0];
  EXPECT_NEAR(v[0], 2 * 12 * std::sin(2 * M_PI / 24), tolerance);
  EXPECT_NEAR(v[1], v[0], tolerance);
  EXPECT_NEAR(v[2], 8 * v[0], 8 * tolerance);
  EXPECT_NEAR(v[3], 6 * v[0], 6 * tolerance);
  EXPECT_NEAR(v[4], v[0], tolerance);
  EXPECT_NEAR(v[5], v[0] / 3, tolerance);
}

TEST(Builtins, SolidOperatorsNeedSolids) {
  EXPECT_EQ(first_error_line("x = box([0, 0, 0], [1, 1, 1]) | 3"), "t.bsp:1:31: error: cannot apply '|' to solid and number");
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
  const auto dir = std::filesystem::temp_directory_path() / "sculpt_language_test";
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
  const auto dir = std::filesystem::temp_directory_path() / "sculpt_language_test";
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
TEST(Builtins, ImportRefusesAMeshThatSelfIntersectsOnceSnapped) {
  const auto dir = std::filesystem::temp_directory_path() / "sculpt_language_test";
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
  const std::string near = write_two_cubes("two_cubes_near.off", 1e-6);
  const std::string e = first_error_line("s = import(\"" + near + "\")");
  EXPECT_NE(e.find("t.bsp:1:5: error: import: "), std::string::npos) << e;
  EXPECT_NE(e.find("meet when the vertices are snapped to the exact kernel's grid"), std::string::npos) << e;
}

}  // namespace
}  // namespace sculpt::language
