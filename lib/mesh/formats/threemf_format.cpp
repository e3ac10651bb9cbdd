// 3MF (3D Manufacturing Format, the format slicers prefer) through lib3mf 1.8, Debian's
// lib3mf-dev (BSD-2-clause), with its plain C interface (NMR_DLLInterfaces.h). A 3MF file is a
// zip package whose model is XML; lib3mf keeps vertex positions as float32 (MODELMESHVERTEX) and
// writes them as decimal text with six decimals (truncated, after a float32 product by 10^6), so a
// coordinate comes back within 1e-6 plus float32 roundings of it (tests/mesh/mesh_io_test.cpp
// checks each one against a model of exactly that, docs/mesh_io.md). The unit is
// the millimetre: one world unit is written as 1 mm, and a file in another unit is scaled to
// millimetres when read. Faces are triangulated (3MF holds triangles only). The package's UUIDs
// come from the mesh's data, so the same mesh gives the same bytes.
#include "mesh/formats/lib3mf_loader.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "mesh/formats/mesh_formats.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt::mesh::detail {
namespace {

/// Releases a lib3mf object when it goes out of scope.
class Handle {
 public:
  Handle() = default;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (p_) lib3mf().release(p_);
  }
  /// Where lib3mf writes the object it creates (a PLib3MF...** argument; its instances are
  /// PLib3MF...* = void**).
  void*** out() { return &p_; }
  [[nodiscard]] void** get() const { return p_; }

 private:
  void** p_ = nullptr;
};

/// The text lib3mf gives for its last error on `instance`.
std::string last_error(void** instance) {
  DWORD code = 0;
  LPCSTR message = nullptr;
  if (instance && lib3mf().getlasterror(instance, &code, &message) == LIB3MF_OK && message)
    return std::string(message) + " (lib3mf error " + std::to_string(code) + ")";
  return "lib3mf reported an error";
}

constexpr double kLargest = 1e12;  ///< |coordinate| lib3mf 1.8 can write (x * 10^6 < 2^63)

/// Millimetres per unit of the 3MF unit enumeration (eModelUnit).
double millimetres(DWORD unit) {
  switch (unit) {
    case NMR::MODELUNIT_MICROMETER:
      return 0.001;
    case NMR::MODELUNIT_MILLIMETER:
      return 1.0;
    case NMR::MODELUNIT_CENTIMETER:
      return 10.0;
    case NMR::MODELUNIT_INCH:
      return 25.4;
    case NMR::MODELUNIT_FOOT:
      return 304.8;
    case NMR::MODELUNIT_METER:
      return 1000.0;
    default:
      return 0;
  }
}

/// A UUID made from the mesh's data and a role (object, build, item), so that the same mesh gives
/// the same bytes (lib3mf would draw random ones): FNV-1a over the data, with the version 4 and
/// variant bits set as a random UUID's.
std::string content_uuid(const std::vector<NMR::MODELMESHVERTEX>& vertices,
                         const std::vector<NMR::MODELMESHTRIANGLE>& triangles, int role) {
  std::uint64_t h[2] = {0xcbf29ce484222325ull ^ std::uint64_t(role), 0x84222325cbf29ce4ull + std::uint64_t(role)};
  auto mix = [&](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
      for (std::uint64_t& x : h) x = (x ^ bytes[i]) * 0x100000001b3ull;
    h[1] = (h[1] ^ (h[0] >> 29)) * 0x100000001b3ull;
  };
  mix(vertices.data(), vertices.size() * sizeof(NMR::MODELMESHVERTEX));
  mix(triangles.data(), triangles.size() * sizeof(NMR::MODELMESHTRIANGLE));
  h[0] = (h[0] & ~0xf000ull) | 0x4000ull;        // version 4
  h[1] = (h[1] & ~(3ull << 62)) | (2ull << 62);  // variant 10
  char text[40];
  std::snprintf(text, sizeof text, "%08llx-%04llx-%04llx-%04llx-%012llx", (unsigned long long)(h[0] >> 32),
                (unsigned long long)((h[0] >> 16) & 0xffff), (unsigned long long)(h[0] & 0xffff),
                (unsigned long long)(h[1] >> 48), (unsigned long long)(h[1] & 0xffffffffffffull));
  return text;
}

}  // namespace

