// The scene and status messages (lib/view/scene_message.hpp): layout, measures, the GLB inside
// decoded by the mesh layer's own reader, feature edges as index pairs, JSON escaping.
#include "view/scene_message.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "language/interpreter.hpp"
#include "language/solid_values.hpp"
#include "language/source.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"

namespace sculpt::view {
namespace {

std::uint32_t u32_at(const std::string& s, std::size_t at) {
  std::uint32_t x;
  std::memcpy(&x, s.data() + at, 4);
  return x;
}

/// The number after `"key":[` (first element) or `"key":` in `json`, from position `from`.
double number_after(const std::string& json, const std::string& key, std::size_t from = 0) {
  std::size_t at = json.find("\"" + key + "\":", from);
  EXPECT_NE(at, std::string::npos) << key;
  at += key.size() + 3;
  if (json[at] == '[') ++at;
  return std::stod(json.substr(at));
}

TEST(SceneMessage, HoldsEachPartAsGlbWithEdgesAndMeasures) {
  const language::Value cube = language::solid_value(box({0, 0, 0}, {1, 2, 3}));
  const Scene scene = scene_of({{"cube", std::array<double, 3>{1, 0, 0}, cube}}, std::nullopt);
  ASSERT_EQ(scene.parts.size(), 1u);
  EXPECT_DOUBLE_EQ(*scene.parts[0].volume, 6.0);
  EXPECT_DOUBLE_EQ(scene.parts[0].area, 22.0);

  const std::string message = encode_scene(scene);
  ASSERT_GE(message.size(), 8u);
  EXPECT_EQ(message.substr(0, 4), "SCLV");
  const std::uint32_t json_size = u32_at(message, 4);
  EXPECT_EQ(json_size % 4, 0u);
  const std::string json = message.substr(8, json_size);
  EXPECT_NE(json.find("\"name\":\"cube\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"solid\":true"), std::string::npos);
  EXPECT_NE(json.find("\"box\":[[0,0,0],[1,2,3]]"), std::string::npos) << json;
  EXPECT_DOUBLE_EQ(number_after(json, "volume"), 6.0);
  EXPECT_EQ(number_after(json, "triangles"), 12);
  const std::size_t data = 8 + json_size;
  const auto glb_offset = static_cast<std::size_t>(number_after(json, "glb"));
  const std::size_t glb_size = std::stoul(json.substr(json.find(',', json.find("\"glb\":")) + 1));
  EXPECT_EQ(glb_offset % 4, 0u);
  const PolygonMesh back =
      decode_mesh(std::string_view(message).substr(data + glb_offset, glb_size), MeshFormat::Glb, "scene");
  EXPECT_DOUBLE_EQ(mesh_volume(back), 6.0);
  EXPECT_EQ(back.faces.size(), 12u);  // triangles
  const auto edges_offset = static_cast<std::size_t>(number_after(json, "edges"));
  const std::size_t edges_count = std::stoul(json.substr(json.find(',', json.find("\"edges\":")) + 1));
  EXPECT_EQ(edges_count, 12u);  // each as two indices into the GLB's positions
  EXPECT_EQ(edges_offset % 4, 0u);
  EXPECT_EQ(json.find("\"loose\""), std::string::npos) << "every edge indexes the positions";
  EXPECT_NE(json.find("\"edges\":[" + std::to_string(edges_offset) + ",12,12]"), std::string::npos) << "all creases";
  EXPECT_NE(json.find("\"depth\":null"), std::string::npos) << "no depths unless asked for";
  EXPECT_EQ(data + edges_offset + edges_count * 8, message.size());
  // Every edge joins two corners of the box along one axis.
  const char* positions = message.data() + data + glb_offset + 28 + u32_at(message, data + glb_offset + 12);
  for (std::size_t e = 0; e < edges_count; ++e) {
    float ends[2][3];
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t v = u32_at(message, data + edges_offset + 8 * e + 4 * k);
      ASSERT_LT(v, 8u);
      std::memcpy(ends[k], positions + 12 * v, 12);
    }
    int differing = 0;
    for (int k = 0; k < 3; ++k) differing += ends[0][k] != ends[1][k];
    EXPECT_EQ(differing, 1) << "edge " << e;
  }
}

/// The offset and count of `"key":[offset,count,...]` in the JSON of `message`, and the JSON's end.
struct Block {
  std::size_t offset = 0, count = 0, third = 0;
};
Block block_of(const std::string& message, const std::string& key) {
  const std::string json = message.substr(8, u32_at(message, 4));
  std::size_t at = json.find("\"" + key + "\":[");
  EXPECT_NE(at, std::string::npos) << key << " in " << json;
  Block b;
  char* end = nullptr;
  const char* first = json.c_str() + at + key.size() + 4;
  b.offset = std::strtoul(first, &end, 10);
  b.count = std::strtoul(end + 1, &end, 10);
  if (*end == ',') b.third = std::strtoul(end + 1, &end, 10);
  b.offset += 8 + json.size();  // from the start of the message
  return b;
}

TEST(SceneMessage, CreasesComeFirstAndCurvedSurfacesHaveNone) {
  // A 32-segment cylinder: the two rims are creases (90 degrees), the 32 edges between side facets
  // (11.25 degrees) are features but no creases.
  const Scene can = scene_of({{"can", std::nullopt, language::solid_value(cylinder(1, 2))}}, std::nullopt);
  const Block edges = block_of(encode_scene(can), "edges");
  EXPECT_EQ(edges.count, 96u);
  EXPECT_EQ(edges.third, 64u);
  // A ball: every facet is its own plane, nothing is a crease.
  const Scene ball = scene_of({{"ball", std::nullopt, language::solid_value(sphere(1))}}, std::nullopt);
  const std::string message = encode_scene(ball);
  // 16 rings of 32 edges, 15 bands between them and a fan at each pole with 32 edges each: all
  // features.
  EXPECT_EQ(block_of(message, "edges").count, 16u * 32 + 17 * 32);
  EXPECT_EQ(block_of(message, "edges").third, 0u);
}

TEST(SceneMessage, AFinelyFacetedPartSendsItsCreasesOnly) {
  // A sphere of n segments has n^2 + n feature edges and no crease (see above): 194,040 at 440
  // segments, all sent; 211,600 at 460, more than kDenseFeatureEdges, so none is sent and
  // "features" still counts them. A box beside it keeps its 12 edges (all creases).
  for (const int n : {440, 460}) {
    const Scene scene = scene_of({{"ball", std::nullopt, language::solid_value(sphere(1, {.segments = n}))},
                                  {"box", std::nullopt, language::solid_value(box({2, 0, 0}, {3, 1, 1}))}},
                                 std::nullopt);
    const std::string message = encode_scene(scene);
    const std::size_t features = std::size_t(n) * std::size_t(n) + std::size_t(n);
    const std::size_t ball_json = message.find("\"name\":\"ball\""), box_json = message.find("\"name\":\"box\"");
    ASSERT_NE(ball_json, std::string::npos);
    ASSERT_NE(box_json, std::string::npos);
    EXPECT_EQ(std::size_t(number_after(message, "features", ball_json)), features);
    const std::size_t sent = n == 440 ? features : 0;
    EXPECT_NE(message.find(",\"edges\":[", ball_json), std::string::npos);
    const std::size_t edges_at = message.find("\"edges\":[", ball_json) + 9;
    EXPECT_EQ(std::strtoul(message.c_str() + message.find(',', edges_at) + 1, nullptr, 10), sent) << n;
    EXPECT_EQ(std::size_t(number_after(message, "features", box_json)), 12u);
    const std::size_t box_edges = message.find("\"edges\":[", box_json) + 9;
    EXPECT_EQ(std::strtoul(message.c_str() + message.find(',', box_edges) + 1, nullptr, 10), 12u);
  }
}

TEST(SceneMessage, DepthsOnlyWhenAskedOneAPerTriangle) {
  const Scene scene =
      scene_of({{"cube", std::nullopt, language::solid_value(box({0, 0, 0}, {1, 2, 3}))}}, std::nullopt);
  const std::string message = encode_scene(scene, {.depth = true});
  const Block depth = block_of(message, "depth");
  ASSERT_EQ(depth.count, 12u);  // one a triangle
  EXPECT_EQ(depth.offset % 4, 0u);
  EXPECT_EQ(depth.offset + 24, message.size());  // 12 uint16, a multiple of 4 bytes
  for (std::size_t k = 0; k < depth.count; ++k) {
    std::uint16_t d;
    std::memcpy(&d, message.data() + depth.offset + 2 * k, 2);
    EXPECT_EQ(d, 6) << "the box's one in-cell is at depth 6";
  }
  // A mesh part has no tree: no depths.
  PolygonMesh square;
  square.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.faces = {{0, 1, 2, 3}};
  const language::Value mesh(std::shared_ptr<const language::Object>(std::make_shared<language::MeshValue>(square)));
  EXPECT_NE(
      encode_scene(scene_of({{"sheet", std::nullopt, mesh}}, std::nullopt), {.depth = true}).find("\"depth\":null"),
      std::string::npos);
}

/// Volume, area and bounding box of the sphere primitive's polyhedron (bsp/primitives.hpp, like
/// OpenSCAD's rings): `rings` = (n + 1) / 2 rings of n vertices at polar angles pi (i + 1/2) / rings,
/// azimuths 2 pi k / n, and a vertex at each pole. Consecutive rings bound frusta of regular n-gon
/// pyramids, the outer rings and the poles two pyramids.
struct SphereMeasures {
  double volume = 0, area = 0, half_width = 0, half_height = 0;
};
SphereMeasures sphere_polyhedron(double r, int n) {
  const int rings = (n + 1) / 2;
  const double pi = std::acos(-1.0);
  const auto radius = [&](int i) { return r * std::sin(pi * (i + 0.5) / rings); };
  const auto height = [&](int i) { return r * std::cos(pi * (i + 0.5) / rings); };
  const auto polygon_area = [&](double rho) { return 0.5 * n * rho * rho * std::sin(2 * pi / n); };
  SphereMeasures m;
  // The pyramids at the poles (the outer rings are congruent).
  const double cap = r - height(0), apothem = radius(0) * std::cos(pi / n), side = 2 * radius(0) * std::sin(pi / n);
  m.volume = 2 * cap / 3 * polygon_area(radius(0));
  m.area = 2 * n * side / 2 * std::hypot(cap, apothem);
  for (int i = 0; i + 1 < rings; ++i) {
    const double h = height(i) - height(i + 1), a1 = polygon_area(radius(i)), a2 = polygon_area(radius(i + 1));
    m.volume += h / 3 * (a1 + a2 + std::sqrt(a1 * a2));
    const double apothems = (radius(i) - radius(i + 1)) * std::cos(pi / n);
    const double sides = 2 * (radius(i) + radius(i + 1)) * std::sin(pi / n);
    m.area += n * sides / 2 * std::hypot(h, apothems);
  }
  for (int i = 0; i < rings; ++i) m.half_width = std::max(m.half_width, radius(i));
  m.half_height = r;
  return m;
}

TEST(SceneMessage, MeasuresOfABoxAndASphereAreTheAnalyticOnes) {
  const Scene box_scene =
      scene_of({{"b", std::nullopt, language::solid_value(box({-1, 0, 2}, {3, 0.5, 2.25}))}}, std::nullopt);
  EXPECT_DOUBLE_EQ(*box_scene.parts[0].volume, 4 * 0.5 * 0.25);
  EXPECT_DOUBLE_EQ(box_scene.parts[0].area, 2 * (4 * 0.5 + 4 * 0.25 + 0.5 * 0.25));
  EXPECT_EQ(box_scene.parts[0].box.min(), Eigen::Vector3d(-1, 0, 2));
  EXPECT_EQ(box_scene.parts[0].box.max(), Eigen::Vector3d(3, 0.5, 2.25));
  const std::string box_message = encode_scene(box_scene);
  EXPECT_NE(box_message.find("\"volume\":0.5,\"area\":6.25,\"box\":[[-1,0,2],[3,0.5,2.25]]"), std::string::npos);

  for (const int n : {12, 32, 64}) {
    const double r = 2;
    const Scene scene =
        scene_of({{"s", std::nullopt, language::solid_value(sphere(r, {.segments = n}))}}, std::nullopt);
    const ViewPart& part = scene.parts[0];
    const SphereMeasures exact = sphere_polyhedron(r, n);
    // The vertices are on the sphere within the rounding of the planes' integer normals.
    EXPECT_NEAR(*part.volume, exact.volume, 1e-5 * exact.volume) << n << " segments";
    EXPECT_NEAR(part.area, exact.area, 1e-5 * exact.area) << n << " segments";
    // The poles are at grid heights (r = 2 is one): within half a grid step (2^-16) in z.
    for (int a = 0; a < 3; ++a) {
      const double half = a == 2 ? exact.half_height : exact.half_width, tolerance = a == 2 ? 0x1p-16 : 1e-5;
      EXPECT_NEAR(part.box.min()[a], -half, tolerance) << n << " segments, axis " << a;
      EXPECT_NEAR(part.box.max()[a], half, tolerance) << n << " segments, axis " << a;
    }
    // And the round sphere's, as the segments grow.
    const double pi = std::acos(-1.0), error = 2 * (1 - std::cos(pi / n));
    EXPECT_NEAR(*part.volume, 4 * pi * r * r * r / 3, 2 * error * 4 * pi * r * r * r / 3) << n;
    EXPECT_NEAR(part.area, 4 * pi * r * r, 2 * error * 4 * pi * r * r) << n;
    // The message carries the same numbers.
    const std::string message = encode_scene(scene);
    EXPECT_DOUBLE_EQ(number_after(message.substr(8, u32_at(message, 4)), "volume"), *part.volume);
  }
}

TEST(SceneMessage, LastSolidWhenNothingShownAndPaletteColours) {
  const language::Value cube = language::solid_value(box({0, 0, 0}, {1, 1, 1}));
  const Scene last = scene_of({}, cube);
  ASSERT_EQ(last.parts.size(), 1u);
  EXPECT_EQ(last.parts[0].name, "last solid");
  EXPECT_EQ(last.parts[0].color, palette_color(0));
  // Something shown: the last solid is not added.
  const Scene shown = scene_of({{"a", std::nullopt, cube}, {"b", std::nullopt, cube}}, cube);
  ASSERT_EQ(shown.parts.size(), 2u);
  EXPECT_EQ(shown.parts[1].color, palette_color(1));
  EXPECT_TRUE(scene_of({}, std::nullopt).parts.empty());
}

TEST(SceneMessage, EmptySceneAndEmptySolid) {
  const std::string empty = encode_scene({});
  EXPECT_EQ(empty.substr(8, 12), "{\"parts\":[]}");
  const Scene nothing = scene_of({{"void", std::nullopt, language::solid_value(Solid())}}, std::nullopt);
  const std::string message = encode_scene(nothing);
  EXPECT_NE(message.find("\"box\":null"), std::string::npos);
}

TEST(SceneMessage, OpenMeshHasNoVolume) {
  PolygonMesh square;
  square.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.faces = {{0, 1, 2, 3}};
  const language::Value mesh(std::shared_ptr<const language::Object>(std::make_shared<language::MeshValue>(square)));
  const Scene scene = scene_of({{"sheet", std::nullopt, mesh}}, std::nullopt);
  const std::string message = encode_scene(scene);
  EXPECT_NE(message.find("\"solid\":false,\"volume\":null,\"area\":1"), std::string::npos);
  // A bad face index is an error, not a crash.
  square.faces = {{0, 1, 7}};
  const language::Value bad(std::shared_ptr<const language::Object>(std::make_shared<language::MeshValue>(square)));
  EXPECT_THROW(encode_scene(scene_of({{"bad", std::nullopt, bad}}, std::nullopt)), InvalidInput);
}

/// The parts a script shows.
Scene shown_scene(const std::string& text) {
  auto source = std::make_shared<language::SourceFile>();
  source->name = "test.bsp";
  source->text = text;
  std::ostringstream out;
  language::Interpreter interpreter({.out = &out, .err = &out});
  interpreter.run(source);
  return scene_of(interpreter.shown(), std::nullopt);
}

/// The float32 points of the part's "curve" in `message` (the part's JSON starts at `from`).
std::vector<Eigen::Vector3f> curve_points(const std::string& message, std::size_t from) {
  const std::uint32_t json_size = u32_at(message, 4);
  const std::string json = message.substr(8, json_size);
  const std::size_t key = json.find("\"curve\":[", from);
  EXPECT_NE(key, std::string::npos) << json;
  if (key == std::string::npos) return {};
  const auto offset = static_cast<std::size_t>(number_after(json, "curve", from));
  const std::size_t count = std::stoul(json.substr(json.find(',', key) + 1));
  EXPECT_EQ(offset % 4, 0u);
  EXPECT_LE(8 + json_size + offset + 12 * count, message.size());
  std::vector<Eigen::Vector3f> points(count);
  std::memcpy(points.data(), message.data() + 8 + json_size + offset, 12 * count);
  return points;
}

/// Distance from p to the polyline through `corners`.
double distance_to_polyline(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& corners) {
  double best = INFINITY;
  for (std::size_t k = 0; k + 1 < corners.size(); ++k) {
    const Eigen::Vector3d a = corners[k], d = corners[k + 1] - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * d - p).norm());
  }
  return best;
}

