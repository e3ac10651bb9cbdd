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
#include <unordered_map>
#include <utility>
#include <vector>

#include "base/errors.hpp"
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

struct FloatPoint {
  std::array<std::uint32_t, 3> bits;
  bool operator==(const FloatPoint&) const = default;
};

struct FloatPointHash {
  std::size_t operator()(const FloatPoint& p) const {
    return (std::size_t(p.bits[0]) * 0x9E3779B97F4A7C15ull) ^ (std::size_t(p.bits[1]) * 0xC2B2AE3D27D4EB4Full) ^
           std::size_t(p.bits[2]);
  }
};

FloatPoint float_point(const void* xyz) {
  FloatPoint p;
  std::memcpy(p.bits.data(), xyz, 12);
  return p;
}

/// The feature edges of a part: as pairs of indices (uint32) into its GLB's positions, 8 bytes an
/// edge; an end the GLB does not hold at the same float32 point (output rounding moved it)
/// sends its edge as 6 float32 ("loose"), as does every edge of a part without positions.
struct EdgeData {
  std::string indexed;
  std::size_t indexed_count = 0, indexed_creases = 0;
  std::string loose;
  std::size_t loose_count = 0, loose_creases = 0;
};

EdgeData edge_data(const PolygonMesh& mesh, const std::string& glb) {
  const std::string_view positions = glb_arrays(glb).positions;
  std::unordered_map<FloatPoint, std::uint32_t, FloatPointHash> index;
  index.reserve(positions.size() / 12);
  for (std::size_t v = 0; 12 * v < positions.size(); ++v)
    index.emplace(float_point(positions.data() + 12 * v), static_cast<std::uint32_t>(v));
  EdgeData data;
  const detail::ClassifiedEdges features = detail::classified_feature_edges(mesh);
  for (std::size_t i = 0; i < features.edges.size(); ++i) {
    const auto& edge = features.edges[i];
    const bool crease = i < features.creases;
    float ends[6];
    for (int e = 0; e < 2; ++e)
      for (int k = 0; k < 3; ++k) ends[3 * e + k] = static_cast<float>(mesh.vertices[edge[e]][k]);
    const auto a = index.find(float_point(ends)), b = index.find(float_point(ends + 3));
    if (a != index.end() && b != index.end()) {
      append_u32(data.indexed, a->second);
      append_u32(data.indexed, b->second);
      ++data.indexed_count;
      data.indexed_creases += crease;
    } else {
      data.loose.append(reinterpret_cast<const char*>(ends), sizeof ends);
      ++data.loose_count;
      data.loose_creases += crease;
    }
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
    const std::string glb = encode_mesh(part.mesh, MeshFormat::Glb);
    const EdgeData edges = edge_data(part.mesh, glb);
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
    json += ",\"edges\":[" + std::to_string(data.size()) + "," + std::to_string(edges.indexed_count) + "," +
            std::to_string(edges.indexed_creases) + "]";
    data += edges.indexed;
    json += ",\"loose\":[" + std::to_string(data.size()) + "," + std::to_string(edges.loose_count) + "," +
            std::to_string(edges.loose_creases) + "]";
    data += edges.loose;
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
  out += ",\"parts\":" + std::to_string(status.parts);
  out += ",\"error\":" + json_string(status.ok ? std::string() : status.error) + "}";
  return out;
}

}  // namespace sculpt::view
