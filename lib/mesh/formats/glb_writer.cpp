// Binary glTF 2.0 (.glb) writer: one scene, one node, one mesh of one TRIANGLES primitive whose
// POSITION accessor holds float32 (glTF 2.0 sec. 3.7.2.1: positions are float VEC3) and whose
// indices are UNSIGNED_INT. The mesh is first rounded to float32 by round_for_output, as for binary
// STL, so the triangles as the file holds them are clean; faces are triangulated by
// triangulate_polygon. Coordinates are written as they are: one world unit is one glTF unit (the
// spec's metre, sec. 3.4), with no scale node, so that a reader gets back exactly the float32 values
// (docs/mesh_io.md says why).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "mesh/formats/glb_container.hpp"
#include "mesh/formats/mesh_formats.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::mesh::detail {
namespace {

/// Appends the float32 `x` as JSON: the shortest decimal of the double equal to it, which every
/// JSON reader parses back to that double and so to exactly `x` (the accessor's min and max must
/// be the data's own values, sec. 3.6.2.5).
void append_float(std::string& out, float x) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, static_cast<double>(x));
  out.append(text, end);
}

void append_int(std::string& out, std::uint64_t x) { out += std::to_string(x); }

/// The JSON chunk (sec. 3: the glTF asset) for `vertex_count` positions and `index_count` indices,
/// positions first in the buffer, indices after them; `lo`/`hi` the positions' bounds.
std::string gltf_json(std::size_t vertex_count, std::size_t index_count, const float lo[3], const float hi[3]) {
  std::string out = R"({"asset":{"version":"2.0","generator":"sculpt"},"scene":0,)";
  if (index_count == 0) return out + R"("scenes":[{}]})";  // nothing to show; arrays may not be empty
  const std::uint64_t positions = 12 * std::uint64_t(vertex_count), indices = 4 * std::uint64_t(index_count);
  out += R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)";
  out += R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":4}]}],)";
  out += R"("buffers":[{"byteLength":)";
  append_int(out, positions + indices);
  out += R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)";
  append_int(out, positions);
  out += R"(,"target":)" + std::to_string(glb::kArrayBuffer) + R"(},{"buffer":0,"byteOffset":)";
  append_int(out, positions);
  out += R"(,"byteLength":)";
  append_int(out, indices);
  out += R"(,"target":)" + std::to_string(glb::kElementArrayBuffer) +
         R"(}],"accessors":[{"bufferView":0,"componentType":)";
  out += std::to_string(glb::kFloat) + R"(,"count":)";
  append_int(out, vertex_count);
  out += R"(,"type":"VEC3","min":[)";
  for (int k = 0; k < 3; ++k) {
    append_float(out, lo[k]);
    out += k < 2 ? "," : R"(],"max":[)";
  }
  for (int k = 0; k < 3; ++k) {
    append_float(out, hi[k]);
    out += k < 2 ? "," : "]}";
  }
  out += R"(,{"bufferView":1,"componentType":)" + std::to_string(glb::kUnsignedInt) + R"(,"count":)";
  append_int(out, index_count);
  out += R"(,"type":"SCALAR"}]})";
  return out;
}

/// Appends a chunk (sec. 4.4.3): its length and type, then `data` padded to 4 bytes with `pad`.
void append_chunk(std::string& out, std::uint32_t type, const std::string& data, char pad) {
  const std::size_t padded = (data.size() + 3) / 4 * 4;
  glb::append_u32(out, static_cast<std::uint32_t>(padded));
  glb::append_u32(out, type);
  out += data;
  out.append(padded - data.size(), pad);
}

/// The GLB of `mesh` as it is: each vertex converted to float32, each face triangulated.
std::string pack_glb(const PolygonMesh& mesh) {
  std::vector<float> positions(3 * mesh.vertices.size());
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.vertices[v][k];
      if (!(std::fabs(x) <= double(std::numeric_limits<float>::max())))
        throw InvalidInput("write_mesh: vertex " + std::to_string(v) + " is beyond the float32 range of glTF");
      const float f = static_cast<float>(x);
      positions[3 * v + k] = f;
      lo[k] = v == 0 ? f : std::min(lo[k], f);
      hi[k] = v == 0 ? f : std::max(hi[k], f);
    }
  std::vector<std::uint32_t> indices;
  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> triangles;
  for (const auto& face : mesh.faces) {
    triangles.clear();
    triangulator.append(mesh.vertices, face, triangles);
    for (const IndexTriangle& t : triangles)
      for (const int i : t) indices.push_back(static_cast<std::uint32_t>(i));
  }
  // The container's lengths are uint32 (sec. 4.4.2): the whole file must stay below 4 GiB.
  const std::uint64_t bin_size = 12 * std::uint64_t(mesh.vertices.size()) + 4 * std::uint64_t(indices.size());
  if (bin_size > 0xF0000000ull)
    throw InvalidInput("write_mesh: the mesh is too large for a GLB file (" + std::to_string(bin_size) +
                       " bytes of data; the format holds less than 4 GiB)");
  std::string bin;
  if (!indices.empty()) {
    bin.resize(bin_size);
    std::memcpy(bin.data(), positions.data(), 4 * positions.size());
    std::memcpy(bin.data() + 4 * positions.size(), indices.data(), 4 * indices.size());
  }
  std::string out;
  glb::append_u32(out, glb::kMagic);
  glb::append_u32(out, glb::kVersion);
  glb::append_u32(out, 0);  // the total length, set below
  append_chunk(out, glb::kJsonChunk, gltf_json(mesh.vertices.size(), indices.size(), lo, hi), ' ');
  if (!bin.empty()) append_chunk(out, glb::kBinChunk, bin, '\0');
  const auto length = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data() + 8, &length, 4);
  return out;
}

}  // namespace

std::string encode_glb(const PolygonMesh& mesh) {
  // glTF positions are float32: round as for binary STL so the file is clean as written.
  return pack_glb(round_for_output(mesh, {.precision = OutputPrecision::Float32, .triangles = true}));
}

std::string encode_glb_unrounded(const PolygonMesh& mesh) { return pack_glb(mesh); }

}  // namespace sculpt::mesh::detail
