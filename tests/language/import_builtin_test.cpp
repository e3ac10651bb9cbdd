// import (issue 35): a closed mesh whose faces intersect, or meet at non-manifold edges, imports as
// the region of positive winding number and says what it resolved; strict=true refuses it as
// before; an open mesh is refused with its open edges; an export that reads back with nothing
// moved prints no warning.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "language/solid_values.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/shapes.hpp"
#include "script_runner.hpp"
#include "support/cgal_mesh_check.hpp"
#include "support/scratch_path.hpp"
#include "support/source_paths.hpp"

namespace sculpt::language {
namespace {

using testing::run_script;

std::string written(const PolygonMesh& mesh, const std::string& name) {
  const auto dir = test::scratch_path("sculpt_import_test");
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  write_mesh(mesh, path);
  return path;
}

// Random case 41 (models/fuzz/csg_cases.txt) exported as OFF: snapping its vertices to the grid made
// from_mesh's check fail, and the snap rounding that followed only triangulated the faces. import
// used to warn "features below 4 grid steps were collapsed ... vertices moved by up to 0 grid
// steps" (and "up to 0.7" where only the snap moved them): nothing was collapsed, so nothing is said.
TEST(ImportBuiltin, ExportedMeshReadsBackWithoutAWarningWhenNothingWasCollapsed) {
  const auto dir = test::scratch_path("sculpt_import_test");
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "case41.off").string();
  const auto r = run_script(
      "s = rotate(sphere(0.67109375, segments=24), [2.0, -2.0, -1.0], 205.6) - translate(cylinder(0.43359375, "
      "0.64453125, segments=9), [-0.62890625, 0.50390625, -0.55859375])\n"
      "export(s, \"" +
      path + "\")\ng = import(\"" + path + "\")\nprint(abs(volume(g) - volume(s)) < area(s) * pow(2, -15))\n");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "true\n");
  EXPECT_EQ(r.err, "");  // no warning (built-ins' warnings go to standard error)
}

TEST(ImportBuiltin, OverlappingBoxesInOneMeshImportAsTheirUnion) {
  const std::string path =
      written(test_shapes::merged(test_shapes::box({0, 0, 0}, {2, 2, 2}), test_shapes::box({1, 1, 1}, {3, 3, 3})),
              "overlapping_boxes.off");
  const auto r = run_script("print(volume(import(\"" + path + "\")))");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.err, "import: " + path +
                       ": 6 face pairs intersect: imported the region of positive winding number (parts enclosed more "
                       "than once count once)\n");
  EXPECT_EQ(r.out, "15\n");
  const auto strict = run_script("s = import(\"" + path + "\", strict=true)");
  EXPECT_NE(strict.error.find("t.bsp:1:5: error: import: " + path + " is not a closed manifold: "), std::string::npos)
      << strict.error;
  EXPECT_NE(strict.error.find("self-intersection"), std::string::npos) << strict.error;
}

TEST(ImportBuiltin, BoxesSharingAnEdgeImportAsBoth) {
  // The two boxes share the edge x = y = 1, its ends one vertex each (four faces on it): a
  // non-manifold edge.
  PolygonMesh mesh =
      test_shapes::merged(test_shapes::box({0, 0, 0}, {1, 1, 1}), test_shapes::box({1, 1, 0}, {2, 2, 1}));
  for (std::size_t f = 6; f < 12; ++f)
    for (int& v : mesh.faces[f]) v = v == 8 ? 3 : (v == 12 ? 7 : v);
  const std::string path = written(mesh, "edge_boxes.off");
  const auto r = run_script("print(volume(import(\"" + path + "\")))");
  EXPECT_EQ(r.error, "");
  EXPECT_NE(r.err.find(": imported the region of positive winding number"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "2\n");
}

TEST(ImportBuiltin, OpenMeshIsRefusedWithItsOpenEdges) {
  PolygonMesh open = test_shapes::box({0, 0, 0}, {1, 1, 1});
  open.faces.pop_back();
  const std::string path = written(open, "open_box.off");
  const auto r = run_script("s = import(\"" + path + "\")");
  EXPECT_NE(r.error.find("is not a closed manifold: open edge: 4"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("open edge (1, 0, 0) - (1, 1, 0)"), std::string::npos) << r.error;  // where
}

// The topology check and the search of the snapped faces run side by side: the search's error
// (a vertex beyond the kernel's range cannot be snapped) is the answer only for a mesh whose
// topology is clean; an open mesh is refused for what is open, as when they ran one after the other.
TEST(ImportBuiltin, TopologyIsReportedBeforeASnappingError) {
  PolygonMesh far = test_shapes::box({0, 0, 0}, {1, 1, 1});
  for (Eigen::Vector3d& v : far.vertices)
    if (v.x() > 0.5) v.x() = 5000;  // beyond the default grid's [-1024, 1024]
  const auto closed = run_script("s = import(\"" + written(far, "far_box.off") + "\")");
  EXPECT_NE(closed.error.find("outside the exact kernel's range"), std::string::npos) << closed.error;
  far.faces.pop_back();
  const auto open = run_script("s = import(\"" + written(far, "far_open_box.off") + "\")");
  EXPECT_NE(open.error.find("is not a closed manifold: open edge: 4"), std::string::npos) << open.error;
  EXPECT_EQ(open.error.find("outside the exact kernel's range"), std::string::npos) << open.error;
}

// The bunny and a turned copy that overlaps it, written as one mesh (many crossing face pairs, as a
// scan that touches itself): imported as their union, whose export CGAL finds clean in every format.
TEST(ImportBuiltin, BunnyAndTurnedCopyInOneFileImportAsOneCleanSolid) {
  const PolygonMesh bunny = read_mesh(sculpt::test::models_dir() + "/bunny.off");
  PolygonMesh copy = bunny;
  const Eigen::Affine3d turn(Eigen::Translation3d(1.5, 0.5, 0) *
                             Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()));
  for (Eigen::Vector3d& v : copy.vertices) v = turn * v;
  const PolygonMesh both = test_shapes::merged(bunny, copy);
  const std::string path = written(both, "two_bunnies.off");
  std::ostringstream out;
  Interpreter interpreter({.err = &out});
  const std::optional<Value> value = interpreter.run(testing::text_source("import(\"" + path + "\")"));
  ASSERT_TRUE(value.has_value());
  EXPECT_NE(out.str().find("face pairs intersect: imported the region of positive winding number"), std::string::npos)
      << out.str();
  const SolidValue* solid = value->object<SolidValue>();
  ASSERT_NE(solid, nullptr);
  EXPECT_GT(solid->volume(), mesh_volume(bunny));
  EXPECT_LT(solid->volume(), mesh_volume(both));
  for (const MeshFormat format : {MeshFormat::Off, MeshFormat::Stl, MeshFormat::Glb}) {
    const PolygonMesh back =
        decode_mesh(encode_mesh(solid->boundary(), format, format == MeshFormat::Stl), format, "bunnies");
    EXPECT_TRUE(checks::CleanForOtherTools(back.vertices, back.faces));
  }
}

}  // namespace
}  // namespace sculpt::language
