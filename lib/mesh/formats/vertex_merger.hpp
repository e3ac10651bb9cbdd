#pragma once
/// \file vertex_merger.hpp
/// Merging of corners with exactly equal coordinates (internal): the formats that store corners
/// per facet (STL) or split vertices by their other attributes (glTF) read back as one vertex per
/// point, so a closed mesh written by them reads back closed.

#include <array>
#include <bit>
#include <cstdint>
#include <unordered_map>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::mesh::detail {

/// Merges corners with exactly equal coordinates (0 and -0 alike) into one vertex.
class VertexMerger {
 public:
  /// The index in `mesh` of the vertex at `p`, appended to mesh.vertices if it is new.
  int add(PolygonMesh& mesh, const Eigen::Vector3d& p) {
    const Key key{bits(p.x()), bits(p.y()), bits(p.z())};
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<uint64_t, 3>;
  static uint64_t bits(double x) { return std::bit_cast<uint64_t>(x + 0.0); }  // -0 + 0 = +0
  struct Hash {
    size_t operator()(const Key& k) const {
      uint64_t h = 0x9e3779b97f4a7c15ull;
      for (uint64_t v : k) h = (h ^ v) * 0x100000001b3ull + (h >> 29);
      return static_cast<size_t>(h);
    }
  };
  std::unordered_map<Key, int, Hash> index_;
};

}  // namespace sculpt::mesh::detail
