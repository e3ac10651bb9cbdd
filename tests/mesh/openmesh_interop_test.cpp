// Interoperability with OpenMesh 9 (the reference reader/writer named by the project):
// it reads what we write, and we read what it writes. OpenMesh passes coordinates as float32,
// so comparisons here are at float precision (docs/mesh_io.md).
// OpenMesh's property containers trip GCC 12's -Wmaybe-uninitialized (a false positive in
// OpenMesh's headers, seen with -O2 and sanitizers).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Utils/vector_cast.hh>
#pragma GCC diagnostic pop
#include <gtest/gtest.h>

#include <sstream>

#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh_test_dir.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

/// OpenMesh prints progress and warnings on std::cerr (omlog/omerr): silence it for a call.
template <typename F>
auto quietly(F f) {
  std::ostringstream sink;
  auto* old = std::cerr.rdbuf(sink.rdbuf());
  auto* old_log = std::clog.rdbuf(sink.rdbuf());
  auto result = f();
  std::cerr.rdbuf(old);
  std::clog.rdbuf(old_log);
  return result;
}

double om_volume(const OmMesh& m) {
  double v = 0;
  for (auto f : m.faces()) {
    std::vector<OpenMesh::Vec3d> p;
    for (auto vh : m.fv_range(f)) p.push_back(m.point(vh));
    for (size_t i = 1; i + 1 < p.size(); ++i) v += OpenMesh::dot(p[0], OpenMesh::cross(p[i], p[i + 1]));
  }
  return v / 6;
}

struct InteropCase {
  const char* ext;
  bool binary;
};

class OpenMeshReadsOurs : public ::testing::TestWithParam<InteropCase> {};

TEST_P(OpenMeshReadsOurs, SameCountsAndVolume) {
  const InteropCase c = GetParam();
  const PolygonMesh m = test_shapes::box({-1, 0.5, 2}, {3, 1.75, 2.5});
  const auto path = test_dir() / (std::string("om_") + (c.binary ? "bin" : "txt") + c.ext);
  write_mesh(m, path, {.binary = c.binary});
  OmMesh om;
  OpenMesh::IO::Options opt;
  if (c.binary) opt += OpenMesh::IO::Options::Binary;
  ASSERT_TRUE(quietly([&] { return OpenMesh::IO::read_mesh(om, path.string(), opt); }));
  EXPECT_EQ(om.n_vertices(), 8u);
  EXPECT_EQ(om.n_faces(), std::string(c.ext) == ".stl" ? 12u : 6u);
  EXPECT_NEAR(om_volume(om), mesh_volume(m), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Formats, OpenMeshReadsOurs,
                         ::testing::Values(InteropCase{".off", false}, InteropCase{".obj", false},
                                           InteropCase{".ply", false}, InteropCase{".ply", true},
                                           InteropCase{".stl", false}, InteropCase{".stl", true}),
                         [](const auto& param_info) {
                           return std::string(param_info.param.ext + 1) + (param_info.param.binary ? "_binary" : "_ascii");
                         });

class WeReadOpenMesh : public ::testing::TestWithParam<InteropCase> {};

TEST_P(WeReadOpenMesh, SameCountsAndVolume) {
  const InteropCase c = GetParam();
  OmMesh om;
  const PolygonMesh m = test_shapes::octahedron();
  std::vector<OmMesh::VertexHandle> vh;
  for (const auto& p : m.vertices) vh.push_back(om.add_vertex({p.x(), p.y(), p.z()}));
  for (const auto& f : m.faces) om.add_face({vh[f[0]], vh[f[1]], vh[f[2]]});
  const auto path = test_dir() / (std::string("from_om_") + (c.binary ? "bin" : "txt") + c.ext);
  OpenMesh::IO::Options opt;
  if (c.binary) opt += OpenMesh::IO::Options::Binary;
  ASSERT_TRUE(quietly([&] { return OpenMesh::IO::write_mesh(om, path.string(), opt, 17); }));
  const PolygonMesh r = read_mesh(path);
  EXPECT_EQ(r.vertices.size(), 6u);
  EXPECT_EQ(r.faces.size(), 8u);
  EXPECT_NEAR(mesh_volume(r), 4.0 / 3, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Formats, WeReadOpenMesh,
                         ::testing::Values(InteropCase{".off", false}, InteropCase{".obj", false},
                                           InteropCase{".ply", false}, InteropCase{".ply", true},
                                           InteropCase{".stl", false}, InteropCase{".stl", true}),
                         [](const auto& param_info) {
                           return std::string(param_info.param.ext + 1) + (param_info.param.binary ? "_binary" : "_ascii");
                         });

}  // namespace
}  // namespace sculpt
