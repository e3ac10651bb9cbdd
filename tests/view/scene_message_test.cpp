// The scene and status messages (lib/view/scene_message.hpp): layout, measures, the GLB inside
// decoded by the mesh layer's own reader, feature edges as float32 segments, JSON escaping.
#include "view/scene_message.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "base/errors.hpp"
#include "bsp/primitives.hpp"
#include "language/solid_values.hpp"
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
  EXPECT_EQ(number_after(json, "loose"), edges_offset + 8 * edges_count);
  EXPECT_NE(json.find("\"loose\":[" + std::to_string(edges_offset + 8 * edges_count) + ",0]"), std::string::npos);
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
