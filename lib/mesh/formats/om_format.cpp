// OpenMesh's own binary format (.om), written and read by OpenMesh itself with a double-precision
// point type, so positions are stored as IEEE binary64 and nothing is narrowed (the project's
// decision: OpenMesh writes .om; tests/mesh/mesh_io_test.cpp checks a bit-exact round trip).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <iostream>
#include <sstream>

#include "base/errors.hpp"
#include "mesh/formats/mesh_formats.hpp"

namespace sculpt::mesh::detail {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

/// OpenMesh logs to standard output and error ("#bytes written", "complex vertex"); the mesh
/// layer prints nothing, so its streams are switched off once (thread-safe static).
void quiet_openmesh() {
  static const bool quiet = [] {
    omlog().disable();
    omout().disable();
    omerr().disable();
    return true;
  }();
  (void)quiet;
}

}  // namespace

std::string encode_om(const PolygonMesh& mesh) {
  quiet_openmesh();
  OmMesh om;
  std::vector<OmMesh::VertexHandle> handles;
  handles.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& p : mesh.vertices) handles.push_back(om.add_vertex(OmMesh::Point(p.x(), p.y(), p.z())));
  std::vector<OmMesh::VertexHandle> corners;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    corners.clear();
    for (int v : mesh.faces[f]) corners.push_back(handles[static_cast<std::size_t>(v)]);
    // OpenMesh's half-edge structure refuses a face that would make the surface non-manifold:
    // say so rather than write a file with a face missing.
    if (!om.add_face(corners).is_valid())
      throw InvalidInput("write_mesh: OpenMesh's .om format cannot hold face " + std::to_string(f) +
                         " (the mesh is not a manifold there)");
  }
  std::ostringstream out(std::ios::binary);
  bool written = false;
  {
    // OpenMesh's .om writer reports "#bytes written" on std::clog; keep it off the user's terminal
    // (the library is used from one thread at a time: the interpreter's).
    std::ostringstream log;
    std::streambuf* const previous = std::clog.rdbuf(log.rdbuf());
    try {
      written = OpenMesh::IO::write_mesh(om, out, ".om", OpenMesh::IO::Options::Binary);
    } catch (...) {
      std::clog.rdbuf(previous);
      throw;
    }
    std::clog.rdbuf(previous);
  }
  if (!written) throw InvalidInput("write_mesh: OpenMesh could not encode the mesh as .om");
  return std::move(out).str();
}

PolygonMesh decode_om(std::string_view data, const std::string& name) {
  quiet_openmesh();
  // OpenMesh reads whatever it is given as .om; check its magic number first ("OM").
  if (data.size() < 2 || data[0] != 'O' || data[1] != 'M') throw IoError(name, "not an OpenMesh .om file (no 'OM' magic)");
  OmMesh om;
  std::istringstream in(std::string(data), std::ios::binary);
  OpenMesh::IO::Options options = OpenMesh::IO::Options::Binary;
  if (!OpenMesh::IO::read_mesh(om, in, ".om", options)) throw IoError(name, "OpenMesh could not read it as an .om file");
  PolygonMesh mesh;
  mesh.vertices.reserve(om.n_vertices());
  for (const auto v : om.vertices()) {
    const OmMesh::Point& p = om.point(v);
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  mesh.faces.reserve(om.n_faces());
  for (const auto f : om.faces()) {
    std::vector<int> face;
    for (const auto v : om.fv_range(f)) face.push_back(v.idx());
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

}  // namespace sculpt::mesh::detail
