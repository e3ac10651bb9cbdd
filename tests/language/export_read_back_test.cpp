// Issue 35, "every export reads back": each solid that the random CSG cases (all 300 of
// models/fuzz/csg_cases.txt), the regression models (models/regressions/) and the golden scripts
// that write no files make is exported to every format the mesh layer writes, imported back as a
// user would (the `export` and `import` built-ins) and rebuilt. Checked: the import succeeds, its
// volume is the solid's within what the format and the import may move (below), rebuild(s) works
// and keeps the volume, and no triangle of a written file has zero area (exactly, on the
// coordinates as the file holds them).
//
// Tolerances. Every vertex the file holds is within `format` of the solid's boundary vertex it
// stands for: 0 for the formats that keep doubles (OFF, OBJ, PLY, ASCII STL, .om), float32
// rounding for binary STL and GLB (half a float unit in the last place of the largest coordinate),
// that and 10^-6 for 3MF (lib3mf's six decimals, docs/mesh_io.md). Output rounding may move a vertex
// by up to a grid step where the boundary needed repairing (docs/kernel.md, "Clean output"), and
// the import snaps each to the grid (sqrt(3)/2 steps) and may collapse features below 4 steps. So
// |volume(import) - volume(s)| <= area x (format + 6 grid steps), and 1e-9 relative for rounding.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "kernel/grid.hpp"
#include "language/solid_values.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/predicates.hpp"
#include "script_runner.hpp"
#include "support/sanitizer_share.hpp"
#include "support/source_paths.hpp"

