#include "view/scene_message.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "base/errors.hpp"
#include "base/parallel.hpp"
#include "language/solid_values.hpp"
#include "mesh/edge_incidence.hpp"
#include "mesh/mesh_io.hpp"
#include "view/detail/cell_depths.hpp"
#include "view/detail/feature_edges.hpp"

namespace sculpt::view {
namespace {

void append_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, x);
  out.append(text, end);
}

void append_u32(std::string& out, std::uint32_t x) {
  char b[4];
  std::memcpy(b, &x, 4);  // little endian, as glTF (mesh/formats/glb_container.hpp checks it)
  out.append(b, 4);
}

void append_vector(std::string& out, const Eigen::Vector3d& v) {
  out += '[';
  for (int k = 0; k < 3; ++k) {
    if (k) out += ',';
    append_number(out, v[k]);
  }
  out += ']';
}

/// The feature edges of a part as pairs of uint32 indices into its GLB's positions, which are
/// the mesh's vertices in order (encode_glb_for_display), 8 bytes an edge, creases first. A part
/// with more than kDenseFeatureEdges features that are not creases sends its creases only: the
/// page would draw no other (`features` still counts them all).
struct EdgeData {
  std::string indexed;
  std::size_t count = 0, creases = 0, features = 0;
};

EdgeData edge_data(const PolygonMesh& mesh) {
  const detail::ClassifiedEdges classified = detail::classified_feature_edges(mesh);
  EdgeData data;
  data.features = classified.edges.size();
  data.creases = classified.creases;
  data.count = data.features - data.creases > kDenseFeatureEdges ? data.creases : data.features;
  data.indexed.resize(8 * data.count);
  for (std::size_t i = 0; i < data.count; ++i) {
    const std::uint32_t ends[2] = {static_cast<std::uint32_t>(classified.edges[i][0]),
                                   static_cast<std::uint32_t>(classified.edges[i][1])};
    std::memcpy(data.indexed.data() + 8 * i, ends, 8);  // little endian (glb_container.hpp checks it)
  }
  return data;
}

/// The cell depth behind each triangle of `arrays` (what the part's GLB holds, in its order;
/// detail/cell_depths.hpp) as uint16, padded to a multiple of 4 bytes; the count of triangles.
std::pair<std::string, std::size_t> depth_data(const Solid& solid, const DisplayArrays& arrays) {
  std::vector<Eigen::Vector3d> points(arrays.positions.size() / 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    points[v] = {arrays.positions[3 * v], arrays.positions[3 * v + 1], arrays.positions[3 * v + 2]};
  std::vector<std::array<std::uint32_t, 3>> triangles(arrays.indices.size() / 3);
  if (!triangles.empty()) std::memcpy(triangles.data(), arrays.indices.data(), 4 * arrays.indices.size());
  const std::vector<int> depths = detail::cell_depths_behind(solid, points, triangles);
  std::string out;
  out.reserve(2 * depths.size() + 2);
  for (const int d : depths) {
    const auto x = static_cast<std::uint16_t>(std::min(d, 65535));
    char b[2];
    std::memcpy(b, &x, 2);
    out.append(b, 2);
  }
  out.append((4 - out.size() % 4) % 4, '\0');
  return {std::move(out), depths.size()};
}

/// A curve's points as float32 (12 bytes a point).
std::string curve_data(const std::vector<Eigen::Vector3d>& points) {
  std::string out;
  out.reserve(12 * points.size());
  for (const Eigen::Vector3d& p : points) {
    if (!(p.cwiseAbs().maxCoeff() <= std::numeric_limits<float>::max()))
      throw InvalidInput("view: a curve point is not finite or beyond float32");
    const float xyz[3] = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    out.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  return out;
}

}  // namespace

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", c);
      out += code;
    } else if (c < 0x80) {
      out += static_cast<char>(c);
    } else {
      // Copy a well-formed UTF-8 sequence; replace a stray byte by U+FFFD.
      const int length = c >= 0xF0 && c < 0xF5 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 0;
      bool ok = length > 0 && i + length <= text.size();
      for (int k = 1; ok && k < length; ++k) ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
      if (ok) {
        out.append(text, i, length);
        i += length - 1;
      } else {
        out += "\\ufffd";
      }
    }
  }
  return out + "\"";
}

