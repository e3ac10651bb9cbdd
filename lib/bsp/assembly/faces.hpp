#pragma once
/// \file assembly_faces.hpp
/// Internal to mesh assembly (mesh_assembly.hpp): the data the stages pass on. Faces are flat
/// arrays (corner c of the whole list is a vertex and the plane of the edge leaving it); vertices
/// are exact plane triples with a floating-point approximation (Bernstein & Fussell 2009, sec. 3),
/// plus the planes known to pass through each of them, so most on-plane questions need no
/// arithmetic. Planes are compared through canonical ids: equal or opposite planes share one.

#include <array>
#include <cstdint>
#include <vector>

#include "kernel/convex_polygon.hpp"

namespace sculpt::bsp::detail {

/// Canonical ids of planes modulo orientation (planes are normalized, so equal values are equal
/// planes): id[i] == id[j] iff plane i equals plane j or its opposite; negated[i] tells whether
/// plane i is the opposite of the id's representative (whose first non-zero normal coefficient
/// is positive).
struct PlaneIds {
  std::vector<std::uint32_t> id;
  std::vector<std::uint8_t> negated;
};
PlaneIds canonical_plane_ids(const kernel::PlaneTable& planes);

struct PlaneTriple {
  std::int32_t s, p, q;  ///< plane indices; the vertex is s ∩ p ∩ q
};

/// Canonical plane ids of a corner's three planes, sorted: corners with the same ids are the
/// same point without arithmetic (one class).
using IdTriple = std::array<std::uint32_t, 3>;

/// Vertices of the mesh being assembled (grid units).
struct AssemblyVertices {
  std::vector<kernel::ApproxPoint> at;  ///< approximation of each vertex (exact, err 0, for a grid point)
  /// 1: vertex v is a grid point (then `at` is it, exactly), found so when it was merged.
  /// Only vertices made by vertex merging have entries.
  std::vector<std::uint8_t> on_grid;
  std::vector<PlaneTriple> triple;      ///< one defining triple per vertex
  /// The planes known to contain vertex v: those of its classes (corners merged into v with
  /// one IdTriple each), a list through class_next from first_class[v] (-1 ends it; repeats
  /// are harmless for membership). Only vertices made by vertex merging have entries (copies
  /// made later have none).
  std::vector<int> first_class;
  std::vector<IdTriple> class_planes;
  std::vector<int> class_next;
  [[nodiscard]] int size() const { return int(at.size()); }
};

/// Polygons as flat arrays: face f has corners start[f] .. start[f+1]-1, corner c is vertex
/// vertex[c] and the edge from it to the next corner lies on plane line[c] (and on support[f]).
/// Vertex order is final: counter-clockwise seen from outside.
struct FaceList {
  std::vector<int> start{0};
  std::vector<int> vertex;
  std::vector<std::int32_t> line;
  std::vector<std::int32_t> support;
  std::vector<std::uint8_t> flip;  ///< 1: the outward normal is the support's negative normal

  [[nodiscard]] int size() const { return int(support.size()); }
  [[nodiscard]] int corners() const { return int(vertex.size()); }
  [[nodiscard]] int begin(int f) const { return start[std::size_t(f)]; }
  [[nodiscard]] int end(int f) const { return start[std::size_t(f) + 1]; }
  [[nodiscard]] int count(int f) const { return end(f) - begin(f); }
  /// The corner after c in its face f.
  [[nodiscard]] int next(int f, int c) const { return c + 1 == end(f) ? begin(f) : c + 1; }
  void reserve(std::size_t faces, std::size_t corners);
  /// Appends an empty face; add corners with add_corner.
  void open_face(std::int32_t support_plane, bool flipped);
  void add_corner(int v, std::int32_t edge_line);
  /// Removes the last face and its corners (one being built that turned out not to be wanted).
  void drop_last_face();
  /// Appends face f of `other` unchanged.
  void copy_face(const FaceList& other, int f);
};

/// Disjoint sets over 0..n-1 with path halving; the root of a set is its smallest element.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = int(i);
  }
  int find(int x) {
    while (parent_[std::size_t(x)] != x) x = parent_[std::size_t(x)] = parent_[std::size_t(parent_[std::size_t(x)])];
    return x;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::size_t(a < b ? b : a)] = a < b ? a : b;
  }

 private:
  std::vector<int> parent_;
};

