// Binary glTF 2.0 (.glb) reader: the triangles of every mesh the scene's nodes instantiate, each
// node's transform applied (glTF 2.0 sec. 3.5), positions that coincide merged into one vertex
// (glTF splits vertices by normals and texture coordinates; merging makes a closed mesh closed
// again). Every offset, length and count in the file is checked against the data it points into
// before anything is read, in 64-bit arithmetic that cannot overflow (counts and offsets are
// bounded first); any problem is an IoError naming the property.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "base/errors.hpp"
#include "mesh/formats/glb_container.hpp"
#include "mesh/formats/json_reader.hpp"
#include "mesh/formats/mesh_formats.hpp"
#include "mesh/formats/vertex_merger.hpp"

namespace sculpt::mesh::detail {
namespace {

/// Integers in the JSON are taken up to 2^53 (exact in a double); with counts also bounded by
/// 2^32, sums and products of offsets, strides and counts stay far below 2^64.
constexpr double kLargestInteger = 9007199254740992.0;
constexpr std::uint64_t kLargestCount = 0xFFFFFFFFull;
/// Triangles in all, instances included: at least 2^25, or one per byte of the file (more than a
/// file without instancing can hold: a triangle takes at least 3 bytes of indices), so that a small
/// file that places a large mesh many times cannot exhaust memory; never more than int indexes.
constexpr std::size_t kFewestAllowedTriangles = std::size_t(1) << 25;
constexpr std::size_t kMostTriangles = 0x7FFFFFFF / 3;

/// The bytes an accessor reads: `count` elements of `size` bytes, `stride` apart, from `data`
/// (all checked to lie inside the BIN chunk).
struct ElementRange {
  const char* data = nullptr;
  std::uint64_t count = 0;
  std::uint64_t stride = 0;
  int component_type = 0;
};

/// Reads the glTF asset of one GLB file: its JSON and BIN chunks.
class GlbReader {
 public:
  GlbReader(std::string_view json, std::string_view bin, std::size_t file_size, const std::string& name)
      : name_(name),
        bin_(bin),
        doc_(json, name),
        max_triangles_(std::min(std::max(kFewestAllowedTriangles, file_size), kMostTriangles)) {
    if (doc_.root().kind != JsonKind::Object) fail("the JSON chunk is not an object");
  }

  PolygonMesh read() {
    check_asset();
    const std::vector<std::size_t> roots = scene_roots();
    // Depth-first over the node trees (sec. 3.5.2) with an explicit stack: a node's global
    // transform is its parent's times its own (sec. 3.5.3).
    const JsonValue* nodes = array(doc_.root(), "nodes", "the asset");
    std::vector<char> reached(nodes ? nodes->children.size() : 0, 0);
    std::vector<std::pair<std::size_t, Eigen::Matrix4d>> stack, placed;  // (node, parent's); (mesh, global)
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, Eigen::Matrix4d::Identity());
    while (!stack.empty()) {
      const auto [n, parent] = stack.back();
      stack.pop_back();
      const std::string what = "nodes[" + std::to_string(n) + "]";
      if (reached[n]) fail(what + " is reached twice: the nodes must form trees (glTF 2.0 sec. 3.5.2)");
      reached[n] = 1;
      const JsonValue& node = object(doc_.at(nodes->children[n]), what);
      const Eigen::Matrix4d global = parent * local_transform(node, what);
      if (const JsonValue* m = doc_.member(node, "mesh"))
        placed.emplace_back(index(*m, what + ".mesh", "meshes"), global);
      if (const JsonValue* children = array(node, "children", what))
        for (auto c = children->children.rbegin(); c != children->children.rend(); ++c)
          stack.emplace_back(index(doc_.at(*c), what + ".children", "nodes"), global);
    }
    // Counted before anything is built, from the accessors' counts.
    const JsonValue* meshes = array(doc_.root(), "meshes", "the asset");
    std::vector<std::uint64_t> triangles_of(meshes ? meshes->children.size() : 0, kLargestCount);  // not yet counted
    std::uint64_t triangles = 0;
    for (const auto& [m, global] : placed) {
      if (triangles_of[m] == kLargestCount) triangles_of[m] = triangle_count(m);
      triangles += triangles_of[m];
      if (triangles > max_triangles_)
        fail("the nodes place more than " + std::to_string(max_triangles_) +
             " triangles in all (at most 2^25 or one per byte of the file are read)");
    }
    for (const auto& [m, global] : placed) add_mesh(m, global);
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { throw IoError(name_, message); }

