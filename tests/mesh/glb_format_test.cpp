// Binary glTF 2.0 (.glb): round trips of closed meshes, the container's bytes checked by hand,
// hand-built files (strides, offsets, index types, node transforms) read with known volumes, and
// malformed files refused with an IoError, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "mesh/formats/json_reader.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/triangulate.hpp"
#include "mesh_test_dir.hpp"
#include "shapes.hpp"
#include "support/cgal_mesh_check.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

namespace fs = std::filesystem;

std::uint32_t u32_at(const std::string& s, std::size_t pos) {
  std::uint32_t x = 0;
  for (int i = 3; i >= 0; --i) x = x << 8 | static_cast<unsigned char>(s[pos + i]);  // little endian, by hand
  return x;
}

void put_u32(std::string& out, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((x >> (8 * i)) & 0xFF);
}
void put_u16(std::string& out, std::uint16_t x) {
  out += static_cast<char>(x & 0xFF);
  out += static_cast<char>(x >> 8);
}
void put_float(std::string& out, float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, 4);
  put_u32(out, bits);
}

/// A GLB file made here (glTF 2.0 sec. 4.4): header, JSON chunk padded with spaces, BIN chunk
/// (if any) padded with zeros.
std::string glb_file(std::string json, std::string bin) {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const bool has_bin = !bin.empty();
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  std::string out;
  put_u32(out, 0x46546C67);
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + (has_bin ? 8 + bin.size() : 0)));
  put_u32(out, static_cast<std::uint32_t>(json.size()));
  put_u32(out, 0x4E4F534A);
  out += json;
  if (has_bin) {
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, 0x004E4942);
    out += bin;
  }
  return out;
}

/// The tetrahedron (0,0,0), (2,0,0), (0,3,0), (0,0,4): volume 2 * 3 * 4 / 6 = 4.
const float kTetraCorners[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
const int kTetraFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};  // outward
constexpr double kTetraVolume = 4;

PolygonMesh decode(const std::string& data) { return decode_mesh(data, MeshFormat::Glb, "t.glb"); }

