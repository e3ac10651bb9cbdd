// OFF (Geomview) and Wavefront OBJ: plain text, vertices written as shortest round-trip doubles.
#include <limits>
#include <string>

#include "mesh/formats/mesh_formats.hpp"
#include "mesh/formats/text_scanner.hpp"

namespace sculpt::mesh::detail {
namespace {

void append_point(std::string& out, const Eigen::Vector3d& p) {
  append_number(out, p.x());
  out += ' ';
  append_number(out, p.y());
  out += ' ';
  append_number(out, p.z());
}

int checked_index(const TextScanner& s, long long index, size_t vertex_count) {
  if (index < 0 || index >= static_cast<long long>(vertex_count))
    s.fail("vertex index " + std::to_string(index) + " out of range (" +
           std::to_string(vertex_count) + " vertices)");
  return static_cast<int>(index);
}

}  // namespace

std::string encode_off(const PolygonMesh& mesh) {
  std::string out = "OFF\n";
  append_number(out, static_cast<long long>(mesh.vertices.size()));
  out += ' ';
  append_number(out, static_cast<long long>(mesh.faces.size()));
  out += " 0\n";
  for (const auto& p : mesh.vertices) {
    append_point(out, p);
    out += '\n';
  }
  for (const auto& f : mesh.faces) append_face_line(out, f);
  return out;
}

PolygonMesh decode_off(std::string_view data, const std::string& name) {
  TextScanner s(data, name);
  if (!s.next_line()) s.fail("empty file, expected the OFF header");
  std::string_view head = s.tokens()[0];
  // OFF, COFF, NOFF, CNOFF, STOFF...: the first three numbers of a vertex line are x y z.
  if (head.size() < 3 || head.substr(head.size() - 3) != "OFF" || head.find('4') != head.npos ||
      head.find('n') != head.npos)
    s.fail("expected the header 'OFF', got '" + std::string(head) + "'");
  size_t first = 1;
  if (s.tokens().size() > 1 && s.tokens()[1] == "BINARY") s.fail("binary OFF is not supported");
  if (s.tokens().size() == 1) {
    if (!s.next_line()) s.fail("missing the vertex and face counts");
    first = 0;
  }
  const long long nv = s.integer(first, "vertex count");
  const long long nf = s.integer(first + 1, "face count");
  if (nv < 0 || nf < 0) s.fail("negative vertex or face count");
  PolygonMesh mesh;
  // Each vertex and face takes at least 2 bytes of text: never reserve beyond that.
  mesh.vertices.reserve(static_cast<size_t>(std::min<long long>(nv, data.size() / 2)));
  mesh.faces.reserve(static_cast<size_t>(std::min<long long>(nf, data.size() / 2)));
  for (long long i = 0; i < nv; ++i) {
    if (!s.next_line())
      s.fail("file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    mesh.vertices.emplace_back(s.real(0, "x"), s.real(1, "y"), s.real(2, "z"));
  }
  for (long long i = 0; i < nf; ++i) {
    if (!s.next_line())
      s.fail("file ends after " + std::to_string(i) + " of " + std::to_string(nf) + " faces");
    const long long n = s.integer(0, "face corner count");
    if (n < 3) s.fail("a face needs at least 3 corners, got " + std::to_string(n));
    if (static_cast<size_t>(n) + 1 > s.tokens().size())
      s.fail("face announces " + std::to_string(n) + " corners but lists " +
             std::to_string(s.tokens().size() - 1));
    std::vector<int> face;
    face.reserve(static_cast<size_t>(n));
    for (long long k = 0; k < n; ++k)
      face.push_back(checked_index(s, s.integer(static_cast<size_t>(k + 1), "vertex index"),
                                   mesh.vertices.size()));
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

std::string encode_obj(const PolygonMesh& mesh) {
  std::string out = "# sculpt\n";
  for (const auto& p : mesh.vertices) {
    out += "v ";
    append_point(out, p);
    out += '\n';
  }
  for (const auto& f : mesh.faces) {
    out += 'f';
    for (int v : f) {
      out += ' ';
      append_number(out, static_cast<long long>(v) + 1);
    }
    out += '\n';
  }
  return out;
}

PolygonMesh decode_obj(std::string_view data, const std::string& name) {
  TextScanner s(data, name);
  PolygonMesh mesh;
  std::vector<int> face_lines;  // indices may refer to vertices listed later: checked at the end
  while (s.next_line()) {
    const auto& t = s.tokens();
    if (t[0] == "v") {
      Eigen::Vector3d p(s.real(1, "x"), s.real(2, "y"), s.real(3, "z"));
      if (t.size() > 4) {  // homogeneous coordinate w
        const double w = s.real(4, "w");
        if (w == 0) s.fail("vertex with w = 0");
        if (w != 1) p /= w;
      }
      mesh.vertices.push_back(p);
    } else if (t[0] == "f") {
      if (t.size() < 4) s.fail("a face needs at least 3 corners");
      std::vector<int> face;
      for (size_t k = 1; k < t.size(); ++k) {
        // "v", "v/vt", "v//vn" or "v/vt/vn": the vertex index comes first; negative counts back.
        const std::string_view corner = t[k].substr(0, t[k].find('/'));
        const long long index = s.parse_integer(corner, "vertex index");
        if (index == 0) s.fail("vertex index 0 (OBJ indices start at 1)");
        const long long n = static_cast<long long>(mesh.vertices.size());
        const long long resolved = index > 0 ? index - 1 : n + index;
        if (resolved < 0 || resolved > std::numeric_limits<int>::max())
          s.fail("vertex index " + std::string(corner) + " out of range");
        face.push_back(static_cast<int>(resolved));
      }
      mesh.faces.push_back(std::move(face));
      face_lines.push_back(s.line());
    }
    // Other statements (vt, vn, g, o, s, usemtl, mtllib, l, ...) carry nothing for solids.
  }
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi)
    for (int v : mesh.faces[fi])
      if (static_cast<size_t>(v) >= mesh.vertices.size())
        s.fail_at(face_lines[fi], "vertex index " + std::to_string(v + 1) + " out of range (" +
                                      std::to_string(mesh.vertices.size()) + " vertices)");
  return mesh;
}

}  // namespace sculpt::mesh::detail
