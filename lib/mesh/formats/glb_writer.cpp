// Binary glTF 2.0 (.glb) writer: one scene, one node, one mesh of one TRIANGLES primitive whose
// POSITION accessor holds float32 (glTF 2.0 sec. 3.7.2.1: positions are float VEC3) and whose
// indices are UNSIGNED_INT. The mesh is first rounded to float32 by round_for_output, as for binary
// STL, so the triangles as the file holds them are clean; faces are triangulated by
// triangulate_polygon. Coordinates are written as they are: one world unit is one glTF unit (the
// spec's metre, sec. 3.4), with no scale node, so that a reader gets back exactly the float32 values
// (docs/mesh_io.md says why). For a screen (the live view) the vertices are converted without
// rounding and the triangles go out in runs of 16-bit indices where the numbering allows
// (index_runs: one primitive a run, all of them on one bufferView of positions).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
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

/// Appends the accessor (sec. 3.6.2) of `count` elements of `type` at `byte_offset` in `view`.
void append_accessor(std::string& out, int view, std::uint64_t byte_offset, int component_type, std::uint64_t count,
                     const char* type) {
  out += R"({"bufferView":)" + std::to_string(view);
  if (byte_offset != 0) {
    out += R"(,"byteOffset":)";
    append_int(out, byte_offset);
  }
  out += R"(,"componentType":)" + std::to_string(component_type) + R"(,"count":)";
  append_int(out, count);
  out += R"(,"type":")";
  out += type;
  out += '"';
}

/// The smallest coordinates of vertices [first, first + count) (count > 0), then the largest.
std::array<float, 6> bounds(const DisplayArrays& arrays, std::size_t first, std::size_t count) {
  std::array<float, 6> b;
  for (std::size_t k = 0; k < 3; ++k) b[k] = b[k + 3] = arrays.positions[3 * first + k];
  for (std::size_t v = first; v < first + count; ++v)
    for (std::size_t k = 0; k < 3; ++k) {
      b[k] = std::min(b[k], arrays.positions[3 * v + k]);
      b[k + 3] = std::max(b[k + 3], arrays.positions[3 * v + k]);
    }
  return b;
}

/// The JSON chunk (sec. 3: the glTF asset): positions first in the buffer, then each run's indices
/// (4-byte aligned); one primitive a run, whose POSITION accessor starts at the run's base vertex.
std::string gltf_json(const DisplayArrays& arrays, const std::vector<IndexRun>& runs, std::uint64_t index_bytes) {
  std::string out = R"({"asset":{"version":"2.0","generator":"sculpt"},"scene":0,)";
  if (runs.empty()) return out + R"("scenes":[{}]})";  // nothing to show; arrays may not be empty
  const std::uint64_t positions = 4 * std::uint64_t(arrays.positions.size());
  out += R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[)";
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (r) out += ',';
    out += R"({"attributes":{"POSITION":)" + std::to_string(2 * r) + R"(},"indices":)" + std::to_string(2 * r + 1) +
           R"(,"mode":4})";
  }
  out += R"(]}],"buffers":[{"byteLength":)";
  append_int(out, positions + index_bytes);
  out += R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)";
  append_int(out, positions);
  out += R"(,"target":)" + std::to_string(glb::kArrayBuffer) + R"(},{"buffer":0,"byteOffset":)";
  append_int(out, positions);
  out += R"(,"byteLength":)";
  append_int(out, index_bytes);
  out += R"(,"target":)" + std::to_string(glb::kElementArrayBuffer) + R"(}],"accessors":[)";
  const auto vertex_count = std::uint32_t(arrays.positions.size() / 3);
  std::optional<std::array<float, 6>> all_bounds;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const IndexRun& run = runs[r];
    if (r) out += ',';
    // POSITION accessors carry the bounds of their elements (sec. 3.7.2.1): a run of 16-bit
    // indices spans at most 65,536 vertices; a wide run spans them all, whose bounds are found once.
    if (run.wide && !all_bounds) all_bounds = bounds(arrays, 0, vertex_count);
    const std::array<float, 6> b = run.wide ? *all_bounds : bounds(arrays, run.base, run.vertices);
    append_accessor(out, 0, 12 * std::uint64_t(run.wide ? 0 : run.base), glb::kFloat,
                    run.wide ? vertex_count : run.vertices, "VEC3");
    out += R"(,"min":[)";
    for (std::size_t k = 0; k < 6; ++k) {
      append_float(out, b[k]);
      out += k == 2 ? R"(],"max":[)" : k == 5 ? "]}," : ",";
    }
    append_accessor(out, 1, run.byte_offset, run.wide ? glb::kUnsignedInt : glb::kUnsignedShort,
                    3 * std::uint64_t(run.triangles), "SCALAR");
    out += '}';
  }
  return out + "]}";
}

/// Appends a chunk header (sec. 4.4.3): its length padded to 4 bytes, and its type.
void append_chunk_header(std::string& out, std::uint32_t type, std::size_t size) {
  glb::append_u32(out, static_cast<std::uint32_t>((size + 3) / 4 * 4));
  glb::append_u32(out, type);
}