/// The message of the IoError decoding `data` gives ("" if it decodes).
std::string decode_error(const std::string& data) {
  try {
    (void)decode(data);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(GlbFormat, ClosedSolidsComeBackClosedWithTheirFloat32Volume) {
  // glTF positions are float32: the mesh read back is the mesh rounded for float32 output
  // (round_for_output, which moves a vertex only where rounding alone would leave a defect),
  // triangulated, each coordinate a float32: the same vertices in the same order, closed, oriented
  // and clean for CGAL, its volume the original's within float32 precision and the rounding's moves.
  PolygonMesh sphere = test_shapes::uv_sphere(24);
  for (Eigen::Vector3d& v : sphere.vertices) v = v * 37.123456789 + Eigen::Vector3d(1.0 / 3, -250.000001, 1e-7);
  const PolygonMesh shapes[] = {test_shapes::box({-1, -2, -3}, {0.5, 0.25, 4}),
                                test_shapes::box({0.1, 1.0 / 3, -7}, {3.3, 2.2, 1e-3}), test_shapes::uv_sphere(32, 1.7),
                                sphere, test_shapes::torus(16, 8)};
  for (const PolygonMesh& m : shapes) {
    const fs::path path = test_dir() / "solid.glb";
    write_mesh(m, path);
    const PolygonMesh r = read_mesh(path);
    OutputRoundingReport report;
    PolygonMesh expected =
        triangulate(round_for_output(m, {.precision = OutputPrecision::Float32, .triangles = true}, &report));
    for (Eigen::Vector3d& v : expected.vertices) v = v.cast<float>().cast<double>();
    ASSERT_EQ(r.vertices.size(), expected.vertices.size());
    for (std::size_t i = 0; i < r.vertices.size(); ++i)
      EXPECT_EQ(r.vertices[i], expected.vertices[i]) << "vertex " << i;
    EXPECT_EQ(r.faces, expected.faces);
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(r));
    EXPECT_TRUE(checks::NoDuplicateVertices(r));
    EXPECT_TRUE(checks::CleanForOtherTools(r.vertices, r.faces));
    // No coordinate moved more than 2^-24 of the largest one beyond what the rounding moved.
    const Eigen::AlignedBox3d box = mesh_bounding_box(m);
    const double largest = box.max().cwiseAbs().cwiseMax(box.min().cwiseAbs()).maxCoeff();
    EXPECT_LE(std::abs(mesh_volume(r) - mesh_volume(m)),
              mesh_surface_area(m) * (largest * 0x1p-24 * 2 + report.max_move));
  }
}

TEST(GlbFormat, TheContainerIsLaidOutAsTheSpecSays) {
  // Header, chunk lengths, alignment and padding, read byte by byte here (sec. 4.4), and the data:
  // float32 positions then uint32 indices, min and max the positions' bounds.
  PolygonMesh m;
  for (const auto& c : kTetraCorners) m.vertices.emplace_back(c[0], c[1], c[2]);
  for (const auto& f : kTetraFaces) m.faces.push_back({f[0], f[1], f[2]});
  const std::string g = encode_mesh(m, MeshFormat::Glb);
  ASSERT_GE(g.size(), 28u);
  EXPECT_EQ(g.substr(0, 4), "glTF");
  EXPECT_EQ(u32_at(g, 4), 2u);
  EXPECT_EQ(u32_at(g, 8), g.size());
  const std::uint32_t json_length = u32_at(g, 12);
  EXPECT_EQ(json_length % 4, 0u);
  EXPECT_EQ(g.substr(16, 4), "JSON");
  ASSERT_LE(20 + json_length + 8, g.size());
  const std::string json = g.substr(20, json_length);
  const std::size_t last = json.find_last_not_of(' ');
  EXPECT_EQ(json[last], '}');
  EXPECT_LT(json_length - last - 1, 4u);  // padded with at most three spaces
  EXPECT_EQ(json.find('\0'), std::string::npos);
  EXPECT_NE(json.find(R"("version":"2.0")"), std::string::npos);
  EXPECT_NE(json.find(R"("min":[0,0,0],"max":[2,3,4])"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("mode":4)"), std::string::npos);
  EXPECT_NE(json.find(R"("componentType":5125)"), std::string::npos);  // UNSIGNED_INT indices
  const std::size_t bin_at = 20 + json_length;
  EXPECT_EQ(bin_at % 4, 0u);
  const std::uint32_t bin_length = u32_at(g, bin_at);
  EXPECT_EQ(std::string(g, bin_at + 4, 4), std::string("BIN\0", 4));
  EXPECT_EQ(bin_at + 8 + bin_length, g.size());
  ASSERT_EQ(bin_length, 4u * 12 + 4u * 12);  // 4 positions of 12 bytes, 12 indices of 4 bytes
  std::string expected;
  for (const auto& c : kTetraCorners)
    for (float x : c) put_float(expected, x);
  for (const auto& f : kTetraFaces)
    for (int i : f) put_u32(expected, static_cast<std::uint32_t>(i));
  EXPECT_EQ(g.substr(bin_at + 8), expected);
}

/// Every triangle of `decoded` (a GLB read back) has the float32 corners of triangle t of
/// `triangles` (indices into `vertices`), in order.
void expect_same_triangles(const PolygonMesh& decoded, const std::vector<Eigen::Vector3d>& vertices,
                           const std::vector<std::vector<int>>& triangles) {
  ASSERT_EQ(decoded.faces.size(), triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = vertices[std::size_t(triangles[t][std::size_t(k)])];
      const Eigen::Vector3d as_float(double(float(v.x())), double(float(v.y())), double(float(v.z())));
      ASSERT_EQ(decoded.vertices[std::size_t(decoded.faces[t][std::size_t(k)])], as_float)
          << "triangle " << t << " corner " << k;
    }
}

TEST(GlbFormat, ForDisplayEveryVertexIsKeptInOrderAsItsFloat32) {
  // Two vertices 1e-12 apart (one float32 point) and a sliver: output rounding for a file merges
  // or moves them; the display GLB keeps every vertex, in order, converted to float32 alone.
  PolygonMesh m = test_shapes::uv_sphere(12, 1.3);
  m.vertices[5] += Eigen::Vector3d(1e-12, 0, 0);
  m.vertices.push_back(m.vertices[5] + Eigen::Vector3d(1e-12, 1e-12, 0));  // unused: still sent
  const std::string g = encode_glb_for_display(m);
  const std::size_t bin = 20 + u32_at(g, 12);  // the BIN chunk: positions, then indices
  const PolygonMesh triangles = triangulate(m);
  // Fewer than 65,536 vertices: the indices are 16-bit (padded to 4 bytes).
  ASSERT_EQ(u32_at(g, bin), 12 * m.vertices.size() + (6 * triangles.faces.size() + 3) / 4 * 4);
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    float xyz[3];
    std::memcpy(xyz, g.data() + bin + 8 + 12 * i, 12);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(xyz[k], static_cast<float>(m.vertices[i][k])) << "vertex " << i;
  }
  for (std::size_t t = 0; t < triangles.faces.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::size_t at = bin + 8 + 12 * m.vertices.size() + 6 * t + 2 * std::size_t(k);
      EXPECT_EQ(std::uint32_t(static_cast<unsigned char>(g[at])) | std::uint32_t(static_cast<unsigned char>(g[at + 1]))
                                                                       << 8,
                std::uint32_t(triangles.faces[t][std::size_t(k)]));
    }
  // A reader gets the same triangles (equal positions merged, as for every GLB).
  EXPECT_EQ(decode_mesh(g, MeshFormat::Glb, "display").faces.size(), triangles.faces.size());
  EXPECT_THROW((void)encode_glb_for_display(PolygonMesh{{Eigen::Vector3d(1e300, 0, 0)}, {}}), InvalidInput);
  PolygonMesh bad = test_shapes::unit_cube();
  bad.faces[0][0] = 99;
  EXPECT_THROW((void)encode_glb_for_display(bad), InvalidInput);
}

/// A rows x columns grid of vertices (numbered row by row, z from a hash so no two coincide), two
/// triangles a cell, in row order.
PolygonMesh grid_sheet(int rows, int columns) {
  PolygonMesh m;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) m.vertices.emplace_back(c, r, double((r * 7919 + c * 104729) % 1000) / 1000);
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < columns; ++c) {
      const int a = r * columns + c, b = a + 1, d = a + columns, e = d + 1;
      m.faces.push_back({a, b, e});
      m.faces.push_back({a, e, d});
    }
  return m;
}

