// Round trips through every format, exactness of doubles, and error messages on bad files.
#include "mesh/mesh_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>

#include "base/errors.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/triangulate.hpp"
#include "mesh_test_dir.hpp"
#include "shapes.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

namespace fs = std::filesystem;

/// A closed mesh whose coordinates are awkward doubles (not representable in decimal with
/// few digits, tiny, huge, negative zero, subnormal).
PolygonMesh awkward_mesh() {
  PolygonMesh m = test_shapes::box({0.1, 1.0 / 3, -0.0}, {std::numbers::pi, 2.0 / 3 + 1e-12, 1e-300});
  m.vertices[7] = {std::nextafter(std::numbers::pi, 4.0), 2.0 / 3 + 1e-12, 1e-300};
  m.vertices[0].y() = 4.9406564584124654e-324;  // smallest subnormal
  m.vertices[5].x() = 1.7976931348623157e308;  // largest double
  return m;
}

bool bit_equal(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  for (int k = 0; k < 3; ++k)
    if (std::bit_cast<uint64_t>(a[k]) != std::bit_cast<uint64_t>(b[k])) return false;
  return true;
}

void expect_identical(const PolygonMesh& a, const PolygonMesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i)
    EXPECT_TRUE(bit_equal(a.vertices[i], b.vertices[i]))
        << "vertex " << i << ": " << a.vertices[i].transpose() << " vs " << b.vertices[i].transpose();
  EXPECT_EQ(a.faces, b.faces);
}

/// Triangles of a mesh as sorted coordinate lists, rotated to start at the smallest corner:
/// comparable across different vertex numberings.
std::multiset<std::vector<std::tuple<double, double, double>>> triangle_set(const PolygonMesh& m) {
  std::multiset<std::vector<std::tuple<double, double, double>>> out;
  for (const auto& f : m.faces) {
    std::vector<std::tuple<double, double, double>> c;
    for (int v : f) c.emplace_back(m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z());
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    out.insert(c);
  }
  return out;
}

struct Case {
  const char* ext;
  bool binary;
};

class RoundTrip : public ::testing::TestWithParam<Case> {};
class PolygonRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(PolygonRoundTrip, KeepsEveryBitAndIndex) {  // STL stores triangles: see StlRoundTrip
  const Case c = GetParam();
  const PolygonMesh m = awkward_mesh();
  const fs::path path = test_dir() / (std::string("awkward") + (c.binary ? "_bin" : "") + c.ext);
  write_mesh(m, path, {.binary = c.binary});
  expect_identical(m, read_mesh(path));
}

TEST_P(RoundTrip, CubeKeepsVolumeAndTopology) {
  const Case c = GetParam();
  const PolygonMesh m = test_shapes::box({-1, -2, -3}, {0.5, 0.25, 4});
  const fs::path path = test_dir() / (std::string("cube") + (c.binary ? "_bin" : "") + c.ext);
  write_mesh(m, path, {.binary = c.binary});
  const PolygonMesh r = read_mesh(path);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(r));
  EXPECT_TRUE(checks::NoDuplicateVertices(r));
  EXPECT_TRUE(checks::GenusIs(r, 0));
  EXPECT_TRUE(checks::VolumeNear(r, 1.5 * 2.25 * 7, 1e-15));
  EXPECT_EQ(r.vertices.size(), 8u);
  const std::string ext = c.ext;
  EXPECT_EQ(r.faces.size(), ext == ".stl" || ext == ".3mf" || ext == ".glb" ? 12u : 6u);
}

INSTANTIATE_TEST_SUITE_P(Formats, PolygonRoundTrip,
                         ::testing::Values(Case{".off", false}, Case{".obj", false}, Case{".ply", false},
                                           Case{".ply", true}, Case{".om", false}),
                         [](const auto& param_info) {
                           return std::string(param_info.param.ext + 1) + (param_info.param.binary ? "_binary" : "_ascii");
                         });

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip,
                         ::testing::Values(Case{".off", false}, Case{".obj", false}, Case{".ply", false},
                                           Case{".ply", true}, Case{".stl", false}, Case{".stl", true},
                                           Case{".om", false}, Case{".3mf", false}, Case{".glb", false}),
                         [](const auto& param_info) {
                           return std::string(param_info.param.ext + 1) + (param_info.param.binary ? "_binary" : "_ascii");
                         });

