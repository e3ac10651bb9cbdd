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

/// The bytes of the float32 positions and of the uint32 indices in the BIN chunk of a GLB made by
/// encode_mesh (mesh/formats/glb_writer.cpp: positions first, then indices, their counts in the
/// first two accessors); empty for a GLB without triangles.
struct GlbArrays {
  std::string_view positions;  ///< 12 bytes a vertex
  std::string_view indices;    ///< 12 bytes a triangle
};

GlbArrays glb_arrays(const std::string& glb) {
  if (glb.size() < 20) return {};
  std::uint32_t json_size;
  std::memcpy(&json_size, glb.data() + 12, 4);
  if (glb.size() < 28 + std::size_t(json_size)) return {};
  const std::string_view json(glb.data() + 20, json_size);
  const std::size_t accessors = json.find("\"accessors\":[{");
  if (accessors == std::string_view::npos) return {};
  std::size_t counts[2] = {0, 0};
  std::size_t at = accessors;
  for (std::size_t& count : counts) {
    at = json.find("\"count\":", at);
    if (at == std::string_view::npos) return {};
    at += 8;
    if (std::from_chars(json.data() + at, json.data() + json.size(), count).ec != std::errc()) return {};
  }
  const std::size_t bin = 28 + std::size_t(json_size);
  if (counts[0] > (glb.size() - bin) / 12 || counts[1] > (glb.size() - bin - 12 * counts[0]) / 4) return {};
  return {{glb.data() + bin, 12 * counts[0]}, {glb.data() + bin + 12 * counts[0], 4 * (counts[1] / 3 * 3)}};
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

/// The cell depth behind each triangle of `glb` (detail/cell_depths.hpp) as uint16, padded to a
/// multiple of 4 bytes; the count of triangles.
std::pair<std::string, std::size_t> depth_data(const Solid& solid, const std::string& glb) {
  const GlbArrays arrays = glb_arrays(glb);
  std::vector<Eigen::Vector3d> points(arrays.positions.size() / 12);
  for (std::size_t v = 0; v < points.size(); ++v) {
    float xyz[3];
    std::memcpy(xyz, arrays.positions.data() + 12 * v, 12);
    points[v] = {xyz[0], xyz[1], xyz[2]};
  }
  std::vector<std::array<std::uint32_t, 3>> triangles(arrays.indices.size() / 12);
  if (!triangles.empty()) std::memcpy(triangles.data(), arrays.indices.data(), arrays.indices.size());
  for (const auto& t : triangles)
    for (const std::uint32_t v : t)
      if (v >= points.size()) throw InvalidInput("view: a triangle's index is out of range");
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
  std::string data;
  for (std::size_t p = 0; p < scene.parts.size(); ++p) {
    const ViewPart& part = scene.parts[p];
    check_face_indices(part.mesh, "view");
    std::string glb;
    EdgeData edges;
    parallel_invoke([&] { glb = encode_glb_for_display(part.mesh); }, [&] { edges = edge_data(part.mesh); });
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
    // GLB files are whole multiples of 4 bytes (glTF 2.0 sec. 4.4), so every offset stays aligned.
    json += ",\"glb\":[" + std::to_string(data.size()) + "," + std::to_string(glb.size()) + "]";
    data += glb;
    data.append((4 - data.size() % 4) % 4, '\0');
    json += ",\"edges\":[" + std::to_string(data.size()) + "," + std::to_string(edges.count) + "," +
            std::to_string(edges.creases) + "],\"features\":" + std::to_string(edges.features);
    data += edges.indexed;
    json += ",\"depth\":";
    const auto* solid = part.value.object<language::SolidValue>();
    if (options.depth && solid) {
      auto [depths, count] = depth_data(solid->solid, glb);
      json += '[';  // (not "[" + std::string: GCC 12 warns falsely about its memcpy)
      json += std::to_string(data.size()) + "," + std::to_string(count) + "]";
      data += depths;
    } else {
      json += "null";
    }
    json += ",\"curve\":";
    if (!part.curve.empty()) {
      json += '[';
      json += std::to_string(data.size()) + "," + std::to_string(part.curve.size()) + "]";
      data += curve_data(part.curve);
    } else {
      json += "null";
    }
    json += ",\"length\":";
    append_number(json, part.length);
    json += '}';
  }
  json += "]}";
  json.append((4 - json.size() % 4) % 4, ' ');
  if (json.size() + data.size() > std::numeric_limits<std::uint32_t>::max() - 8u)
    throw InvalidInput("view: the scene is too large to send (" + std::to_string(data.size()) + " bytes)");
  std::string message = "SCLV";
  append_u32(message, static_cast<std::uint32_t>(json.size()));
  message += json;
  message += data;
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
  out += ",\"parts\":" + std::to_string(status.parts);
  out += ",\"error\":" + json_string(status.ok ? std::string() : status.error) + "}";
  return out;
}

}  // namespace sculpt::view