/// Key of the directed edge u -> w.
inline std::uint64_t edge_key(int u, int w) { return (std::uint64_t(std::uint32_t(u)) << 32) | std::uint32_t(w); }

/// Multimap from 64-bit keys to dense values 0..n-1 (open addressing for the keys, a chain
/// through the values for repeated keys): constant-time half-edge lookups.
class EdgeIndex {
 public:
  explicit EdgeIndex(std::size_t values);
  void insert(std::uint64_t key, int value);
  /// The last value inserted with `key`, or -1; earlier ones follow through next().
  [[nodiscard]] int find(std::uint64_t key) const;
  [[nodiscard]] int next(int value) const { return next_[std::size_t(value)]; }

 private:
  struct Slot {
    std::uint64_t key;
    int head;  // -1: empty
  };
  [[nodiscard]] std::size_t home(std::uint64_t key) const {
    return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  std::vector<Slot> slots_;
  std::vector<int> next_;
  int shift_ = 60;
};

/// The half-edges of a face list by start vertex (counting sort): finding the half-edges u -> w
/// scans the few edges leaving u, in two small arrays that stay in cache far better than a hash
/// table over all half-edges.
class OutgoingEdges {
 public:
  OutgoingEdges(const FaceList& faces, int vertex_count);
  /// A corner whose edge goes from u to w, or -1.
  [[nodiscard]] int find(int u, int w) const {
    for (int i = start_[std::size_t(u)]; i < start_[std::size_t(u) + 1]; ++i)
      if (out_[std::size_t(i)].to == w) return out_[std::size_t(i)].corner;
    return -1;
  }
  /// Calls fn(corner) for every corner whose edge goes from u to w.
  template <typename Fn>
  void for_each(int u, int w, Fn&& fn) const {
    for (int i = start_[std::size_t(u)]; i < start_[std::size_t(u) + 1]; ++i)
      if (out_[std::size_t(i)].to == w) fn(out_[std::size_t(i)].corner);
  }

 private:
  struct Out {
    int to, corner;
  };
  std::vector<int> start_;
  std::vector<Out> out_;
};

/// Exact questions about assembly vertices (approximations filter, exact predicates decide).
class VertexGeometry {
 public:
  VertexGeometry(const kernel::PlaneTable& planes, const PlaneIds& ids, const AssemblyVertices& vertices)
      : planes_(planes), ids_(ids), v_(vertices) {}
  /// Vertex v lies on plane i: for a grid vertex (on_grid) the plane evaluated there in Int128;
  /// otherwise known without arithmetic when one of the planes merged into v is plane i or its
  /// opposite, else decided exactly.
  [[nodiscard]] bool on_plane(int v, std::int32_t plane) const;
  /// The axis along which the line support ∩ edge changes most (exact direction): two distinct
  /// points of the line always differ in this coordinate.
  [[nodiscard]] int line_axis(std::int32_t support, std::int32_t edge) const;
  /// Exact comparison of coordinate `axis` of two vertices.
  [[nodiscard]] bool less_along(int a, int b, int axis) const;
  /// Exact test that collinear, distinct vertices satisfy u < c < w or w < c < u along `axis`.
  [[nodiscard]] bool between(int u, int c, int w, int axis) const;
  [[nodiscard]] const kernel::ApproxPoint& at(int v) const { return v_.at[std::size_t(v)]; }
  [[nodiscard]] const kernel::PlaneTable& planes() const { return planes_; }
  [[nodiscard]] int vertex_count() const { return v_.size(); }

 private:
  const kernel::PlaneTable& planes_;
  const PlaneIds& ids_;
  const AssemblyVertices& v_;
};

}  // namespace sculpt::bsp::detail
