#pragma once
/// \file mesh_io.hpp
/// Reading and writing polygon meshes as OFF, OBJ, STL (ASCII and binary), PLY (ASCII and
/// binary), OpenMesh's .om (written and read by OpenMesh itself, points as doubles), 3MF
/// (through lib3mf: triangles, float32 positions, millimetres) and binary glTF 2.0 (.glb:
/// triangles, float32 positions, one world unit per glTF unit). Text formats and binary PLY carry
/// doubles exactly (shortest round-trip decimal text, IEEE binary64); binary STL, 3MF and GLB carry
/// float32. Writes are atomic: the
/// data goes to a temporary file in the target directory that is renamed over the target
/// only when complete. Nothing is printed. Precision per format: docs/mesh_io.md.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

enum class MeshFormat { Auto, Off, Obj, Stl, Ply, Om, ThreeMf, Glb };

/// Format named by the extension (.off, .obj, .stl, .ply, .om, .3mf, .glb; any case).
/// \throw IoError naming the path if the extension is none of these.
MeshFormat mesh_format_from_path(const std::filesystem::path& path);

struct WriteOptions {
  MeshFormat format = MeshFormat::Auto;  ///< Auto: from the extension
  bool binary = false;                   ///< STL and PLY only: binary encoding
};

struct ReadOptions {
  MeshFormat format = MeshFormat::Auto;  ///< Auto: from the extension (STL: ASCII or binary detected)
};

/// Writes `mesh` to `path` atomically (temporary file + rename; on failure the previous file
/// is untouched and the temporary removed). STL, 3MF and GLB get triangulated faces (triangulate.hpp).
/// \throw InvalidInput if a face index is out of range or a coordinate is not finite.
/// \throw IoError naming the path and what failed.
void write_mesh(const PolygonMesh& mesh, const std::filesystem::path& path, WriteOptions options = {});

/// Reads a mesh. STL's per-facet vertices and GLB's positions (after the nodes' transforms) are
/// merged when their coordinates are exactly equal (0 and -0 count as equal); no other merging or
/// repair happens.
/// \throw IoError naming the path and, for text formats, the line of the first problem.
PolygonMesh read_mesh(const std::filesystem::path& path, ReadOptions options = {});

/// Writes `data` to `path` the way write_mesh does: a temporary file in the target's directory,
/// flushed and renamed over the target, so readers see the old file or the complete new one.
/// \throw IoError naming the path and what failed (the previous file is left as it was).
void write_file_atomically(const std::filesystem::path& path, std::string_view data);

/// The bytes write_mesh would write (format must not be Auto).
std::string encode_mesh(const PolygonMesh& mesh, MeshFormat format, bool binary = false);

/// A mesh as a screen draws it (the live view), not as a file holds it: each vertex converted to
/// float32 as it is, in the mesh's order, and each face triangulated in order, without the output
/// rounding that keeps a written GLB clean (docs/kernel.md, "Clean output"): a picture does not
/// need it, and for a million faces it takes seconds.
struct DisplayArrays {
  std::vector<float> positions;        ///< x, y, z of vertex i at 3i
  std::vector<std::uint32_t> indices;  ///< three a triangle
};

/// \throw InvalidInput as encode_mesh for a GLB.
DisplayArrays display_arrays(const PolygonMesh& mesh);

/// The bytes of a GLB of `arrays` for a screen: the GLB's vertex i is the mesh's vertex i (one
/// bufferView of every position), its triangles in their order, as primitives of 16-bit indices
/// over windows of 65,536 vertices where the mesh's numbering allows (6 bytes a triangle instead
/// of 12; docs/viewing.md), else of 32-bit ones.
std::string encode_glb_for_display(const DisplayArrays& arrays);
/// encode_glb_for_display(display_arrays(mesh)). \throw InvalidInput as encode_mesh.
std::string encode_glb_for_display(const PolygonMesh& mesh);

/// Parses bytes as read_mesh would; `name` stands for the path in error messages.
PolygonMesh decode_mesh(std::string_view data, MeshFormat format, const std::string& name);

}  // namespace sculpt