TEST(SceneMessage, CurvesAreShownAsPolylinesInTheirColour) {
  // A degree-1 spline is its control polygon: the points lie on it and the length is exact (3 + 4).
  // A closed degree-1 spline through a square's corners ends where it starts (length 4). A list of
  // points is one curve, not three parts.
  const Scene scene = shown_scene(
      "show(bspline([[0, 0, 0], [3, 0, 0], [3, 4, 0]], degree=1), name=\"path\", color=\"red\")\n"
      "show(bspline([[0, 0], [1, 0], [1, 1], [0, 1]], degree=1, closed=true), name=\"loop\")\n"
      "show([[0, 0, 1], [1, 0, 1], [1, 1, 1]], name=\"points\")\n");
  ASSERT_EQ(scene.parts.size(), 3u);
  const ViewPart& path = scene.parts[0];
  EXPECT_TRUE(path.mesh.faces.empty());
  EXPECT_FALSE(path.solid);
  EXPECT_NEAR(path.length, 7.0, 1e-12);
  EXPECT_GT(path.curve.size(), 2u);
  for (const Eigen::Vector3d& p : path.curve)
    EXPECT_LT(distance_to_polyline(p, {{0, 0, 0}, {3, 0, 0}, {3, 4, 0}}), 1e-12);
  EXPECT_TRUE(path.box.isApprox(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 4, 0))));
  const ViewPart& loop = scene.parts[1];
  EXPECT_NEAR(loop.length, 4.0, 1e-12);
  EXPECT_EQ(loop.curve.front(), loop.curve.back());
  EXPECT_NEAR(scene.parts[2].length, 2.0, 1e-15);
  EXPECT_EQ(scene.parts[2].curve.size(), 3u);

  const std::string message = encode_scene(scene);
  const std::string json = message.substr(8, u32_at(message, 4));
  EXPECT_NE(json.find("\"name\":\"path\",\"color\":[0.85,0.2,0.2],\"solid\":false,\"volume\":null,\"area\":0"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("\"triangles\":0"), std::string::npos);
  EXPECT_DOUBLE_EQ(number_after(json, "length"), 7.0);
  const std::vector<Eigen::Vector3f> sent = curve_points(message, 0);
  ASSERT_EQ(sent.size(), path.curve.size());
  for (std::size_t k = 0; k < sent.size(); ++k) EXPECT_EQ(sent[k], path.curve[k].cast<float>());
  const std::vector<Eigen::Vector3f> third = curve_points(message, json.find("\"name\":\"points\""));
  ASSERT_EQ(third.size(), 3u);
  EXPECT_EQ(third[2], Eigen::Vector3f(1, 1, 1));
}