  const JsonValue& object(const JsonValue& v, const std::string& what) const {
    if (v.kind != JsonKind::Object) fail(what + " is not a JSON object");
    return v;
  }
  /// The member `key` of `owner` if it is an array (nullptr if absent).
  const JsonValue* array(const JsonValue& owner, std::string_view key, const std::string& what) const {
    const JsonValue* v = doc_.member(owner, key);
    if (v && v->kind != JsonKind::Array) fail(what + "." + std::string(key) + " is not an array");
    return v;
  }
  /// A non-negative integer (at most 2^53).
  std::uint64_t integer(const JsonValue& v, const std::string& what) const {
    if (v.kind != JsonKind::Number || !(v.number >= 0 && v.number <= kLargestInteger) ||
        std::floor(v.number) != v.number)
      fail(what + " must be a non-negative integer");
    return static_cast<std::uint64_t>(v.number);
  }
  /// The integer member `key` of `owner`, or `fallback` when it is absent.
  std::optional<std::uint64_t> integer_member(const JsonValue& owner, std::string_view key, const std::string& what,
                                              std::optional<std::uint64_t> fallback = std::nullopt) const {
    const JsonValue* v = doc_.member(owner, key);
    if (!v) return fallback;
    return integer(*v, what + "." + std::string(key));
  }
  std::uint64_t required_integer(const JsonValue& owner, std::string_view key, const std::string& what) const {
    const std::optional<std::uint64_t> v = integer_member(owner, key, what);
    if (!v) fail(what + " has no " + std::string(key));
    return *v;
  }
  /// An index into the top-level array `table` (meshes, nodes, ...), checked.
  std::size_t index(const JsonValue& v, const std::string& what, std::string_view table) const {
    const std::uint64_t i = integer(v, what);
    const JsonValue* t = array(doc_.root(), table, "the asset");
    if (!t || i >= t->children.size())
      fail(what + " refers to " + std::string(table) + "[" + std::to_string(i) + "], which does not exist");
    return static_cast<std::size_t>(i);
  }
  /// Element `i` of the top-level array `table` as an object (i checked by index()).
  const JsonValue& element(std::string_view table, std::size_t i) const {
    return object(doc_.at(doc_.member(doc_.root(), table)->children[i]),
                  std::string(table) + "[" + std::to_string(i) + "]");
  }
  /// `n` numbers of the array member `key` of `owner`, or nullopt if it is absent.
  std::optional<std::vector<double>> numbers(const JsonValue& owner, std::string_view key, std::size_t n,
                                             const std::string& what) const {
    const JsonValue* a = array(owner, key, what);
    if (!a) return std::nullopt;
    if (a->children.size() != n) fail(what + "." + std::string(key) + " must have " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const std::size_t c : a->children) {
      if (doc_.at(c).kind != JsonKind::Number) fail(what + "." + std::string(key) + " must hold numbers only");
      out.push_back(doc_.at(c).number);
    }
    return out;
  }

  /// asset.version must be 2.x (sec. 3.2); required extensions change what the data means, and
  /// none is implemented here (Draco, meshopt, quantization: sec. 3.12).
  void check_asset() const {
    const JsonValue* asset = doc_.member(doc_.root(), "asset");
    const JsonValue* version = asset ? doc_.member(*asset, "version") : nullptr;
    if (!version || version->kind != JsonKind::String) fail("the asset has no asset.version (not glTF 2.0)");
    if (version->text.substr(0, 2) != "2.") fail("glTF version " + version->text + " (only 2.x is read)");
    if (const JsonValue* required = array(doc_.root(), "extensionsRequired", "the asset"))
      for (const std::size_t e : required->children)
        fail("the file requires the glTF extension '" + (doc_.at(e).kind == JsonKind::String ? doc_.at(e).text : "?") +
             "', which is not read");
  }

