// PLY (Turk 1994): ASCII or binary (either byte order) on input; written with double
// coordinates, as ASCII text (shortest round-trip) or binary little endian.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>

#include "mesh/formats/mesh_formats.hpp"
#include "mesh/formats/text_scanner.hpp"

namespace sculpt::mesh::detail {
namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
  std::string name;
  bool is_list = false;
  Scalar count_type = Scalar::UInt8;  // lists only
  Scalar type = Scalar::Float32;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

bool scalar_from_name(std::string_view n, Scalar& out) {
  static const std::array<std::pair<std::string_view, Scalar>, 16> names = {{
      {"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
      {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
      {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
      {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
      {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
      {"float64", Scalar::Float64},
  }};
  for (auto [name, s] : names)
    if (n == name) {
      out = s;
      return true;
    }
  return false;
}

size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::Int8: case Scalar::UInt8: return 1;
    case Scalar::Int16: case Scalar::UInt16: return 2;
    case Scalar::Int32: case Scalar::UInt32: case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 8;
}

/// Reads values of the body, ASCII tokens or binary, with positions for messages.
class BodyReader {
 public:
  BodyReader(std::string_view data, size_t start, int header_lines, bool ascii, bool swap,
             const std::string& name)
      : text_(data.substr(start), name), bin_(data.substr(start)), ascii_(ascii), swap_(swap),
        name_(name), header_lines_(header_lines) {}

  double read(Scalar type, const char* what) {
    if (ascii_) {
      while (token_ >= text_.tokens().size()) {
        if (!text_.next_line(0)) fail(std::string("data ends where ") + what + " was expected");
        token_ = 0;
      }
      const double v = text_.real(token_++, what);
      return v;
    }
    const size_t n = scalar_size(type);
    if (pos_ + n > bin_.size()) fail(std::string("data ends where ") + what + " was expected");
    unsigned char b[8];
    std::memcpy(b, bin_.data() + pos_, n);
    if (swap_) std::reverse(b, b + n);
    pos_ += n;
    switch (type) {
      case Scalar::Int8: { int8_t v; std::memcpy(&v, b, 1); return v; }
      case Scalar::UInt8: return b[0];
      case Scalar::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
      case Scalar::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Scalar::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
      case Scalar::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Scalar::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case Scalar::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }

  [[noreturn]] void fail(const std::string& message) const {
    if (ascii_) throw IoError(name_, "line " + std::to_string(header_lines_ + text_.line()) + ": " + message);
    throw IoError(name_, "byte " + std::to_string(pos_) + " after the header: " + message);
  }

  [[nodiscard]] size_t bytes_left() const { return ascii_ ? text_.offset() : bin_.size() - pos_; }

 private:
  TextScanner text_;
  std::string_view bin_;
  bool ascii_;
  bool swap_;
  std::string name_;
  int header_lines_;
  size_t token_ = 0;
  size_t pos_ = 0;
};

long long as_index(BodyReader& body, double v, const char* what) {
  if (v != std::floor(v) || v < 0 || v > std::numeric_limits<int>::max())
    body.fail(std::string(what) + " is not a valid index or count");
  return static_cast<long long>(v);
}

template <typename T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace

std::string encode_ply(const PolygonMesh& mesh, bool binary) {
  size_t max_corners = 0;
  for (const auto& f : mesh.faces) max_corners = std::max(max_corners, f.size());
  const bool wide = max_corners > 255;
  std::string out = "ply\nformat ";
  out += binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  out += "comment sculpt: double coordinates\nelement vertex ";
  append_number(out, static_cast<long long>(mesh.vertices.size()));
  out += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  append_number(out, static_cast<long long>(mesh.faces.size()));
  out += wide ? "\nproperty list uint int vertex_indices\n" : "\nproperty list uchar int vertex_indices\n";
  out += "end_header\n";
  for (const auto& p : mesh.vertices) {
    for (int k = 0; k < 3; ++k) {
      if (binary) {
        put(out, p[k]);
      } else {
        append_number(out, p[k]);
        out += k < 2 ? ' ' : '\n';
      }
    }
  }
  for (const auto& f : mesh.faces) {
    if (binary) {
      if (wide) put(out, static_cast<uint32_t>(f.size()));
      else put(out, static_cast<uint8_t>(f.size()));
      for (int v : f) put(out, static_cast<int32_t>(v));
    } else {
      append_face_line(out, f);
    }
  }
  return out;
}

PolygonMesh decode_ply(std::string_view data, const std::string& name) {
  TextScanner h(data, name);
  if (!h.next_line(0) || h.tokens()[0] != "ply") h.fail("not a PLY file (no 'ply' magic)");
  bool ascii = true, swap = false, have_format = false;
  std::vector<Element> elements;
  for (;;) {
    if (!h.next_line(0)) h.fail("header ends without 'end_header'");
    const auto& t = h.tokens();
    if (t[0] == "end_header") break;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() < 2) h.fail("format without a name");
      have_format = true;
      if (t[1] == "ascii") ascii = true;
      else if (t[1] == "binary_little_endian") ascii = false, swap = false;
      else if (t[1] == "binary_big_endian") ascii = false, swap = true;
      else h.fail("unknown format '" + std::string(t[1]) + "'");
    } else if (t[0] == "element") {
      if (t.size() < 3) h.fail("element needs a name and a count");
      const long long count = h.integer(2, "element count");
      if (count < 0) h.fail("negative element count");
      elements.push_back({std::string(t[1]), count, {}});
    } else if (t[0] == "property") {
      if (elements.empty()) h.fail("property before any element");
      Property p;
      if (t.size() >= 5 && t[1] == "list") {
        p.is_list = true;
        if (!scalar_from_name(t[2], p.count_type) || !scalar_from_name(t[3], p.type))
          h.fail("unknown list types '" + std::string(t[2]) + " " + std::string(t[3]) + "'");
        p.name = t[4];
      } else if (t.size() >= 3) {
        if (!scalar_from_name(t[1], p.type)) h.fail("unknown type '" + std::string(t[1]) + "'");
        p.name = t[2];
      } else {
        h.fail("property needs a type and a name");
      }
      elements.back().properties.push_back(p);
    } else {
      h.fail("unexpected header line '" + std::string(t[0]) + "'");
    }
  }
  if (!have_format) h.fail("header has no 'format' line");

  BodyReader body(data, h.offset(), h.line(), ascii, swap, name);
  PolygonMesh mesh;
  bool have_vertices = false;
  for (const Element& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int axis_of[64];
    std::fill(std::begin(axis_of), std::end(axis_of), -1);
    int index_list = -1;
    if (is_vertex) {
      have_vertices = true;
      for (size_t i = 0; i < e.properties.size() && i < 64; ++i)
        for (int k = 0; k < 3; ++k)
          if (!e.properties[i].is_list && e.properties[i].name == std::string(1, char('x' + k))) axis_of[i] = k;
      for (int k = 0; k < 3; ++k)
        if (std::find(std::begin(axis_of), std::end(axis_of), k) == std::end(axis_of))
          h.fail(std::string("element vertex has no property ") + char('x' + k));
      // Each vertex takes at least 3 bytes (3 values): never reserve beyond the data.
      mesh.vertices.reserve(static_cast<size_t>(std::min<long long>(e.count, body.bytes_left() / 3 + 1)));
    }
    if (is_face) {
      for (size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].is_list &&
            (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
          index_list = static_cast<int>(i);
      if (index_list < 0) h.fail("element face has no list property vertex_indices");
    }
    for (long long item = 0; item < e.count; ++item) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& prop = e.properties[i];
        if (prop.is_list) {
          const long long n = as_index(body, body.read(prop.count_type, "a list length"), "list length");
          std::vector<int> face;
          for (long long k = 0; k < n; ++k) {
            const double v = body.read(prop.type, "a list entry");
            if (static_cast<int>(i) == index_list) face.push_back(static_cast<int>(as_index(body, v, "vertex index")));
          }
          if (static_cast<int>(i) == index_list) {
            if (face.size() < 3) body.fail("face " + std::to_string(item) + " has fewer than 3 corners");
            mesh.faces.push_back(std::move(face));
          }
        } else {
          const double v = body.read(prop.type, "a value");
          if (is_vertex && i < 64 && axis_of[i] >= 0) {
            if (!std::isfinite(v)) body.fail("vertex " + std::to_string(item) + " has a non-finite coordinate");
            p[axis_of[i]] = v;
          }
        }
      }
      if (is_vertex) mesh.vertices.push_back(p);
    }
  }
  if (!have_vertices) h.fail("no element vertex in the header");
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi)
    for (int v : mesh.faces[fi])
      if (static_cast<size_t>(v) >= mesh.vertices.size())
        throw IoError(name, "face " + std::to_string(fi) + " refers to vertex " + std::to_string(v) +
                                " but there are " + std::to_string(mesh.vertices.size()) + " vertices");
  return mesh;
}

}  // namespace sculpt::mesh::detail