TEST(GlbFormat, ForDisplayLargeMeshesTakeSixteenBitIndicesWhereTheNumberingAllows) {
  // 90,000 vertices: no 16-bit index reaches all of them, but each triangle's corners lie within
  // one row of each other, so runs of 16-bit indices over windows of vertices cover the mesh.
  PolygonMesh m = grid_sheet(300, 300);
  const std::size_t triangles = m.faces.size();
  {
    const std::string g = encode_glb_for_display(m);
    const std::size_t bin = 20 + u32_at(g, 12);
    const std::size_t index_bytes = u32_at(g, bin) - 12 * m.vertices.size();
    EXPECT_GE(index_bytes, 6 * triangles);
    EXPECT_LE(index_bytes, 6 * triangles + 4 * 8) << "a few runs, each padded to 4 bytes";
    expect_same_triangles(decode_mesh(g, MeshFormat::Glb, "display"), m.vertices, m.faces);
  }
  // A triangle spanning the whole mesh in the middle: a run of 32-bit indices between two of
  // 16-bit ones, the triangles still in order.
  m.faces.insert(m.faces.begin() + std::ptrdiff_t(triangles / 2), {0, 89999, 1});
  {
    const std::string g = encode_glb_for_display(m);
    const std::size_t bin = 20 + u32_at(g, 12);
    const std::size_t index_bytes = u32_at(g, bin) - 12 * m.vertices.size();
    EXPECT_GE(index_bytes, 6 * triangles + 12);
    EXPECT_LE(index_bytes, 6 * triangles + 12 + 4 * 8);
    expect_same_triangles(decode_mesh(g, MeshFormat::Glb, "display"), m.vertices, m.faces);
  }
  // Numbered at random, the triangles have no locality: one run of 32-bit indices.
  std::vector<int> order(m.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  PolygonMesh shuffled;
  shuffled.vertices.resize(m.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) shuffled.vertices[std::size_t(order[i])] = m.vertices[i];
  for (const auto& f : m.faces)
    shuffled.faces.push_back({order[std::size_t(f[0])], order[std::size_t(f[1])], order[std::size_t(f[2])]});
  {
    const std::string g = encode_glb_for_display(shuffled);
    const std::size_t bin = 20 + u32_at(g, 12);
    EXPECT_EQ(u32_at(g, bin), 12 * m.vertices.size() + 12 * shuffled.faces.size());
    expect_same_triangles(decode_mesh(g, MeshFormat::Glb, "display"), shuffled.vertices, shuffled.faces);
  }
}

TEST(GlbFormat, AnEmptyMeshIsAnEmptyScene) {
  const std::string g = encode_mesh(PolygonMesh{}, MeshFormat::Glb);
  EXPECT_EQ(u32_at(g, 8), g.size());
  EXPECT_EQ(g.size(), 20u + u32_at(g, 12));  // no BIN chunk
  const PolygonMesh r = decode(g);
  EXPECT_TRUE(r.vertices.empty());
  EXPECT_TRUE(r.faces.empty());
}

TEST(GlbFormat, BeyondFloat32IsRefused) {
  PolygonMesh far = test_shapes::unit_cube();
  far.vertices[0].x() = 1e300;
  EXPECT_THROW((void)encode_mesh(far, MeshFormat::Glb), InvalidInput);
}

/// Non-indexed: 12 corners, 16 bytes apart (the last 4 of each are NaN bytes the reader must not
/// take), after 8 bytes of another view, placed by a translation split over a parent and a child.
TEST(GlbFormat, ReadsANonIndexedTetrahedronWithAByteStrideAndNodeTranslations) {
  std::string bin(8, '\x7f');
  for (const auto& f : kTetraFaces)
    for (int i : f) {
      for (float x : kTetraCorners[i]) put_float(bin, x);
      bin += std::string(4, '\xff');
    }
  const std::string json =
      R"({"asset":{"version":"2.0","generator":"hand"},"scene":0,"scenes":[{"nodes":[0]}],)"
      R"("nodes":[{"translation":[10,0,0],"children":[1]},{"translation":[0,20,30],"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
      R"("buffers":[{"byteLength":200}],"bufferViews":[{"buffer":0,"byteOffset":8,"byteLength":188,"byteStride":16}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":12,"type":"VEC3"}]})";
  const PolygonMesh r = decode(glb_file(json, bin));
  EXPECT_EQ(r.vertices.size(), 4u);  // the split corners merged
  EXPECT_EQ(r.faces.size(), 4u);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(r));
  EXPECT_TRUE(checks::VolumeNear(r, kTetraVolume, 1e-15));
  EXPECT_EQ(r.vertices[0], Eigen::Vector3d(10, 20, 30));
  const auto box = mesh_bounding_box(r);
  EXPECT_EQ(box.min(), Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(box.max(), Eigen::Vector3d(12, 23, 34));
}

