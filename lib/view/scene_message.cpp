#include "view/scene_message.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include "base/errors.hpp"
#include "mesh/edge_incidence.hpp"
#include "mesh/mesh_io.hpp"
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

/// The feature edges of `mesh` as float32 segments (6 numbers each).
std::string edge_data(const PolygonMesh& mesh, std::size_t& count) {
  const auto edges = detail::feature_edges(mesh);
  count = edges.size();
  std::string data(edges.size() * 6 * sizeof(float), '\0');
  char* out = data.data();
  for (const auto& edge : edges)
    for (const int v : edge)
      for (int k = 0; k < 3; ++k) {
        const auto f = static_cast<float>(mesh.vertices[v][k]);
        std::memcpy(out, &f, sizeof f);
        out += sizeof f;
      }
  return data;
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

std::string encode_scene(const Scene& scene) {
  std::string json = "{\"parts\":[";
  std::string data;
  for (std::size_t p = 0; p < scene.parts.size(); ++p) {
    const ViewPart& part = scene.parts[p];
    check_face_indices(part.mesh, "view");
    const std::string glb = encode_mesh(part.mesh, MeshFormat::Glb);
    std::size_t edge_count = 0;
    const std::string edges = edge_data(part.mesh, edge_count);
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
    json += ",\"edges\":[" + std::to_string(data.size()) + "," + std::to_string(edge_count) + "]}";
    data += edges;
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