double lib3mf_kept(double x) {
  if (!(std::fabs(x) <= kLargest)) return x;  // beyond what lib3mf writes (refused by encode_3mf)
  const float f = static_cast<float>(x);
  const auto n = static_cast<std::int64_t>(f * 1000000.0f);
  const std::int64_t a = n < 0 ? -n : n;
  char text[64];
  std::snprintf(text, sizeof text, "%s%lld.%06lld", f < 0 && a != 0 ? "-" : "", static_cast<long long>(a / 1000000),
                static_cast<long long>(a % 1000000));
  return static_cast<double>(std::strtof(text, nullptr));
}

std::string encode_3mf(const PolygonMesh& given) {
  // Rounded to what lib3mf keeps (positions that it writes and reads back unchanged), so that the
  // file is clean as written: 3MF holds triangles (output_rounding.hpp).
  for (std::size_t v = 0; v < given.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k)
      // lib3mf writes x * 10^6 through a 64-bit integer (six decimals): keep well inside that.
      if (!(std::fabs(given.vertices[v][k]) <= kLargest))
        throw InvalidInput("write_mesh: vertex " + std::to_string(v) +
                           " is beyond the range lib3mf writes in 3MF (|x| <= 1e12)");
  const PolygonMesh mesh = round_for_output(given, {.precision = OutputPrecision::ThreeMf, .triangles = true});
  auto fail = [](void** instance, const std::string& what) {
    throw InvalidInput("write_mesh: lib3mf could not " + what + ": " + last_error(instance));
  };
  std::vector<NMR::MODELMESHVERTEX> vertices(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      vertices[v].m_fPosition[k] = static_cast<float>(mesh.vertices[v][k]);
    }
  std::vector<NMR::MODELMESHTRIANGLE> triangles;
  for (const auto& face : mesh.faces)
    for (const IndexTriangle& t : triangulate_polygon(mesh.vertices, face))
      triangles.push_back({{DWORD(t[0]), DWORD(t[1]), DWORD(t[2])}});
  Handle model, object, item, writer;
  if (lib3mf().createmodel(model.out()) != LIB3MF_OK) throw InvalidInput("write_mesh: lib3mf could not create a model");
  if (lib3mf().model_setunit(model.get(), NMR::MODELUNIT_MILLIMETER) != LIB3MF_OK) fail(model.get(), "set the unit");
  if (lib3mf().model_addmeshobject(model.get(), object.out()) != LIB3MF_OK) fail(model.get(), "add a mesh object");
  if (lib3mf().meshobject_setgeometry(object.get(), vertices.data(), DWORD(vertices.size()), triangles.data(),
                                      DWORD(triangles.size())) != LIB3MF_OK)
    fail(object.get(), "set the mesh");
  if (lib3mf().model_addbuilditem(model.get(), object.get(), nullptr, item.out()) != LIB3MF_OK)
    fail(model.get(), "add a build item");
  if (lib3mf().object_setuuidutf8(object.get(), content_uuid(vertices, triangles, 1).c_str()) != LIB3MF_OK ||
      lib3mf().model_setbuilduuidutf8(model.get(), content_uuid(vertices, triangles, 2).c_str()) != LIB3MF_OK ||
      lib3mf().builditem_setuuidutf8(item.get(), content_uuid(vertices, triangles, 3).c_str()) != LIB3MF_OK)
    fail(model.get(), "set the UUIDs");
  if (lib3mf().model_querywriter(model.get(), "3mf", writer.out()) != LIB3MF_OK) fail(model.get(), "make a writer");
  ULONG64 size = 0;
  if (lib3mf().writer_getstreamsize(writer.get(), &size) != LIB3MF_OK) fail(writer.get(), "size the package");
  std::string data(std::size_t(size), '\0');
  if (lib3mf().writer_writetobuffer(writer.get(), reinterpret_cast<BYTE*>(data.data()), size) != LIB3MF_OK)
    fail(writer.get(), "write the package");
  return data;
}