  /// The root nodes of the scene to show (sec. 3.5.1): `scene`, else the first scene; without
  /// scenes, every node that is no node's child.
  std::vector<std::size_t> scene_roots() const {
    std::vector<std::size_t> roots;
    const JsonValue* scenes = array(doc_.root(), "scenes", "the asset");
    if (scenes && !scenes->children.empty()) {
      std::size_t s = 0;
      if (const JsonValue* chosen = doc_.member(doc_.root(), "scene")) s = index(*chosen, "scene", "scenes");
      const std::string what = "scenes[" + std::to_string(s) + "]";
      if (const JsonValue* list = array(element("scenes", s), "nodes", what))
        for (const std::size_t r : list->children) roots.push_back(index(doc_.at(r), what + ".nodes", "nodes"));
      return roots;
    }
    const JsonValue* nodes = array(doc_.root(), "nodes", "the asset");
    if (!nodes) return roots;
    std::vector<char> child(nodes->children.size(), 0);
    for (std::size_t n = 0; n < nodes->children.size(); ++n) {
      const std::string what = "nodes[" + std::to_string(n) + "]";
      if (const JsonValue* children = array(object(doc_.at(nodes->children[n]), what), "children", what))
        for (const std::size_t c : children->children) child[index(doc_.at(c), what + ".children", "nodes")] = 1;
    }
    for (std::size_t n = 0; n < child.size(); ++n)
      if (!child[n]) roots.push_back(n);
    return roots;
  }