TEST(OmFormat, TruncatedOrForeignDataIsAnErrorOrAMeshNeverACrash) {
  // OpenMesh's reader is not ours: feed it every prefix of a valid file and some foreign bytes.
  const std::string om = encode_mesh(test_shapes::uv_sphere(8), MeshFormat::Om);
  int errors = 0;
  for (std::size_t n = 0; n < om.size(); ++n) {
    try {
      (void)decode_mesh(std::string_view(om).substr(0, n), MeshFormat::Om, "cut.om");
    } catch (const IoError&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 0);
  EXPECT_THROW((void)decode_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Om, "off.om"), IoError);
}

/// What lib3mf 1.8 keeps of a coordinate (its mesh writer, putFloat): the float32 nearest to the
/// double, times 10^6 in float32 arithmetic, truncated towards zero to an integer, written as
/// that integer / 10^6 with six decimals, and parsed back into a float32.
double lib3mf_stored(double x) {
  const float f = static_cast<float>(x);
  const auto n = static_cast<std::int64_t>(f * 1000000.0f);
  char text[64];
  const std::int64_t a = n < 0 ? -n : n;
  std::snprintf(text, sizeof text, "%s%lld.%06lld", f < 0 && a ? "-" : "", static_cast<long long>(a / 1000000),
                static_cast<long long>(a % 1000000));
  return double(std::strtof(text, nullptr));
}

/// lib3mf truncates, so what it keeps of a kept value can be one unit less: the value written is
/// the first of lib3mf_stored(x), lib3mf_stored of that, ... that it keeps unchanged (the writer
/// rounds to such values so that the file is judged clean as it will be read).
double lib3mf_written(double x) {
  double v = lib3mf_stored(x);
  for (int i = 0; i < 32 && lib3mf_stored(v) != v; ++i) v = lib3mf_stored(v);
  return v;
}

TEST(ThreeMfFormat, KeepsMicrometresOfEachFloat32CoordinateAndTheVolume) {
  // 3MF through lib3mf 1.8: a position is a float32 (MODELMESHVERTEX) that lib3mf writes as XML
  // text with six decimals (nanometres when the unit is the millimetre). Every coordinate must
  // read back as exactly lib3mf_stored() of it, within 1e-6 plus float32 roundings of
  // it; the vertices in the same order, the triangles as written, closed and oriented.
  PolygonMesh m = test_shapes::uv_sphere(24);
  for (Eigen::Vector3d& v : m.vertices) v = v * 37.123456789 + Eigen::Vector3d(1.0 / 3, -250.000001, 1e-7);
  const fs::path path = test_dir() / "sphere.3mf";
  write_mesh(m, path);
  const PolygonMesh r = read_mesh(path);
  const PolygonMesh t = triangulate(m);
  ASSERT_EQ(r.vertices.size(), m.vertices.size());
  PolygonMesh stored = t;  // the model of what 3MF keeps, computed here
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      stored.vertices[i][k] = lib3mf_written(m.vertices[i][k]);
      EXPECT_LE(std::abs(r.vertices[i][k] - m.vertices[i][k]), 1e-6 + 3 * std::abs(m.vertices[i][k]) * 0x1p-24);
    }
    EXPECT_TRUE(bit_equal(r.vertices[i], stored.vertices[i])) << "vertex " << i << ": " << r.vertices[i].transpose();
  }
  EXPECT_EQ(r.faces, t.faces);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(r));
  EXPECT_NEAR(mesh_volume(r), mesh_volume(stored), 1e-12 * mesh_volume(stored));
  // The narrowing is real: this mesh's doubles are not kept.
  EXPECT_GT(std::abs(mesh_volume(r) - mesh_volume(m)), 0.0);
}