PolygonMesh decode_3mf(std::string_view data, const std::string& name) {
  // A 3MF package is a zip archive ("PK"); lib3mf is given nothing else.
  if (data.size() < 4 || data[0] != 'P' || data[1] != 'K') throw IoError(name, "not a 3MF file (not a zip package)");
  Handle model, reader, items;
  if (lib3mf().createmodel(model.out()) != LIB3MF_OK) throw IoError(name, "lib3mf could not create a model");
  if (lib3mf().model_queryreader(model.get(), "3mf", reader.out()) != LIB3MF_OK)
    throw IoError(name, "lib3mf could not make a reader: " + last_error(model.get()));
  std::string copy(data);  // lib3mf takes a non-const buffer
  if (lib3mf().reader_readfrombuffer(reader.get(), reinterpret_cast<BYTE*>(copy.data()), copy.size()) != LIB3MF_OK)
    throw IoError(name, "lib3mf could not read it as 3MF: " + last_error(reader.get()));
  DWORD unit = NMR::MODELUNIT_MILLIMETER;
  if (lib3mf().model_getunit(model.get(), &unit) != LIB3MF_OK || millimetres(unit) == 0)
    throw IoError(name, "unknown 3MF unit");
  const double scale = millimetres(unit);
  // Every build item's mesh, with the item's transform (x' = F[r][0..2] . x + F[r][3]) applied.
  PolygonMesh mesh;
  if (lib3mf().model_getbuilditems(model.get(), items.out()) != LIB3MF_OK)
    throw IoError(name, "lib3mf could not list the build items: " + last_error(model.get()));
  for (;;) {
    BOOL more = false;
    if (lib3mf().builditemiterator_movenext(items.get(), &more) != LIB3MF_OK || !more) break;
    Handle item, object;
    if (lib3mf().builditemiterator_getcurrent(items.get(), item.out()) != LIB3MF_OK ||
        lib3mf().builditem_getobjectresource(item.get(), object.out()) != LIB3MF_OK)
      throw IoError(name, "lib3mf could not read a build item: " + last_error(items.get()));
    BOOL is_mesh = false;
    if (lib3mf().object_ismeshobject(object.get(), &is_mesh) != LIB3MF_OK || !is_mesh)
      throw IoError(name, "a build item is not a mesh object (3MF components are not read)");
    NMR::MODELTRANSFORM f{};
    BOOL has_transform = false;
    if (lib3mf().builditem_hasobjecttransform(item.get(), &has_transform) == LIB3MF_OK && has_transform &&
        lib3mf().builditem_getobjecttransform(item.get(), &f) != LIB3MF_OK)
      throw IoError(name, "lib3mf could not read a build item's transform");
    DWORD nv = 0, nt = 0;
    if (lib3mf().meshobject_getvertexcount(object.get(), &nv) != LIB3MF_OK ||
        lib3mf().meshobject_gettrianglecount(object.get(), &nt) != LIB3MF_OK)
      throw IoError(name, "lib3mf could not read a mesh: " + last_error(object.get()));
    std::vector<NMR::MODELMESHVERTEX> vertices(nv);
    std::vector<NMR::MODELMESHTRIANGLE> triangles(nt);
    DWORD got = 0;
    if ((nv && lib3mf().meshobject_getvertices(object.get(), vertices.data(), nv, &got) != LIB3MF_OK) ||
        (nt && lib3mf().meshobject_gettriangleindices(object.get(), triangles.data(), nt, &got) != LIB3MF_OK))
      throw IoError(name, "lib3mf could not read a mesh: " + last_error(object.get()));
    const auto first = int(mesh.vertices.size());
    for (const NMR::MODELMESHVERTEX& v : vertices) {
      Eigen::Vector3d p(v.m_fPosition[0], v.m_fPosition[1], v.m_fPosition[2]);
      if (has_transform) {
        Eigen::Vector3d q;
        for (int r = 0; r < 3; ++r)
          q[r] = double(f.m_fFields[r][0]) * p.x() + double(f.m_fFields[r][1]) * p.y() +
                 double(f.m_fFields[r][2]) * p.z() + double(f.m_fFields[r][3]);
        p = q;
      }
      mesh.vertices.push_back(p * scale);
    }
    for (const NMR::MODELMESHTRIANGLE& t : triangles) {
      for (const DWORD i : t.m_nIndices)
        if (i >= nv)
          throw IoError(name, "a triangle refers to vertex " + std::to_string(i) + " of " + std::to_string(nv));
      mesh.faces.push_back({first + int(t.m_nIndices[0]), first + int(t.m_nIndices[1]), first + int(t.m_nIndices[2])});
    }
  }
  return mesh;
}

}  // namespace sculpt::mesh::detail
