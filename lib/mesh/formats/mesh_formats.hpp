#pragma once
/// \file mesh_formats.hpp
/// Encoders and decoders of each file format (internal to the mesh layer; mesh_io.hpp is the
/// public entry). Decoders throw IoError(name, "line N: ...") on malformed data.

#include <string>
#include <string_view>

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
/// The same container for display (encode_glb_for_display in mesh_io.hpp): the vertices converted
/// to float32 one by one, in their order, without output rounding.
std::string encode_glb_unrounded(const PolygonMesh& mesh);

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
