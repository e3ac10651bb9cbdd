#pragma once
/// \file plane_table.hpp
/// The planes of one tree (or one operation), referred to by index (Bernstein & Fussell 2009,
/// sec. 3: polygons are lists of plane references). Stored in blocks of kBlock planes that copies
/// of a table share: copying a table copies block pointers, not planes, and a table copies a
/// block only before it writes into one it shares (copy on write). So a solid copied, a set
/// operation's arena started from its larger operand, and a result that keeps its arena's planes
/// cost no plane copies (docs/bsp.md, "Memory"). Reading stays one index step: operator[] goes
/// through a list of block addresses.
///
/// Tables are values for one thread, like solids; tables that share blocks may be used on
/// different threads (shared blocks are never written).

#include <cstdint>
#include <memory>
#include <vector>

#include "base/assert.hpp"
#include "kernel/plane.hpp"

namespace sculpt::kernel {

/// Planes with stable indices. Indices 0..5 are the world box (+x, -x, +y, -y, +z, -z faces).
/// A plane may be marked *auxiliary*: a splitting plane that carries no face of the solid
/// (the axial and inner ring planes of a solid of revolution). The boundary of a regularized
/// set operation lies on its operands' boundaries, so boundary extraction skips such planes;
/// tree algorithms clear the mark when a face plane of another tree turns out to coincide.
class PlaneTable {
 public:
  /// Planes per block: 4096 (192 KB). Only the last block of a table may be partly filled.
  static constexpr int kBlockBits = 12;
  static constexpr std::int32_t kBlock = std::int32_t(1) << kBlockBits;

  /// The world box's six planes.
  PlaneTable();
  [[nodiscard]] const Plane& operator[](std::int32_t i) const {
    SCULPT_ASSERT(i >= 0 && i < size_, "PlaneTable: plane index outside the table");
    return blocks_[std::size_t(i) >> kBlockBits][std::size_t(i) & std::size_t(kBlock - 1)];
  }
  [[nodiscard]] std::int32_t size() const { return size_; }
  std::int32_t add(const Plane& p, bool auxiliary = false);
  /// Appends `from`'s planes from index `first` on, with their auxiliary flags (copies, as add()
  /// one by one would make); returns the index the first of them gets.
  std::int32_t append(const PlaneTable& from, std::int32_t first);
  /// Appends all of `from`'s planes, world box included, sharing its blocks (no plane copied):
  /// the table is first padded to a whole number of blocks with copies of plane 0 that nothing
  /// refers to. Returns the index plane 0 of `from` gets (its plane i is at that index + i). For
  /// large tables: the padding is up to kBlock - 1 planes.
  std::int32_t append_shared(const PlaneTable& from);
  [[nodiscard]] bool auxiliary(std::int32_t i) const { return auxiliary_[std::size_t(i)]; }
  void set_auxiliary(std::int32_t i, bool auxiliary) { auxiliary_[std::size_t(i)] = auxiliary; }
  /// Room for n planes' bookkeeping (flags and block list; blocks are made as they fill).
  void reserve(std::size_t n);
  /// Drops the planes at indices >= n (n >= 6: the world box stays), and puts plane p at index
  /// i < size() in place of the one there: for tree algorithms that renumber the planes they
  /// added and reuse the slots of planes nothing refers to any more (bsp/tree/tree_arena.hpp,
  /// reclaim_added). The caller rewrites the references.
  void truncate(std::int32_t n);
  void replace(std::int32_t i, const Plane& p, bool auxiliary);
  /// All planes in index order (a copy: tests and reports).
  [[nodiscard]] std::vector<Plane> to_vector() const;
  /// True if this table and `other` share plane storage (a copy, or an arena started from it).
  [[nodiscard]] bool shares_storage_with(const PlaneTable& other) const;

  /// Half-size of the world box in grid units: 4 * kMaxCoord.
  static constexpr std::int64_t kWorld = 4 * kMaxCoord;

 private:
  using Block = std::vector<Plane>;
  /// Block k, copied first if another table shares it; holds exactly the table's planes in it.
  Block& writable(std::size_t k);
  /// Appends planes [p, p + n) that lie in one block of their source.
  void append_run(const Plane* p, std::size_t n);

  std::vector<const Plane*> blocks_;             ///< block addresses, for reads
  std::vector<std::shared_ptr<Block>> storage_;  ///< the blocks, shared between copies
  std::int32_t size_ = 0;
  std::vector<bool> auxiliary_;
};

}  // namespace sculpt::kernel
