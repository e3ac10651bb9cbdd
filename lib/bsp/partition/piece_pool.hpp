#pragma once
/// \file piece_pool.hpp
/// Internal (autopartition): the pieces of boundary a tree build splits, and their boxes.

#include <cstdint>
#include <span>
#include <vector>

#include "bsp/fragment_list.hpp"
#include "kernel/convex_polygon.hpp"

namespace sculpt::bsp::detail {

/// A fragment's piece in a cell being partitioned, with its outward plane (the support, or its
/// opposite for a flipped fragment).
struct PartitionPiece {
  kernel::ConvexPolygon polygon;
  std::int32_t outward;
};

/// Every piece a build makes, by index: the fragments first, then the parts of split pieces.
/// Boxes are kept apart, in an array of their own: scoring reads boxes far more often than
/// polygons.
struct PiecePool {
  std::vector<PartitionPiece> pieces;
  std::vector<kernel::CornerBox> boxes;

  /// The pool of `fragments`, in order (`opposite` turns a flipped fragment's support outward).
  template <class Opposite>
  static PiecePool of(const FragmentList& fragments, Opposite opposite) {
    PiecePool pool;
    pool.pieces.reserve(2 * fragments.size());
    pool.boxes.reserve(2 * fragments.size());
    for (const FragmentRef f : fragments) {
      const std::int32_t s = f.polygon.support;
      pool.add(kernel::ConvexPolygon::copy_of(f.polygon), f.flip ? opposite(s) : s);
    }
    return pool;
  }
  /// Appends a piece; returns its index.
  std::int32_t add(const kernel::ConvexPolygon& polygon, std::int32_t outward);
  [[nodiscard]] std::size_t size() const { return pieces.size(); }
};

/// The pieces of a cell on either side of a plane (indices into a PiecePool).
struct CellSides {
  std::vector<std::int32_t> negative, positive;
};

/// Splits the cell's `pieces` by `plane` (its opposite: `opposite`) into `sides`, appending the
/// parts of pieces it cuts to `pool` (exactly: kernel::split). Pieces on the plane are used up,
/// unless `auxiliary`: then a piece on it makes the split fail (false; an auxiliary plane must
/// carry none).
bool split_cell(const kernel::PlaneTable& planes, PiecePool& pool, std::span<const std::int32_t> pieces,
                std::int32_t plane, std::int32_t opposite, bool auxiliary, CellSides& sides);

}  // namespace sculpt::bsp::detail
