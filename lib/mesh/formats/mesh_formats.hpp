#pragma once
/// \file mesh_formats.hpp
/// Encoders and decoders of each file format (internal to the mesh layer; mesh_io.hpp is the
/// public entry). Decoders throw IoError(name, "line N: ...") on malformed data.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh_io.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::mesh::detail {

std::string encode_off(const PolygonMesh& mesh);
std::string encode_obj(const PolygonMesh& mesh);
std::string encode_stl(const PolygonMesh& mesh, bool binary);
std::string encode_ply(const PolygonMesh& mesh, bool binary);
/// OpenMesh's .om through OpenMesh, points as doubles. \throw InvalidInput for a non-manifold face.
std::string encode_om(const PolygonMesh& mesh);
/// 3MF through lib3mf: triangulated, float32 positions, millimetres, rounded by round_for_output
/// in lib3mf's numbers (OutputPrecision::ThreeMf). \throw InvalidInput beyond float32.
std::string encode_3mf(const PolygonMesh& mesh);
/// What lib3mf 1.8 keeps of a coordinate: its writer (putFloat) prints the float32 nearest to x
/// times 10^6 in float32 arithmetic, truncated towards zero, with six decimals; its reader parses
/// that text into a float32.
double lib3mf_kept(double x);
/// Binary glTF 2.0 (.glb): one mesh of one TRIANGLES primitive, float32 positions rounded by
/// round_for_output (OutputPrecision::Float32, as binary STL), UNSIGNED_INT indices; one world unit
/// is one glTF unit (no scale node). \throw InvalidInput beyond float32 or 4 GiB.
std::string encode_glb(const PolygonMesh& mesh);
/// The same container for display (encode_glb_for_display in mesh_io.hpp), its triangles in the
/// runs of index_runs.
std::string encode_display_glb(const DisplayArrays& arrays);
/// display_arrays (mesh_io.hpp) without its checks. \throw InvalidInput beyond float32.
DisplayArrays triangle_arrays(const PolygonMesh& mesh);

/// Consecutive triangles written as one glTF primitive (sec. 3.7.2): their indices as
/// UNSIGNED_SHORT less `base` (its POSITION accessor starts at vertex `base`: sec. 3.6.2.4's
/// byteOffset), or as UNSIGNED_INT with base 0 (`wide`: its POSITION accessor covers every vertex,
/// so that the bounds glTF asks of it are found once however many wide runs there are).
struct IndexRun {
  std::size_t first = 0;          ///< the first triangle
  std::size_t triangles = 0;      ///< how many
  std::uint32_t base = 0;         ///< a 16-bit run: its POSITION accessor's first vertex
  std::uint32_t vertices = 0;     ///< and count (its indices lie in [base, base + vertices))
  bool wide = false;              ///< UNSIGNED_INT indices
  std::uint64_t byte_offset = 0;  ///< (set by the writer) where its indices start in their view
};

/// The triangles of `indices` (three a triangle) as runs, in order: a run of UNSIGNED_SHORT grows
/// while its indices span at most 65,536 vertices, so a mesh numbered in the order of first use
/// (as to_mesh numbers its vertices) costs 6 bytes of indices a triangle instead of 12; a triangle
/// whose own indices span more joins a run of UNSIGNED_INT. A mesh without such locality (more than
/// one run per 4,096 triangles) is one run of UNSIGNED_INT.
std::vector<IndexRun> index_runs(std::span<const std::uint32_t> indices);
/// All of `indices` as one run of UNSIGNED_INT (empty indices: no triangles).
IndexRun whole_run(std::span<const std::uint32_t> indices);

PolygonMesh decode_off(std::string_view data, const std::string& name);
PolygonMesh decode_obj(std::string_view data, const std::string& name);
PolygonMesh decode_stl(std::string_view data, const std::string& name);
PolygonMesh decode_ply(std::string_view data, const std::string& name);
PolygonMesh decode_om(std::string_view data, const std::string& name);
/// Every build item's mesh (its transform applied), scaled from the file's unit to millimetres.
PolygonMesh decode_3mf(std::string_view data, const std::string& name);
/// The triangles of every mesh the scene's nodes instantiate, each node's transform applied and
/// coincident positions merged; points and lines are skipped.
PolygonMesh decode_glb(std::string_view data, const std::string& name);

}  // namespace sculpt::mesh::detail