  /// A node's own transform (sec. 3.5.3): `matrix` (column-major, affine), else T * R * S.
  Eigen::Matrix4d local_transform(const JsonValue& node, const std::string& what) const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (const auto a = numbers(node, "matrix", 16, what)) {  // as three.js: a matrix wins over TRS
      for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = (*a)[i];
      if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 2) != 0 || m(3, 3) != 1)
        fail(what + ".matrix is not affine (its last row must be 0 0 0 1)");
      return m;
    }
    if (const auto s = numbers(node, "scale", 3, what))
      m.topLeftCorner<3, 3>() = Eigen::Vector3d((*s)[0], (*s)[1], (*s)[2]).asDiagonal();
    if (const auto r = numbers(node, "rotation", 4, what)) {  // a unit quaternion x, y, z, w
      Eigen::Quaterniond q((*r)[3], (*r)[0], (*r)[1], (*r)[2]);
      if (!(q.norm() > 0) || !std::isfinite(q.norm())) fail(what + ".rotation is not a rotation quaternion");
      m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix() * m.topLeftCorner<3, 3>();
    }
    if (const auto t = numbers(node, "translation", 3, what))
      m.topRightCorner<3, 1>() = Eigen::Vector3d((*t)[0], (*t)[1], (*t)[2]);
    return m;
  }

  /// The bytes of accessor `a` (sec. 3.6.2): its buffer view's range in the BIN chunk, checked to
  /// hold `count` elements of `components` values of `component_type` (or of any of the index
  /// types when `component_type` is 0), `stride` apart.
  ElementRange accessor(std::size_t a, int component_type, std::string_view type, int components) const {
    const std::string what = "accessors[" + std::to_string(a) + "]";
    const JsonValue& acc = element("accessors", a);
    if (doc_.member(acc, "sparse")) fail(what + " is sparse (sparse accessors are not read)");
    const JsonValue* view_index = doc_.member(acc, "bufferView");
    if (!view_index) fail(what + " has no bufferView (accessors filled with zeros are not read)");
    ElementRange r;
    r.component_type =
        static_cast<int>(std::min<std::uint64_t>(required_integer(acc, "componentType", what), 1u << 20));
    const bool index_type = r.component_type == glb::kUnsignedByte || r.component_type == glb::kUnsignedShort ||
                            r.component_type == glb::kUnsignedInt;
    if (component_type ? r.component_type != component_type : !index_type)
      fail(what + " has componentType " + std::to_string(r.component_type) + ", expected " +
           (component_type ? std::to_string(component_type) + " (FLOAT)" : "5121, 5123 or 5125 (unsigned integers)"));
    const JsonValue* t = doc_.member(acc, "type");
    if (!t || t->kind != JsonKind::String || t->text != type) fail(what + " must be of type " + std::string(type));
    r.count = required_integer(acc, "count", what);
    if (r.count == 0 || r.count > kLargestCount) fail(what + ".count must be 1 to 2^32 - 1");
    const std::uint64_t component_size = r.component_type == glb::kUnsignedByte    ? 1
                                         : r.component_type == glb::kUnsignedShort ? 2
                                                                                   : 4;
    const std::uint64_t element_size = component_size * std::uint64_t(components);
    const std::uint64_t offset = *integer_member(acc, "byteOffset", what, 0);

    const std::size_t v = index(*view_index, what + ".bufferView", "bufferViews");
    const std::string view_what = "bufferViews[" + std::to_string(v) + "]";
    const JsonValue& view = element("bufferViews", v);
    const JsonValue* buffer_index = doc_.member(view, "buffer");
    if (!buffer_index) fail(view_what + " has no buffer");
    const std::size_t b = index(*buffer_index, view_what + ".buffer", "buffers");
    const std::uint64_t view_offset = *integer_member(view, "byteOffset", view_what, 0);
    const std::uint64_t view_length = required_integer(view, "byteLength", view_what);
    r.stride = *integer_member(view, "byteStride", view_what, element_size);
    if (r.stride < element_size || r.stride > 252)  // the bufferView schema: at most 252
      fail(view_what + ".byteStride " + std::to_string(r.stride) + " does not fit " + what + "'s elements of " +
           std::to_string(element_size) + " bytes");
    // All terms below 2^53 and count * stride below 2^40: no sum overflows.
    if (offset + (r.count - 1) * r.stride + element_size > view_length)
      fail(what + " reads " + std::to_string(r.count) + " elements from byte " + std::to_string(offset) +
           ", beyond the " + std::to_string(view_length) + " bytes of " + view_what);

    const std::string buffer_what = "buffers[" + std::to_string(b) + "]";
    const JsonValue& buffer = element("buffers", b);
    if (doc_.member(buffer, "uri"))
      fail(buffer_what + " refers to data outside the file (a uri); only the GLB's own BIN chunk is read");
    if (b != 0) fail(buffer_what + " has no uri, but only buffers[0] can be the GLB's BIN chunk (sec. 4.4.3.3)");
    const std::uint64_t buffer_length = required_integer(buffer, "byteLength", buffer_what);
    if (buffer_length > bin_.size())
      fail(buffer_what + " has " + std::to_string(buffer_length) + " bytes but the BIN chunk " +
           (bin_.empty() ? std::string("is missing") : "has " + std::to_string(bin_.size())));
    if (view_offset + view_length > buffer_length)
      fail(view_what + " (bytes " + std::to_string(view_offset) + " to " + std::to_string(view_offset + view_length) +
           ") lies beyond the " + std::to_string(buffer_length) + " bytes of " + buffer_what);
    r.data = bin_.data() + view_offset + offset;
    return r;
  }

  /// The positions of accessor `a` (float VEC3, sec. 3.7.2.1), all finite.
  std::vector<Eigen::Vector3d> positions(std::size_t a) const {
    const ElementRange r = accessor(a, glb::kFloat, "VEC3", 3);
    std::vector<Eigen::Vector3d> out(r.count);
    for (std::uint64_t i = 0; i < r.count; ++i) {
      float c[3];
      std::memcpy(c, r.data + i * r.stride, 12);
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]))
        fail("accessors[" + std::to_string(a) + "] position " + std::to_string(i) + " is not finite");
      out[i] = {c[0], c[1], c[2]};
    }
    return out;
  }

  /// The indices of accessor `a` (unsigned byte, short or int SCALAR), each below `vertex_count`.
  std::vector<std::uint32_t> indices(std::size_t a, std::size_t vertex_count) const {
    const ElementRange r = accessor(a, 0, "SCALAR", 1);
    std::vector<std::uint32_t> out(r.count);
    for (std::uint64_t i = 0; i < r.count; ++i) {
      const char* p = r.data + i * r.stride;
      std::uint32_t x = 0;
      if (r.component_type == glb::kUnsignedByte)
        x = static_cast<unsigned char>(*p);
      else if (r.component_type == glb::kUnsignedShort)
        x = std::uint32_t(static_cast<unsigned char>(p[0])) | std::uint32_t(static_cast<unsigned char>(p[1])) << 8;
      else
        x = glb::load_u32(p);
      if (x >= vertex_count)
        fail("accessors[" + std::to_string(a) + "] index " + std::to_string(i) + " is " + std::to_string(x) +
             ", beyond the " + std::to_string(vertex_count) + " positions");
      out[i] = x;
    }
    return out;
  }

  /// How many triangles mesh `m` has (its TRIANGLES primitives' index or position counts / 3, each
  /// count below 2^32), before anything is checked or read.
  std::uint64_t triangle_count(std::size_t m) const {
    const std::string what = "meshes[" + std::to_string(m) + "]";
    std::uint64_t n = 0;
    const JsonValue* primitives = array(element("meshes", m), "primitives", what);
    for (std::size_t p = 0; primitives && p < primitives->children.size(); ++p) {
      const std::string pwhat = what + ".primitives[" + std::to_string(p) + "]";
      const JsonValue& primitive = object(doc_.at(primitives->children[p]), pwhat);
      const JsonValue* attributes = doc_.member(primitive, "attributes");
      const JsonValue* counted = doc_.member(primitive, "indices");
      if (!counted && attributes) counted = doc_.member(object(*attributes, pwhat + ".attributes"), "POSITION");
      if (*integer_member(primitive, "mode", pwhat, glb::kTriangles) != glb::kTriangles || !counted) continue;
      const std::size_t a = index(*counted, pwhat, "accessors");
      n += std::min(required_integer(element("accessors", a), "count", "accessors[" + std::to_string(a) + "]"),
                    kLargestCount) /
           3;
    }
    return n;
  }

  /// Adds the triangles of mesh `m` (sec. 3.7.2) placed by `global`. Points and lines are skipped.
  void add_mesh(std::size_t m, const Eigen::Matrix4d& global) {
    const std::string what = "meshes[" + std::to_string(m) + "]";
    const JsonValue* primitives = array(element("meshes", m), "primitives", what);
    if (!primitives) fail(what + " has no primitives");
    // A mirroring transform reverses the winding (sec. 3.7.2.1): the triangles are turned back.
    const bool mirrored = global.topLeftCorner<3, 3>().determinant() < 0;
    for (std::size_t p = 0; p < primitives->children.size(); ++p) {
      const std::string pwhat = what + ".primitives[" + std::to_string(p) + "]";
      const JsonValue& primitive = object(doc_.at(primitives->children[p]), pwhat);
      const std::uint64_t mode = *integer_member(primitive, "mode", pwhat, glb::kTriangles);
      if (mode < glb::kTriangles) continue;  // points and lines bound nothing
      if (mode != glb::kTriangles)
        fail(pwhat + " has mode " + std::to_string(mode) + " (only TRIANGLES, mode 4, is read; not strips or fans)");
      const JsonValue* attributes = doc_.member(primitive, "attributes");
      if (!attributes) fail(pwhat + " has no attributes");
      const JsonValue* position = doc_.member(object(*attributes, pwhat + ".attributes"), "POSITION");
      if (!position) continue;  // nothing to place (sec. 3.7.2.1: such a primitive is not rendered)
      const std::vector<Eigen::Vector3d> points =
          positions(index(*position, pwhat + ".attributes.POSITION", "accessors"));
      std::vector<std::uint32_t> corners;
      if (const JsonValue* i = doc_.member(primitive, "indices")) {
        corners = indices(index(*i, pwhat + ".indices", "accessors"), points.size());
      } else {
        corners.resize(points.size());
        for (std::size_t k = 0; k < corners.size(); ++k) corners[k] = static_cast<std::uint32_t>(k);
      }
      if (corners.size() % 3 != 0)
        fail(pwhat + " has " + std::to_string(corners.size()) + " corners, not a multiple of 3 (TRIANGLES)");
      // The positions the triangles use, in accessor order, placed and merged.
      std::vector<int> vertex(points.size(), -1);
      for (const std::uint32_t c : corners) vertex[c] = 0;
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (vertex[k] < 0) continue;
        const Eigen::Vector3d q = (global * points[k].homogeneous()).head<3>();
        if (!q.allFinite()) fail(pwhat + ": position " + std::to_string(k) + " is not finite once placed by its nodes");
        vertex[k] = merger_.add(mesh_, q);
      }
      for (std::size_t k = 0; k < corners.size(); k += 3) {
        const int a = vertex[corners[k]], b = vertex[corners[k + 1]], c = vertex[corners[k + 2]];
        mesh_.faces.push_back(mirrored ? std::vector<int>{a, c, b} : std::vector<int>{a, b, c});
      }
    }
  }

  const std::string& name_;
  std::string_view bin_;
  JsonDocument doc_;
  std::size_t max_triangles_;
  PolygonMesh mesh_;
  VertexMerger merger_;
};

}  // namespace

