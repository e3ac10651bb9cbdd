// STL: ASCII (full double precision text) and binary (float32 by definition, little endian).
// Facets carry their own corners; reading merges corners with exactly equal coordinates.
#include <bit>
#include <cstdint>
#include <cstring>

#include <Eigen/Geometry>

#include "mesh/formats/mesh_formats.hpp"
#include "mesh/formats/text_scanner.hpp"
#include "mesh/formats/vertex_merger.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::mesh::detail {
namespace {

static_assert(std::endian::native == std::endian::little, "binary STL/PLY code assumes little endian");

Eigen::Vector3d facet_normal(const PolygonMesh& m, const IndexTriangle& t) {
  // Edges scaled to unit size first, so that huge or tiny coordinates neither overflow nor underflow.
  Eigen::Vector3d e1 = m.vertices[t[1]] - m.vertices[t[0]];
  Eigen::Vector3d e2 = m.vertices[t[2]] - m.vertices[t[0]];
  const double s1 = e1.cwiseAbs().maxCoeff(), s2 = e2.cwiseAbs().maxCoeff();
  if (!(s1 > 0 && s2 > 0 && std::isfinite(s1) && std::isfinite(s2))) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d n = (e1 / s1).cross(e2 / s2);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

std::vector<IndexTriangle> all_triangles(const PolygonMesh& mesh) {
  std::vector<IndexTriangle> out;
  for (const auto& f : mesh.faces)
    for (const IndexTriangle& t : triangulate_polygon(mesh.vertices, f)) out.push_back(t);
  return out;
}

void put_float(std::string& out, float x) {
  char b[4];
  std::memcpy(b, &x, 4);
  out.append(b, 4);
}

PolygonMesh decode_binary(std::string_view data, const std::string& name, uint32_t count) {
  PolygonMesh mesh;
  VertexMerger merger;
  mesh.faces.reserve(count);
  for (uint32_t i = 0; i < count; ++i) {
    const char* rec = data.data() + 84 + 50 * static_cast<size_t>(i);
    std::vector<int> face;
    for (int k = 0; k < 3; ++k) {
      float c[3];
      std::memcpy(c, rec + 12 + 12 * k, 12);  // after the facet normal
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
        throw IoError(name, "binary STL triangle " + std::to_string(i) + " has a non-finite coordinate");
      face.push_back(merger.add(mesh, Eigen::Vector3d(c[0], c[1], c[2])));
    }
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

PolygonMesh decode_ascii(std::string_view data, const std::string& name) {
  TextScanner s(data, name);
  PolygonMesh mesh;
  VertexMerger merger;
  auto expect = [&](std::string_view keyword, std::string_view second = {}) {
    if (!s.next_line(0)) s.fail("file ends where '" + std::string(keyword) + "' was expected");
    if (s.tokens()[0] != keyword || (!second.empty() && (s.tokens().size() < 2 || s.tokens()[1] != second)))
      s.fail("expected '" + std::string(keyword) + (second.empty() ? "" : " ") +
             std::string(second) + "', got '" + std::string(s.tokens()[0]) + "'");
  };
  expect("solid");
  for (;;) {
    if (!s.next_line(0)) s.fail("file ends without 'endsolid'");
    if (s.tokens()[0] == "endsolid") break;
    if (s.tokens()[0] != "facet") s.fail("expected 'facet' or 'endsolid', got '" + std::string(s.tokens()[0]) + "'");
    expect("outer", "loop");
    std::vector<int> face;
    for (;;) {
      if (!s.next_line(0)) s.fail("file ends inside a facet");
      if (s.tokens()[0] == "endloop") break;
      if (s.tokens()[0] != "vertex") s.fail("expected 'vertex' or 'endloop', got '" + std::string(s.tokens()[0]) + "'");
      face.push_back(merger.add(mesh, {s.real(1, "x"), s.real(2, "y"), s.real(3, "z")}));
    }
    if (face.size() < 3) s.fail("a facet needs at least 3 vertices, got " + std::to_string(face.size()));
    expect("endfacet");
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

}  // namespace

std::string encode_stl(const PolygonMesh& given, bool binary) {
  // STL holds triangles, binary STL float32: a closed mesh is rounded so that it stays clean.
  const PolygonMesh mesh = round_for_output(
      given, {.precision = binary ? OutputPrecision::Float32 : OutputPrecision::Double, .triangles = true});
  const std::vector<IndexTriangle> tris = all_triangles(mesh);
  std::string out;
  if (binary) {
    out.reserve(84 + 50 * tris.size());
    std::string header = "sculpt binary STL (float32 coordinates)";
    header.resize(80, ' ');
    out += header;
    const auto count = static_cast<uint32_t>(tris.size());
    char b[4];
    std::memcpy(b, &count, 4);
    out.append(b, 4);
    for (const IndexTriangle& t : tris) {
      const Eigen::Vector3d n = facet_normal(mesh, t);
      for (int k = 0; k < 3; ++k) put_float(out, static_cast<float>(n[k]));
      for (int v : t)
        for (int k = 0; k < 3; ++k) put_float(out, static_cast<float>(mesh.vertices[v][k]));
      out.append(2, '\0');  // attribute byte count
    }
    return out;
  }
  out = "solid sculpt\n";
  for (const IndexTriangle& t : tris) {
    const Eigen::Vector3d n = facet_normal(mesh, t);
    out += "facet normal ";
    for (int k = 0; k < 3; ++k) {
      append_number(out, n[k]);
      out += k < 2 ? ' ' : '\n';
    }
    out += "outer loop\n";
    for (int v : t) {
      out += "vertex ";
      for (int k = 0; k < 3; ++k) {
        append_number(out, mesh.vertices[v][k]);
        out += k < 2 ? ' ' : '\n';
      }
    }
    out += "endloop\nendfacet\n";
  }
  out += "endsolid sculpt\n";
  return out;
}

PolygonMesh decode_stl(std::string_view data, const std::string& name) {
  // Binary when the size matches the triangle count exactly (some binary headers start
  // with "solid" too); otherwise ASCII if it starts with "solid".
  if (data.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, 4);
    if (data.size() == 84 + 50 * static_cast<uint64_t>(count)) return decode_binary(data, name, count);
  }
  const size_t first = data.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && data.substr(first, 5) == "solid") return decode_ascii(data, name);
  if (data.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, 4);
    throw IoError(name, "binary STL announces " + std::to_string(count) + " triangles (" +
                            std::to_string(84 + 50 * static_cast<uint64_t>(count)) +
                            " bytes) but the file has " + std::to_string(data.size()) + " bytes");
  }
  throw IoError(name, "not an STL file (no 'solid' header, too short for binary STL)");
}

}  // namespace sculpt::mesh::detail
