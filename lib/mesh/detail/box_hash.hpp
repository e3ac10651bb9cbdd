#pragma once
/// \file box_hash.hpp
/// The output rounding's index of triangle boxes that change (mesh/output_rounding.hpp): a
/// spatial hash with levels of cubic cells cell * 4^k, each box kept at the finest level whose
/// cells it spans at most 4 of per axis (so long triangles do not fill every query), boxes that
/// fit no level in one list; cells are hashed as in Teschner et al., "Optimized Spatial Hashing
/// for Collision Detection of Deformable Objects" (2003). Boxes are inserted and erased one at a
/// time as the cleaner edits the mesh, and queried between edits.
///
/// Why not BoxGrid (box_grid.hpp), the broad phase of the full searches: it is built once over
/// fixed boxes and enumerates all overlapping pairs; the cleaner's checks ask which boxes meet one
/// box, after each contraction, flip or vertex move, and rebuilding a BoxGrid for each would take
/// time in proportion to the whole mesh per local edit. Even the search for crossings of the
/// triangles changed since construction (crossing_search.hpp), done over a BoxGrid of all live
/// triangles instead of a query per changed triangle here, made round_for_output 7-18 % slower
/// on UV spheres of 16k triangles with a few hundred changed (float32 and grid rounding), and no
/// faster at 65k: the first, full search uses BoxGrid, the later ones this index.

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

namespace sculpt::mesh::detail {

class BoxHash {
 public:
  /// Cells of the finest level of about `cell` (positive and finite).
  explicit BoxHash(double cell) : cell_(cell) {}

  /// Keeps id (>= 0, not kept) under `box`.
  void insert(int id, const Eigen::AlignedBox3d& box);
  /// Makes room for ids below n at once: growing the table of millions of cells later rehashes
  /// all of them between two Ctrl-C checks.
  void reserve(std::size_t n) {
    cells_.reserve(n);
    level_.reserve(n);
  }
  /// Drops id, kept under `box` (the box it was inserted with).
  void erase(int id, const Eigen::AlignedBox3d& box);
  /// The kept ids whose boxes may meet `box`, each once.
  [[nodiscard]] std::vector<int> near(const Eigen::AlignedBox3d& box) const;

 private:
  static constexpr int kLevels = 16;
  static constexpr int kBig = -1;     ///< level_ of an id kept in big_
  static constexpr int kAbsent = -2;  ///< level_ of an id not kept

  bool cell_range(const Eigen::AlignedBox3d& box, int k, Eigen::Array3i& lo, Eigen::Array3i& hi) const;
  [[nodiscard]] int level_of(const Eigen::AlignedBox3d& box) const;
  /// Adds (sign > 0) or removes id under `box` at level k.
  void update_cells(int id, const Eigen::AlignedBox3d& box, int k, int sign);

  double cell_ = 1;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
  std::array<int, kLevels> per_level_{};  ///< ids kept at each level
  std::vector<int> level_;                ///< per id: its level, kBig or kAbsent
  std::vector<int> big_;                  ///< ids whose boxes fit no level
  mutable std::vector<unsigned> seen_;    ///< near(): the stamp of the last query that returned an id
  mutable unsigned stamp_ = 0;
};

}  // namespace sculpt::mesh::detail