PolygonMesh decode_glb(std::string_view data, const std::string& name) {
  // The header (sec. 4.4.2): magic, version, the file's length.
  if (data.size() < glb::kHeaderSize) throw IoError(name, "not a GLB file (shorter than its 12-byte header)");
  if (glb::load_u32(data.data()) != glb::kMagic) throw IoError(name, "not a GLB file (it does not start with 'glTF')");
  if (const std::uint32_t version = glb::load_u32(data.data() + 4); version != glb::kVersion)
    throw IoError(name, "GLB version " + std::to_string(version) + " (only version 2 is read)");
  if (const std::uint32_t length = glb::load_u32(data.data() + 8); length != data.size())
    throw IoError(name, "the GLB header gives a length of " + std::to_string(length) + " bytes but the file has " +
                            std::to_string(data.size()));
  // The chunks (sec. 4.4.3): JSON first, then at most one BIN; chunks of other types are skipped.
  std::string_view json, bin;
  bool has_json = false, has_bin = false;
  for (std::size_t pos = glb::kHeaderSize; pos < data.size();) {
    if (data.size() - pos < glb::kChunkHeaderSize)
      throw IoError(name, "the chunk header at byte " + std::to_string(pos) + " is cut off");
    const std::uint32_t length = glb::load_u32(data.data() + pos), type = glb::load_u32(data.data() + pos + 4);
    pos += glb::kChunkHeaderSize;
    if (length > data.size() - pos)
      throw IoError(name, "a chunk at byte " + std::to_string(pos - 8) + " announces " + std::to_string(length) +
                              " bytes but only " + std::to_string(data.size() - pos) + " follow");
    const std::string_view chunk = data.substr(pos, length);
    pos += length;
    if (!has_json) {
      if (type != glb::kJsonChunk) throw IoError(name, "the first GLB chunk is not the JSON chunk");
      json = chunk;
      has_json = true;
    } else if (type == glb::kJsonChunk) {
      throw IoError(name, "a second JSON chunk");
    } else if (type == glb::kBinChunk) {
      if (has_bin) throw IoError(name, "a second BIN chunk");
      bin = chunk;
      has_bin = true;
    }
  }
  if (!has_json) throw IoError(name, "the GLB file has no JSON chunk");
  return GlbReader(json, bin, data.size(), name).read();
}

}  // namespace sculpt::mesh::detail