TEST(SceneMessage, SurfacesAreShownAsOpenTriangleMeshes) {
  // A bilinear patch is flat: its triangles cover it exactly (area 3 x 2). A curved one: every
  // triangle corner lies on it, and its top within the chord error (1e-3 of its size).
  const Scene scene = shown_scene(
      "show(bspline_surface([[[0, 0, 0], [0, 2, 0]], [[3, 0, 0], [3, 2, 0]]], degree=1), name=\"sheet\")\n"
      "show(bspline_surface([[[0, 0, 0], [0, 1, 0], [0, 2, 0]], [[1, 0, 1], [1, 1, 1], [1, 2, 1]],"
      " [[2, 0, 0], [2, 1, 0], [2, 2, 0]]], degree=2), name=\"arch\")\n");
  ASSERT_EQ(scene.parts.size(), 2u);
  const ViewPart& sheet = scene.parts[0];
  EXPECT_FALSE(sheet.solid);
  EXPECT_TRUE(sheet.curve.empty());
  EXPECT_FALSE(sheet.mesh.faces.empty());
  EXPECT_NEAR(sheet.area, 6.0, 1e-12);
  EXPECT_TRUE(sheet.box.isApprox(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 2, 0))));
  // The arch x in [0, 2], z = x (2 - x) / 2 (a degree-2 Bezier in u with controls 0, 1, 0),
  // extruded along y: every triangle corner on it.
  const ViewPart& arch = scene.parts[1];
  for (const Eigen::Vector3d& p : arch.mesh.vertices) EXPECT_NEAR(p.z(), p.x() * (2 - p.x()) / 2, 1e-12);
  EXPECT_NEAR(arch.box.max().z(), 0.5, 5e-3);
  const std::string message = encode_scene(scene);
  EXPECT_NE(message.find("\"name\":\"sheet\",\"color\""), std::string::npos);
  EXPECT_NE(message.find("\"curve\":null"), std::string::npos);
}