// A coordinate whose kept value lib3mf would narrow again (truncation) is written as a value it
// keeps, so a file read and written again is the same file.
TEST(ThreeMfFormat, AFileReadAndWrittenAgainIsTheSameFile) {
  double x = 0.1;
  while (lib3mf_stored(lib3mf_stored(x)) == lib3mf_stored(x)) x += 1e-7;  // such values are about 1 in 100
  ASSERT_LT(x, 0.2);
  PolygonMesh tetra;
  tetra.vertices = {{x, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::string once = encode_mesh(tetra, MeshFormat::ThreeMf);
  const PolygonMesh back = decode_mesh(once, MeshFormat::ThreeMf, "t.3mf");
  ASSERT_EQ(back.vertices.size(), 4u);
  EXPECT_EQ(back.vertices[0].x(), lib3mf_written(x));
  EXPECT_NE(back.vertices[0].x(), lib3mf_stored(x));
  EXPECT_EQ(encode_mesh(back, MeshFormat::ThreeMf), once);
}

TEST(ThreeMfFormat, TheSameMeshGivesTheSameBytes) {
  const PolygonMesh m = test_shapes::uv_sphere(8);
  EXPECT_EQ(encode_mesh(m, MeshFormat::ThreeMf), encode_mesh(m, MeshFormat::ThreeMf));
  PolygonMesh moved = m;
  moved.vertices[0].x() += 0.5;
  EXPECT_NE(encode_mesh(m, MeshFormat::ThreeMf), encode_mesh(moved, MeshFormat::ThreeMf));
}

TEST(ThreeMfFormat, TruncatedOrForeignDataIsAnErrorOrAMeshNeverACrash) {
  const std::string package = encode_mesh(test_shapes::uv_sphere(8), MeshFormat::ThreeMf);
  ASSERT_GT(package.size(), 100u);
  int errors = 0;
  for (std::size_t n = 0; n < package.size(); n += 1 + n / 16) {
    try {
      (void)decode_mesh(std::string_view(package).substr(0, n), MeshFormat::ThreeMf, "cut.3mf");
    } catch (const IoError&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 0);
  EXPECT_THROW((void)decode_mesh("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::ThreeMf, "off.3mf"), IoError);
  PolygonMesh far = test_shapes::unit_cube();
  far.vertices[0].x() = 1e300;
  EXPECT_THROW((void)encode_mesh(far, MeshFormat::ThreeMf), InvalidInput);
}

TEST(OmFormat, ANonManifoldFaceIsRefusedNotDropped) {
  PolygonMesh fin = test_shapes::unit_cube();
  fin.vertices.emplace_back(0.5, -1, 0.5);
  fin.faces.push_back({0, 1, static_cast<int>(fin.vertices.size()) - 1});  // a third face on edge 0-1
  EXPECT_THROW((void)encode_mesh(fin, MeshFormat::Om), InvalidInput);
}

TEST(StlRoundTrip, AsciiKeepsDoublesAndMergesCornersExactly) {
  // Planar faces, so that triangulation keeps them all: subnormal, tiny, negative zero.
  const PolygonMesh m =
      triangulate(test_shapes::box({0.1, 4.9406564584124654e-324, -0.0}, {std::numbers::pi, 2.0 / 3, 1e-300}));
  ASSERT_EQ(m.faces.size(), 12u);
  const fs::path path = test_dir() / "awkward_ascii.stl";
  write_mesh(m, path);
  const PolygonMesh r = read_mesh(path);
  EXPECT_EQ(r.vertices.size(), m.vertices.size());  // 36 facet corners merged back into 8
  EXPECT_EQ(triangle_set(r), triangle_set(m));
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(r));
}

TEST(StlRoundTrip, BinaryRoundsToFloat32) {
  PolygonMesh m = triangulate(test_shapes::box({0.1, 0.2, 0.3}, {1.1, 1.2, 1.3}));
  const fs::path path = test_dir() / "rounded.stl";
  write_mesh(m, path, {.binary = true});
  EXPECT_EQ(fs::file_size(path), 84u + 50u * 12u);
  for (auto& p : m.vertices) p = p.cast<float>().cast<double>();  // what float32 can carry
  const PolygonMesh r = read_mesh(path);
  EXPECT_EQ(triangle_set(r), triangle_set(m));
}

TEST(StlRoundTrip, NegativeZeroMergesWithZero) {
  const std::string text =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex -0 0 -0\nvertex 0 1 0\nvertex -1 0 0\nendloop\nendfacet\nendsolid t\n";
  const PolygonMesh r = decode_mesh(text, MeshFormat::Stl, "t.stl");
  EXPECT_EQ(r.vertices.size(), 4u);
  EXPECT_EQ(r.faces[1][0], 0);
}

TEST(MeshIo, LargePolygonsAndManyVerticesInPly) {
  PolygonMesh m;  // a 300-gon prism: faces with more than 255 corners need a wide list count
  const int n = 300;
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < n; ++i)
      m.vertices.emplace_back(std::cos(2 * std::numbers::pi * i / n), std::sin(2 * std::numbers::pi * i / n), z);
  std::vector<int> bottom, top;
  for (int i = 0; i < n; ++i) {
    bottom.push_back(n - 1 - i);
    top.push_back(n + i);
    m.faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
  }
  m.faces.push_back(bottom);
  m.faces.push_back(top);
  for (bool binary : {false, true}) {
    const fs::path path = test_dir() / (binary ? "prism_bin.ply" : "prism.ply");
    write_mesh(m, path, {.binary = binary});
    expect_identical(m, read_mesh(path));
  }
  EXPECT_TRUE(checks::GenusIs(m, 0));
}

TEST(MeshIo, ReadsForeignVariants) {
  // OFF with comments, counts on the header line, colors after the coordinates.
  const PolygonMesh off = decode_mesh("OFF 3 1 0\n# comment\n0 0 0 255 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 1 1\n",
                                      MeshFormat::Off, "t.off");
  EXPECT_EQ(off.vertices.size(), 3u);
  EXPECT_EQ(off.faces, (std::vector<std::vector<int>>{{0, 1, 2}}));
  // OBJ with texture/normal references, negative indices, groups and w.
  const PolygonMesh obj = decode_mesh(
      "mtllib x.mtl\no thing\nv 0 0 0\nv 2 0 0 2\nv 0 1 0\nvt 0 0\nvn 0 0 1\ng a\nf 1/1/1 2//1 -1/1\n",
      MeshFormat::Obj, "t.obj");
  EXPECT_EQ(obj.faces, (std::vector<std::vector<int>>{{0, 1, 2}}));
  EXPECT_EQ(obj.vertices[1], Eigen::Vector3d(1, 0, 0));
  // PLY, big endian float with an extra property and an extra element.
  std::string ply = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nproperty uchar red\nelement face 1\nproperty list uchar uint vertex_indices\n"
                    "element edge 1\nproperty int a\nproperty int b\nend_header\n";
  auto be_float = [&](float f) {
    const auto u = std::bit_cast<uint32_t>(f);
    for (int s = 24; s >= 0; s -= 8) ply += static_cast<char>((u >> s) & 0xff);
  };
  auto be_u32 = [&](uint32_t u) {
    for (int s = 24; s >= 0; s -= 8) ply += static_cast<char>((u >> s) & 0xff);
  };
  const float coords[3][3] = {{0, 0, 0}, {0.5f, 0, 0}, {0, 0.25f, 0}};
  for (const auto& p : coords) {
    for (float f : p) be_float(f);
    ply += '\x7f';
  }
  ply += '\x03';
  be_u32(0), be_u32(1), be_u32(2);
  be_u32(0), be_u32(1);
  const PolygonMesh pm = decode_mesh(ply, MeshFormat::Ply, "t.ply");
  ASSERT_EQ(pm.vertices.size(), 3u);
  EXPECT_EQ(pm.vertices[1], Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(pm.vertices[2], Eigen::Vector3d(0, 0.25, 0));
  EXPECT_EQ(pm.faces, (std::vector<std::vector<int>>{{0, 1, 2}}));
}

/// The IoError message for `data` read as `format` (empty if it does not throw).
std::string error_of(const std::string& data, MeshFormat format, const std::string& name) {
  try {
    decode_mesh(data, format, name);
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), name);
    return e.what();
  }
  return "";
}

TEST(MeshIo, MalformedFilesGiveThePathAndLine) {
  using ::testing::HasSubstr;
  EXPECT_THAT(error_of("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", MeshFormat::Off, "a.off"),
              HasSubstr("a.off: line 4: expected a finite number for y, got 'x'"));
  EXPECT_THAT(error_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", MeshFormat::Off, "b.off"),
              HasSubstr("b.off: line 6: vertex index 3 out of range (3 vertices)"));
  EXPECT_THAT(error_of("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::Off, "c.off"),
              HasSubstr("file ends after 1 of 2 faces"));
  EXPECT_THAT(error_of("PLY\n", MeshFormat::Off, "d.off"), HasSubstr("line 1: expected the header 'OFF'"));
  EXPECT_THAT(error_of("OFF\n1 0 0\nnan 0 0\n", MeshFormat::Off, "e.off"), HasSubstr("line 3: expected a finite number"));
  EXPECT_THAT(error_of("OFF\n1 0 0\n1e999 0 0\n", MeshFormat::Off, "f.off"), HasSubstr("out of the double range"));
  EXPECT_THAT(error_of("v 0 0 0\nv 1 0 0\nf 1 2 3\n", MeshFormat::Obj, "a.obj"),
              HasSubstr("a.obj: line 3: vertex index 3 out of range (2 vertices)"));
  EXPECT_THAT(error_of("v 0 0 0\nf 0 1 1\n", MeshFormat::Obj, "b.obj"), HasSubstr("line 2: vertex index 0"));
  EXPECT_THAT(error_of("v 0 0\n", MeshFormat::Obj, "c.obj"), HasSubstr("line 1: missing z"));
  EXPECT_THAT(error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
                       MeshFormat::Stl, "a.stl"),
              HasSubstr("a.stl: line 6: a facet needs at least 3 vertices, got 2"));
  EXPECT_THAT(error_of("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", MeshFormat::Stl, "b.stl"),
              HasSubstr("file ends inside a facet"));
  std::string truncated(84 + 50 * 2 - 7, '\0');
  truncated[80] = 2;
  EXPECT_THAT(error_of(truncated, MeshFormat::Stl, "c.stl"),
              HasSubstr("binary STL announces 2 triangles (184 bytes) but the file has 177 bytes"));
  EXPECT_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
                       MeshFormat::Ply, "a.ply"),
              HasSubstr("a.ply: line 6: element vertex has no property z"));
  EXPECT_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                       "end_header\n0 0 0\n1 1\n",
                       MeshFormat::Ply, "b.ply"),
              HasSubstr("b.ply: line 9: data ends where a value was expected"));
  EXPECT_THAT(error_of("ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty double x\n"
                       "property double y\nproperty double z\nend_header\n",
                       MeshFormat::Ply, "c.ply"),
              HasSubstr("data ends"));
}

TEST(MeshIo, ReadingMissingOrUnknownFilesNamesThePath) {
  const fs::path missing = test_dir() / "does_not_exist.off";
  try {
    read_mesh(missing);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), missing.string());
    EXPECT_THAT(e.what(), ::testing::HasSubstr("cannot open"));
  }
  EXPECT_THROW(read_mesh(test_dir() / "x.dae"), IoError);
  EXPECT_THROW(write_mesh(test_shapes::unit_cube(), test_dir() / "x.dae"), IoError);
}

TEST(MeshIo, InvalidMeshesAreNotWritten) {
  PolygonMesh m = test_shapes::unit_cube();
  m.faces[0][0] = 8;
  const fs::path path = test_dir() / "invalid.off";
  EXPECT_THROW(write_mesh(m, path), InvalidInput);
  m = test_shapes::unit_cube();
  m.vertices[0].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_mesh(m, path), InvalidInput);
  m = test_shapes::unit_cube();
  m.vertices[0].x() = 1e300;
  EXPECT_THROW(write_mesh(m, test_dir() / "huge.stl", {.binary = true}), InvalidInput);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace sculpt