/// The same tetrahedron indexed with each index type, placed by `node` (a JSON object).
std::string indexed_tetrahedron(int component_type, const std::string& node) {
  std::string bin;
  for (const auto& c : kTetraCorners)
    for (float x : c) put_float(bin, x);
  const std::size_t index_at = bin.size();
  for (const auto& f : kTetraFaces)
    for (int i : f) {
      if (component_type == 5121) bin += static_cast<char>(i);
      if (component_type == 5123) put_u16(bin, static_cast<std::uint16_t>(i));
      if (component_type == 5125) put_u32(bin, static_cast<std::uint32_t>(i));
    }
  const std::size_t size = bin.size();
  return glb_file(R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[)" + node +
                      R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":4}]}],)"
                      R"("buffers":[{"byteLength":)" +
                      std::to_string(size) +
                      R"(}],"bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":)" +
                      std::to_string(index_at) + R"(,"byteLength":)" + std::to_string(size - index_at) +
                      R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},)"
                      R"({"bufferView":1,"componentType":)" +
                      std::to_string(component_type) + R"(,"count":12,"type":"SCALAR"}]})",
                  bin);
}

TEST(GlbFormat, ReadsAnIndexedTetrahedronWithEveryIndexType) {
  for (const int type : {5121, 5123, 5125}) {
    SCOPED_TRACE(type);
    const PolygonMesh r = decode(indexed_tetrahedron(type, R"({"mesh":0})"));
    EXPECT_EQ(r.vertices.size(), 4u);
    EXPECT_EQ(r.faces.size(), 4u);
    EXPECT_TRUE(checks::VolumeNear(r, kTetraVolume, 1e-15));
  }
}