std::string encode_scene(const Scene& scene, const SceneOptions& options) {
  std::string json = "{\"parts\":[";
  // The binary blocks (each a multiple of 4 bytes long, so every offset stays aligned), copied
  // once into the message after the JSON that gives their offsets.
  std::vector<std::string> blocks;
  std::size_t data_size = 0;
  const auto add_block = [&](std::string block) {
    block.append((4 - block.size() % 4) % 4, '\0');
    const std::size_t offset = data_size;
    data_size += block.size();
    blocks.push_back(std::move(block));
    return offset;
  };
  for (std::size_t p = 0; p < scene.parts.size(); ++p) {
    const ViewPart& part = scene.parts[p];
    check_face_indices(part.mesh, "view");
    DisplayArrays arrays;
    std::string glb;
    EdgeData edges;
    parallel_invoke(
        [&] {
          arrays = display_arrays(part.mesh);
          glb = encode_glb_for_display(arrays);
        },
        [&] { edges = edge_data(part.mesh); });
    std::size_t triangles = 0;
    for (const auto& face : part.mesh.faces) triangles += face.size() - 2;
    if (p) json += ',';
    json += "{\"name\":" + json_string(part.name) + ",\"color\":[";
    for (int k = 0; k < 3; ++k) {
      if (k) json += ',';
      append_number(json, part.color[k]);
    }
    json += "],\"solid\":";
    json += part.solid ? "true" : "false";
    json += ",\"volume\":";
    if (part.volume) {
      append_number(json, *part.volume);
    } else {
      json += "null";
    }
    json += ",\"area\":";
    append_number(json, part.area);
    json += ",\"box\":";
    if (part.box.isEmpty()) {
      json += "null";
    } else {
      json += '[';
      append_vector(json, part.box.min());
      json += ',';
      append_vector(json, part.box.max());
      json += ']';
    }
    json += ",\"triangles\":" + std::to_string(triangles);
    const std::size_t glb_size = glb.size();
    json += ",\"glb\":[" + std::to_string(add_block(std::move(glb))) + "," + std::to_string(glb_size) + "]";
    json += ",\"edges\":[" + std::to_string(add_block(std::move(edges.indexed))) + "," + std::to_string(edges.count) +
            "," + std::to_string(edges.creases) + "],\"features\":" + std::to_string(edges.features);
    json += ",\"depth\":";
    const auto* solid = part.value.object<language::SolidValue>();
    if (options.depth && solid) {
      auto [depths, count] = depth_data(solid->solid, arrays);
      json += '[';  // (not "[" + std::string: GCC 12 warns falsely about its memcpy)
      json += std::to_string(add_block(std::move(depths))) + "," + std::to_string(count) + "]";
    } else {
      json += "null";
    }
    json += ",\"curve\":";
    if (!part.curve.empty()) {
      json += '[';
      json += std::to_string(add_block(curve_data(part.curve))) + "," + std::to_string(part.curve.size()) + "]";
    } else {
      json += "null";
    }
    json += ",\"length\":";
    append_number(json, part.length);
    json += '}';
  }
  json += "]}";
  json.append((4 - json.size() % 4) % 4, ' ');
  if (json.size() + data_size > std::numeric_limits<std::uint32_t>::max() - 8u)
    throw InvalidInput("view: the scene is too large to send (" + std::to_string(data_size) + " bytes)");
  std::string message = "SCLV";
  message.reserve(8 + json.size() + data_size);
  append_u32(message, static_cast<std::uint32_t>(json.size()));
  message += json;
  for (std::string& block : blocks) {
    message += block;
    std::string().swap(block);  // (freed as it goes: the message is the scene's largest copy)
  }
  return message;
}

std::string encode_status(const Status& status) {
  std::string out = "{\"type\":\"status\",\"ok\":";
  out += status.ok ? "true" : "false";
  out += ",\"run\":" + std::to_string(status.run) + ",\"ms\":";
  append_number(out, status.milliseconds);
  out += ",\"script_ms\":";
  append_number(out, status.script_milliseconds);
  out += ",\"script_end\":";
  append_number(out, status.script_end);
  out += ",\"scene_sent\":";
  append_number(out, status.scene_sent);
  out += ",\"parts\":" + std::to_string(status.parts);
  out += ",\"error\":" + json_string(status.ok ? std::string() : status.error) + "}";
  return out;
}

}  // namespace sculpt::view