namespace sculpt::language {
namespace {

struct ReadBackFormat {
  const char* ext;
  bool binary;
  double relative;  // float rounding, relative to the largest coordinate
  double absolute;  // decimals the format cuts
};
const ReadBackFormat kReadBackFormats[] = {
    {"off", false, 0, 0},          {"obj", false, 0, 0}, {"ply", false, 0, 0},
    {"ply", true, 0, 0},           {"stl", false, 0, 0}, {"stl", true, 0x1p-24, 0},
    {"3mf", false, 0x1p-23, 1e-6}, {"om", false, 0, 0},  {"glb", false, 0x1p-24, 0}};

std::string format_name(const ReadBackFormat& f) { return std::string(f.binary ? "binary " : "") + f.ext; }

// Zero area, decided exactly on the doubles: the three corners are collinear exactly when every
// projection on a coordinate plane is (the cross product is zero in each component).
bool zero_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  for (int drop = 0; drop < 3; ++drop) {
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    if (orient2d({a[u], a[v]}, {b[u], b[v]}, {c[u], c[v]}) != 0) return false;
  }
  return true;
}

struct Tally {
  int solids = 0, empty = 0, imports = 0, imports_ok = 0, rebuilds_ok = 0;
  std::size_t triangles = 0, zero_area_triangles = 0;
  std::map<std::string, int> failures;  // by format
};

// Exports `solid` (bound as `s`) in every format, imports each file back and rebuilds `s`.
void expect_reads_back(const Value& solid, const std::string& label, Tally& tally) {
  SCOPED_TRACE(label);
  const SolidValue* sv = solid.object<SolidValue>();
  ASSERT_NE(sv, nullptr);
  ++tally.solids;
  const double v = sv->volume();
  if (sv->boundary().faces.empty()) {
    ++tally.empty;
    return;
  }
  const double area = sv->area();
  double extent = 0;
  for (const Eigen::Vector3d& p : sv->boundary().vertices) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  const double step = sv->solid.grid().step();
  std::ostringstream out;
  Interpreter interpreter({.out = &out, .grid = sv->solid.grid()});  // imports at the solid's grid
  interpreter.define("s", solid);
  // One folder per process: ctest runs the tests of this file side by side.
  const std::string dir = ::testing::TempDir() + "sculpt_read_back_" + std::to_string(::getpid()) + "/";
  std::filesystem::create_directories(dir);
  // The sanitizer build writes each solid in every kSanitizerStride-th format, the formats taking
  // turns from one solid to the next: every format is still written and read back there (by a
  // share of the solids), at a share of the time (docs/building.md).
  for (std::size_t k = 0; k < std::size(kReadBackFormats); ++k) {
    if ((k + std::size_t(tally.solids)) % std::size_t(checks::kSanitizerStride) != 0) continue;
    const ReadBackFormat& f = kReadBackFormats[k];
    SCOPED_TRACE(format_name(f));
    const std::string path = dir + "case" + (f.binary ? "_binary." : ".") + f.ext;
    ++tally.imports;
    std::optional<Value> back;
    try {
      interpreter.run(testing::text_source("export(s, \"" + path + "\"" + (f.binary ? ", binary=true" : "") + ")"));
      back = interpreter.run(testing::text_source("import(\"" + path + "\")"));
    } catch (const ScriptError& e) {
      ADD_FAILURE() << format_error(e);
      ++tally.failures[format_name(f)];
      continue;
    }
    ASSERT_TRUE(back.has_value());
    const SolidValue* imported = back->object<SolidValue>();
    ASSERT_NE(imported, nullptr);
    const double format = f.relative * extent + f.absolute;
    const double tolerance = area * (format + 6 * step) + 1e-9 * std::max(1.0, v);
    EXPECT_NEAR(imported->volume(), v, tolerance);
    if (std::abs(imported->volume() - v) <= tolerance)
      ++tally.imports_ok;
    else
      ++tally.failures[format_name(f) + " volume"];
    const PolygonMesh written = read_mesh(path);
    for (const auto& face : written.faces) {
      if (face.size() != 3) continue;
      ++tally.triangles;
      if (zero_area(written.vertices[std::size_t(face[0])], written.vertices[std::size_t(face[1])],
                    written.vertices[std::size_t(face[2])])) {
        ++tally.zero_area_triangles;
        ADD_FAILURE() << "a triangle of zero area";
      }
    }
  }
  try {
    const std::optional<Value> rebuilt = interpreter.run(testing::text_source("rebuild(s)"));
    ASSERT_TRUE(rebuilt.has_value());
    const SolidValue* r = rebuilt->object<SolidValue>();
    ASSERT_NE(r, nullptr);
    EXPECT_NEAR(r->volume(), v, 1e-9 * std::max(1.0, v));
    ++tally.rebuilds_ok;
  } catch (const ScriptError& e) {
    ADD_FAILURE() << "rebuild: " << format_error(e);
    ++tally.failures["rebuild"];
  }
}

void print(const Tally& t, const std::string& what) {
  std::cout << "[ info ] " << what << ": " << t.solids << " solids (" << t.empty << " empty), " << t.imports_ok
            << " of " << t.imports << " imports read back, " << t.rebuilds_ok << " rebuilds, " << t.zero_area_triangles
            << " of " << t.triangles << " written triangles of zero area\n";
  for (const auto& [kind, n] : t.failures) std::cout << "[ info ]   " << n << " x " << kind << "\n";
}

std::optional<Value> run_file(Interpreter& interpreter, const std::string& path) {
  return interpreter.run(load_source(path));
}

// The random cases: slice k of kSlices takes cases k, k + kSlices, ...: all 300 over the slices,
// which run side by side. The sanitizer build takes every kSanitizerShare-th of each slice's cases
// (25 of the 300): it looks for memory errors, which the same code paths show on fewer cases.
constexpr int kSlices = 12;
constexpr int kSanitizerShare = checks::kSanitizerStride > 1 ? 12 : 1;
class EveryExportReadsBack : public ::testing::TestWithParam<int> {};

TEST_P(EveryExportReadsBack, RandomSetOperationsOverTransformedPrimitives) {
  std::ifstream in(sculpt::test::models_dir() + "/fuzz/csg_cases.txt");
  std::vector<std::string> cases;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("case ", 0) == 0) cases.push_back(line.substr(line.find("expr=") + 5));
  ASSERT_GE(cases.size(), 100u);
  Tally tally;
  for (std::size_t i = std::size_t(GetParam()); i < cases.size(); i += std::size_t(kSlices * kSanitizerShare)) {
    Interpreter interpreter;
    std::optional<Value> value;
    try {
      value = interpreter.run(testing::text_source(cases[i], "case.bsp"));
    } catch (const ScriptError& e) {
      ADD_FAILURE() << format_error(e);
      continue;
    }
    ASSERT_TRUE(value.has_value());
    expect_reads_back(*value, "case " + std::to_string(i) + ": " + cases[i], tally);
  }
  print(tally, "random cases, slice " + std::to_string(GetParam()));
  EXPECT_EQ(tally.imports_ok, tally.imports);
  EXPECT_EQ(tally.zero_area_triangles, 0u);
}
INSTANTIATE_TEST_SUITE_P(ExportReadBack, EveryExportReadsBack, ::testing::Range(0, kSlices));