TEST(GlbFormat, AppliesMatricesAndRotationScaleTranslationAndTurnsMirroredTrianglesBack) {
  struct Placed {
    const char* node;
    double volume;
    Eigen::Vector3d corner;  ///< where (2, 0, 0) goes
  };
  const Placed cases[] = {
      // Column-major: translation in elements 12..14.
      {R"({"mesh":0,"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1]})", kTetraVolume, {7, 6, 7}},
      // 90 degrees about z (x -> y), scale 2 first, then translate: T * R * S.
      {R"({"mesh":0,"scale":[2,2,2],"rotation":[0,0,0.70710678118654752,0.70710678118654752],"translation":[1,0,0]})",
       8 * kTetraVolume,
       {1, 4, 0}},
      // A mirror: the winding is reversed by the reader, so the volume stays positive.
      {R"({"mesh":0,"scale":[-1,1,1]})", kTetraVolume, {-2, 0, 0}},
      {R"({"mesh":0,"matrix":[1,0,0,0, 0,-3,0,0, 0,0,1,0, 0,0,0,1]})", 3 * kTetraVolume, {2, 0, 0}},
  };
  for (const Placed& c : cases) {
    SCOPED_TRACE(c.node);
    const PolygonMesh r = decode(indexed_tetrahedron(5123, c.node));
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(r));
    EXPECT_TRUE(checks::VolumeNear(r, c.volume, 1e-12));
    ASSERT_EQ(r.vertices.size(), 4u);
    EXPECT_LT((r.vertices[1] - c.corner).norm(), 1e-12) << r.vertices[1].transpose();
  }
}

TEST(GlbFormat, MeshesInstancedTwiceAndScenesWithoutTheSceneProperty) {
  // Two nodes place one mesh: two tetrahedra. Without scenes, the root nodes are taken.
  const std::string two =
      indexed_tetrahedron(5125, R"({"children":[1,2]},{"mesh":0},{"mesh":0,"translation":[100,0,0]})");
  const PolygonMesh r = decode(two);
  EXPECT_EQ(r.vertices.size(), 8u);
  EXPECT_TRUE(checks::VolumeNear(r, 2 * kTetraVolume, 1e-15));
  std::string json = R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0,"translation":[0,0,1]}],)"
                     R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"byteLength":144}],)"
                     R"("bufferViews":[{"buffer":0,"byteLength":144}],)"
                     R"("accessors":[{"bufferView":0,"componentType":5126,"count":12,"type":"VEC3"}]})";
  std::string bin;
  for (const auto& f : kTetraFaces)
    for (int i : f)
      for (float x : kTetraCorners[i]) put_float(bin, x);
  const PolygonMesh s = decode(glb_file(json, bin));
  EXPECT_TRUE(checks::VolumeNear(s, kTetraVolume, 1e-15));
  EXPECT_EQ(mesh_bounding_box(s).min().z(), 1.0);
}