TEST(SceneMessage, ASolidIsSentAsItsExactBoundaryVertexForVertex) {
  // A set operation's result (vertices that are rounded, not grid points): the part is to_mesh
  // without output rounding, its vertices at their approximations (MeshOptions::approximate:
  // within 2^-20 grid steps of the correctly rounded ones, the same faces), the GLB's positions
  // are its vertices in order as float32, and the edges index them; the measures are the exact
  // boundary's.
  const Solid ball = sphere(1, {.segments = 24}) - translate(box({0, 0, 0}, {1, 1, 1}), {0.3, 0.2, 0.1});
  const Scene scene = scene_of({{"ball", std::nullopt, language::solid_value(ball)}}, std::nullopt);
  const PolygonMesh exact = to_mesh(ball, {.clean = false, .approximate = true});
  ASSERT_EQ(scene.parts.size(), 1u);
  EXPECT_EQ(scene.parts[0].mesh.vertices, exact.vertices);
  EXPECT_EQ(scene.parts[0].mesh.faces, exact.faces);
  const PolygonMesh rounded = to_mesh(ball, {.clean = false});
  ASSERT_EQ(rounded.faces, exact.faces);
  for (std::size_t i = 0; i < exact.vertices.size(); ++i)
    EXPECT_LE((exact.vertices[i] - rounded.vertices[i]).cwiseAbs().maxCoeff(), std::ldexp(ball.grid().step(), -19))
        << i;
  EXPECT_NEAR(*scene.parts[0].volume, volume(ball), 1e-12);
  EXPECT_NEAR(scene.parts[0].area, surface_area(ball), 1e-12);
  const std::string message = encode_scene(scene);
  const Block glb = block_of(message, "glb");
  const std::size_t bin = glb.offset + 20 + u32_at(message, glb.offset + 12) + 8;
  for (std::size_t i = 0; i < exact.vertices.size(); ++i) {
    float xyz[3];
    std::memcpy(xyz, message.data() + bin + 12 * i, 12);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(xyz[k], static_cast<float>(exact.vertices[i][k])) << i;
  }
  const Block edges = block_of(message, "edges");
  EXPECT_GT(edges.count, exact.faces.size() / 2);
  for (std::size_t e = 0; e < 2 * edges.count; ++e)
    EXPECT_LT(u32_at(message, edges.offset + 4 * e), exact.vertices.size());
}

TEST(StatusMessage, TellsTheScriptsShareItsEndAndWhenTheSceneWentOut) {
  const std::string text = encode_status({.run = 2,
                                          .milliseconds = 30,
                                          .script_milliseconds = 20.5,
                                          .script_end = 1795000000123.5,
                                          .scene_sent = 1795000000140.25});
  EXPECT_NE(text.find("\"ms\":30,\"script_ms\":20.5,\"script_end\":1795000000123.5,\"scene_sent\":1795000000140.25,"),
            std::string::npos)
      << text;
}

TEST(StatusMessage, CarriesTheErrorTextEscaped) {
  const std::string text = encode_status({.ok = false, .error = "a.bsp:1:2: error: \"x\"\n  x\t^\n\x01", .run = 3});
  EXPECT_NE(text.find("\"ok\":false"), std::string::npos);
  EXPECT_NE(text.find("\"run\":3"), std::string::npos);
  EXPECT_NE(text.find(R"("error":"a.bsp:1:2: error: \"x\"\n  x\t^\n\u0001")"), std::string::npos) << text;
  EXPECT_EQ(json_string("\xff"
                        "é"),
            "\"\\ufffdé\"");
}

}  // namespace
}  // namespace sculpt::view