// The regression models and the issue's two parts.
TEST(ExportReadBack, RegressionModelsAndIssueParts) {
  Tally tally;
  for (const char* file : {"apex_of_touching_slivers.bsp", "float32_bridged_hole.bsp", "folded_snap_rotation.bsp",
                           "snap_local_crossings.bsp", "stroke_export_reimport.bsp"}) {
    Interpreter interpreter;
    const std::optional<Value> value = run_file(interpreter, sculpt::test::models_dir() + "/regressions/" + file);
    const std::string last = latest_solid_global(interpreter);
    if (value.has_value() && value->object<SolidValue>() != nullptr)
      expect_reads_back(*value, file, tally);
    else if (!last.empty())
      expect_reads_back(*interpreter.global(last), std::string(file) + ": " + last, tally);
  }
  const char* parts[] = {
      // issue 35: a cylinder's vertex on a box face
      "box([5,5,0],[10,10,40]) - translate(cylinder(5, 40, segments=8), [10,10,0])",
      // issue 35: an L bracket (a hull of a box and two cylinders, an upright, a fillet, four holes)
      "base = hull([box([0,0,0],[40,20,4]), translate(cylinder(5, 4, segments=32), [40,10,0])])\n"
      "up = box([0,0,0],[4,20,30])\n"
      "fillet = box([4,0,4],[10,20,10]) - translate(rotate(cylinder(6, 20, segments=32), [1,0,0], -90), [10,0,10])\n"
      "holes = translate(cylinder(2, 10, segments=16), [15,10,-1]) | translate(cylinder(2, 10, segments=16), "
      "[30,10,-1])"
      " | translate(rotate(cylinder(2, 10, segments=16), [0,1,0], 90), [-1,10,15])"
      " | translate(rotate(cylinder(2, 10, segments=16), [0,1,0], 90), [-1,10,24])\n"
      "(base | up | fillet) - holes",
  };
  for (const char* part : parts) {
    Interpreter interpreter;
    const std::optional<Value> value = interpreter.run(testing::text_source(part, "part.bsp"));
    ASSERT_TRUE(value.has_value());
    expect_reads_back(*value, part, tally);
  }
  print(tally, "regression models and parts");
  EXPECT_EQ(tally.imports_ok, tally.imports);
  EXPECT_EQ(tally.zero_area_triangles, 0u);
}

// Every solid bound by the golden scripts that write no files (scripts/*.bsp with a .expect and no
// export, render or stats file).
TEST(ExportReadBack, GoldenScriptSolids) {
  Tally tally;
  const std::string scripts = sculpt::test::source_dir() + "/scripts";
  for (const char* name :
       {"first_box", "language_tour", "world_range", "implicit", "motions", "bracket", "plate", "vase"}) {
    std::ostringstream out;
    Interpreter interpreter({.out = &out});
    run_file(interpreter, scripts + "/" + name + ".bsp");
    for (const std::string& global : interpreter.global_names())
      if (const Value* v = interpreter.global(global); v->object<SolidValue>() != nullptr)
        expect_reads_back(*v, std::string(name) + ".bsp: " + global, tally);
  }
  print(tally, "golden-script solids");
  EXPECT_EQ(tally.imports_ok, tally.imports);
  EXPECT_EQ(tally.zero_area_triangles, 0u);
}

}  // namespace
}  // namespace sculpt::language