TEST(GlbFormat, MalformedFilesNameWhatIsWrong) {
  const std::string good = indexed_tetrahedron(5123, R"({"mesh":0})");
  ASSERT_EQ(decode_error(good), "");
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string json = good.substr(20, u32_at(good, 12));
    const std::size_t at = json.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    json.replace(at, from.size(), to);
    const std::size_t bin_at = 20 + u32_at(good, 12);
    return glb_file(json, good.substr(bin_at + 8));
  };
  using testing::HasSubstr;
  EXPECT_THAT(decode_error("glTF"), HasSubstr("shorter than its 12-byte header"));
  EXPECT_THAT(decode_error(std::string("PK\3\4") + std::string(20, '\0')), HasSubstr("does not start with 'glTF'"));
  EXPECT_THAT(decode_error(good.substr(0, good.size() - 4)), HasSubstr("header gives a length of"));
  EXPECT_THAT(decode_error(edited(R"("version":"2.0")", R"("version":"1.0")")), HasSubstr("glTF version 1.0"));
  EXPECT_THAT(decode_error(edited(R"({"asset")", R"({"extensionsRequired":["KHR_draco_mesh_compression"],"asset")")),
              HasSubstr("KHR_draco_mesh_compression"));
  EXPECT_THAT(decode_error(edited(R"("count":12)", R"("count":13)")), HasSubstr("accessors[1] reads 13 elements"));
  EXPECT_THAT(decode_error(edited(R"("count":12)", R"("count":4294967295)")), HasSubstr("triangles in all"));
  // Counted before anything is read or built: 2^25 triangles and one more, in a file of 200 bytes.
  EXPECT_THAT(decode_error(edited(R"("count":12)", R"("count":100663299)")),
              HasSubstr("the nodes place more than 33554432 triangles in all"));
  EXPECT_THAT(decode_error(edited(R"("count":12)", R"("count":1e300)")), HasSubstr("accessors[1].count must be"));
  EXPECT_THAT(decode_error(edited(R"("count":12)", R"("count":-1)")), HasSubstr("non-negative integer"));
  EXPECT_THAT(decode_error(edited(R"("count":12)", R"("count":10)")), HasSubstr("not a multiple of 3"));
  EXPECT_THAT(decode_error(edited(R"("count":4)", R"("count":2)")), HasSubstr("beyond the 2 positions"));
  EXPECT_THAT(decode_error(edited(R"("byteLength":48})", R"("byteLength":48,"byteOffset":9007199254740992})")),
              HasSubstr("lies beyond"));
  EXPECT_THAT(decode_error(edited(R"("byteLength":48})", R"("byteLength":48,"byteStride":8})")),
              HasSubstr("byteStride 8 does not fit"));
  EXPECT_THAT(decode_error(edited(R"("buffers":[{)", R"("buffers":[{"uri":"data.bin",)")),
              HasSubstr("outside the file"));
  EXPECT_THAT(decode_error(edited(R"("componentType":5126)", R"("componentType":5120)")),
              HasSubstr("componentType 5120"));
  EXPECT_THAT(decode_error(edited(R"("type":"VEC3")", R"("type":"VEC2")")), HasSubstr("must be of type VEC3"));
  EXPECT_THAT(decode_error(edited(R"("mode":4)", R"("mode":5)")), HasSubstr("only TRIANGLES"));
  EXPECT_THAT(decode_error(edited(R"("indices":1)", R"("indices":7)")),
              HasSubstr("accessors[7], which does not exist"));
  EXPECT_THAT(decode_error(edited(R"("nodes":[{"mesh":0}])", R"("nodes":[{"mesh":0,"children":[0]}])")),
              HasSubstr("nodes[0] is reached twice"));
  EXPECT_THAT(decode_error(edited(R"({"mesh":0})", R"({"mesh":0,"matrix":[1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1]})")),
              HasSubstr("not affine"));
  EXPECT_THAT(decode_error(edited(R"({"mesh":0})", R"({"mesh":0,"scale":[1e308,1e308,1e308]})")),
              HasSubstr("not finite"));
  EXPECT_THAT(decode_error(edited(R"("asset")", R"("asset" "x")")), HasSubstr("JSON byte"));
  EXPECT_THAT(decode_error(edited(R"("buffers":[{"byteLength":)", R"("buffers":[{"byteLength":1)")),
              HasSubstr("bytes but the BIN chunk has 72"));
}