/// The GLB of `arrays`: its triangles in `runs`, written once into the returned string.
std::string pack_glb(const DisplayArrays& arrays, std::vector<IndexRun> runs) {
  std::uint64_t index_bytes = 0;
  for (IndexRun& run : runs) {
    run.byte_offset = index_bytes;
    index_bytes += (std::uint64_t(run.triangles) * 3 * (run.wide ? 4 : 2) + 3) / 4 * 4;
  }
  // The container's lengths are uint32 (sec. 4.4.2): the whole file must stay below 4 GiB.
  const std::uint64_t positions = 4 * std::uint64_t(arrays.positions.size());
  const std::uint64_t bin_size = runs.empty() ? 0 : positions + index_bytes;
  if (bin_size > 0xF0000000ull)
    throw InvalidInput("write_mesh: the mesh is too large for a GLB file (" + std::to_string(bin_size) +
                       " bytes of data; the format holds less than 4 GiB)");
  const std::string json = gltf_json(arrays, runs, index_bytes);
  const std::size_t json_padded = (json.size() + 3) / 4 * 4;
  std::string out;
  out.reserve(glb::kHeaderSize + 2 * glb::kChunkHeaderSize + json_padded + bin_size);
  glb::append_u32(out, glb::kMagic);
  glb::append_u32(out, glb::kVersion);
  glb::append_u32(out, 0);  // the total length, set below
  append_chunk_header(out, glb::kJsonChunk, json.size());
  out += json;
  out.append(json_padded - json.size(), ' ');
  if (bin_size != 0) {
    append_chunk_header(out, glb::kBinChunk, bin_size);
    const std::size_t bin = out.size();
    out.resize(bin + bin_size);  // (zero-filled: the runs' padding)
    char* data = out.data() + bin;
    std::memcpy(data, arrays.positions.data(), positions);
    for (const IndexRun& run : runs) {
      char* at = data + positions + run.byte_offset;
      const std::uint32_t* index = arrays.indices.data() + 3 * run.first;
      const std::size_t n = 3 * run.triangles;
      if (run.wide) {
        std::memcpy(at, index, 4 * n);
      } else {
        for (std::size_t i = 0; i < n; ++i) {
          const auto x = static_cast<std::uint16_t>(index[i] - run.base);
          std::memcpy(at + 2 * i, &x, 2);
        }
      }
    }
  }
  const auto length = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data() + 8, &length, 4);
  return out;
}

}  // namespace

DisplayArrays triangle_arrays(const PolygonMesh& mesh) {
  DisplayArrays out;
  out.positions.resize(3 * mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (std::size_t k = 0; k < 3; ++k) {
      const double x = mesh.vertices[v][Eigen::Index(k)];
      if (!(std::fabs(x) <= double(std::numeric_limits<float>::max())))
        throw InvalidInput("write_mesh: vertex " + std::to_string(v) + " is beyond the float32 range of glTF");
      out.positions[3 * v + k] = static_cast<float>(x);
    }
  std::size_t corners = 0;
  for (const auto& face : mesh.faces) corners += 3 * (face.size() - std::min<std::size_t>(face.size(), 2));
  out.indices.reserve(corners);
  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> triangles;
  for (const auto& face : mesh.faces) {
    triangles.clear();
    triangulator.append(mesh.vertices, face, triangles);
    for (const IndexTriangle& t : triangles)
      for (const int i : t) out.indices.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

IndexRun whole_run(std::span<const std::uint32_t> indices) {
  return {.first = 0, .triangles = indices.size() / 3, .wide = true};
}

std::vector<IndexRun> index_runs(std::span<const std::uint32_t> indices) {
  constexpr std::uint32_t kSpan = 65535;  // the largest index offset in a run of UNSIGNED_SHORT
  std::vector<IndexRun> runs;
  const std::size_t triangles = indices.size() / 3;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t* c = indices.data() + 3 * t;
    const std::uint32_t lo = std::min({c[0], c[1], c[2]}), hi = std::max({c[0], c[1], c[2]});
    const bool wide = hi - lo > kSpan;
    if (!runs.empty()) {
      IndexRun& run = runs.back();
      if (run.wide && wide) {
        ++run.triangles;
        continue;
      }
      const std::uint32_t top = run.base + run.vertices - 1;
      if (!run.wide && !wide && std::max(top, hi) - std::min(run.base, lo) <= kSpan) {
        const std::uint32_t base = std::min(run.base, lo);
        run.vertices = std::max(top, hi) - base + 1;
        run.base = base;
        ++run.triangles;
        continue;
      }
    }
    runs.push_back(wide ? IndexRun{.first = t, .triangles = 1, .wide = true}
                        : IndexRun{.first = t, .triangles = 1, .base = lo, .vertices = hi - lo + 1});
  }
  // Without locality the runs would be many and short: one run of UNSIGNED_INT instead.
  if (runs.size() > 1 + triangles / 4096) runs = {whole_run(indices)};
  return runs;
}

std::string encode_glb(const PolygonMesh& mesh) {
  // glTF positions are float32: round as for binary STL so the file is clean as written. One
  // primitive with UNSIGNED_INT indices over every vertex: the form every reader joins into one
  // closed mesh.
  const DisplayArrays arrays =
      triangle_arrays(round_for_output(mesh, {.precision = OutputPrecision::Float32, .triangles = true}));
  if (arrays.indices.empty()) return pack_glb(arrays, {});
  return pack_glb(arrays, {whole_run(arrays.indices)});
}

std::string encode_display_glb(const DisplayArrays& arrays) { return pack_glb(arrays, index_runs(arrays.indices)); }

}  // namespace sculpt::mesh::detail