TEST(GlbFormat, EveryPrefixAndRandomByteChangesGiveAnIoErrorOrAValidMeshNeverACrash) {
  const std::string files[] = {encode_mesh(test_shapes::uv_sphere(8), MeshFormat::Glb),
                               indexed_tetrahedron(5121, R"({"mesh":0,"translation":[1,2,3]})")};
  std::mt19937 rng(7);
  for (const std::string& good : files) {
    auto graceful = [&](const std::string& data, const std::string& what) {
      try {
        const PolygonMesh m = decode(data);
        EXPECT_TRUE(checks::IndicesValid(m)) << what;
        for (const auto& p : m.vertices) EXPECT_TRUE(p.allFinite()) << what;
      } catch (const IoError& e) {
        EXPECT_EQ(e.path(), "t.glb") << what;
      } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": unexpected " << e.what();
      }
    };
    int errors = 0;
    for (std::size_t n = 0; n < good.size(); ++n) {
      errors += decode_error(good.substr(0, n)) != "";
      graceful(good.substr(0, n), "prefix of " + std::to_string(n) + " bytes");
    }
    EXPECT_EQ(errors, static_cast<int>(good.size()));  // the header's length makes every prefix wrong
    std::uniform_int_distribution<std::size_t> pos(0, good.size() - 1);
    const std::string noise = "0123456789-.e,:[]{}\" \xff\x80";
    for (int trial = 0; trial < 2000; ++trial) {
      std::string bad = good;
      for (int k = 0; k < 1 + trial % 3; ++k)
        bad[pos(rng)] = trial % 2 ? noise[rng() % noise.size()] : static_cast<char>(rng());
      graceful(bad, "trial " + std::to_string(trial));
    }
  }
}

TEST(JsonReader, DeepNestingNeitherRecursesNorCrashes) {
  const std::size_t depth = 100'000;
  const std::string deep = std::string(depth, '[') + std::string(depth, ']');
  const mesh::detail::JsonDocument doc(deep, "deep.json");
  EXPECT_EQ(doc.root().kind, mesh::detail::JsonKind::Array);
  EXPECT_THROW(mesh::detail::JsonDocument(std::string(depth, '['), "open.json"), IoError);
}

TEST(JsonReader, StringsNumbersAndStrictness) {
  const mesh::detail::JsonDocument doc(
      R"( {"a": "x\"\\\/\n\u00e9\ud83d\ude00", "b": -1.5e2, "c": [true, false, null], "a": 0} )", "t.json");
  const auto* a = doc.member(doc.root(), "a");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->text, "x\"\\/\n\xc3\xa9\xf0\x9f\x98\x80");
  EXPECT_EQ(doc.member(doc.root(), "b")->number, -150.0);
  EXPECT_EQ(doc.member(doc.root(), "c")->children.size(), 3u);
  for (const char* bad : {"", "{", "[1,]", "{\"a\":1,}", "01", ".5", "1.", "-", "tru", "\"a\nb\"", "[1] 2", "1e999",
                          "{\"a\" 1}", "{1:2}", "\"\\x\"", "\"\\u12\"", "[\"a\"", "nul"})
    EXPECT_THROW(mesh::detail::JsonDocument(bad, "bad.json"), IoError) << bad;
}

}  // namespace
}  // namespace sculpt
