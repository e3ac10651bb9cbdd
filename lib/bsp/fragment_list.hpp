#pragma once
/// \file fragment_list.hpp
/// A solid's boundary fragments (Bernstein & Fussell 2009: convex plane-based polygons), stored
/// compactly: each fragment's corners lie side by side in a pool of corner blocks, and the list
/// keeps a 16-byte record per fragment (its support, side, corner count and where its corners
/// are). A triangle takes 136 bytes instead of the 200 of a ConvexPolygon with room for four
/// corners inline; fragments are most of a set operation's memory (docs/bsp.md, "Memory").
///
/// Fragments are read in place (FragmentRef: a PolygonView of the corners and the side). Adding
/// fragments never moves the corners already stored, so references stay valid while the list
/// grows; replace(), pop_back() and the renumbering functions change fragments in place.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "base/chunked_vector.hpp"
#include "base/index_iterator.hpp"
#include "kernel/convex_polygon.hpp"

namespace sculpt {

/// A convex piece of a solid's boundary on one of its planes (corners counter-clockwise about the
/// plane's normal) and the side its outward normal points to.
struct BoundaryFragment {
  kernel::ConvexPolygon polygon;
  bool flip = false;  ///< true: the outward normal is the plane's negative normal
};

/// A fragment of a FragmentList read in place: valid until that fragment is changed or the list
/// is destroyed, moved from or assigned.
struct FragmentRef {
  kernel::PolygonView polygon;
  bool flip = false;
  /// A fragment of its own with these corners.
  [[nodiscard]] BoundaryFragment copy() const { return {kernel::ConvexPolygon::copy_of(polygon), flip}; }
};

class FragmentList {
 public:
  FragmentList() = default;
  /// A copy whose corners are packed anew (no room left by replaced or removed fragments).
  FragmentList(const FragmentList& other);
  FragmentList& operator=(const FragmentList& other);
  FragmentList(FragmentList&& other) noexcept;
  FragmentList& operator=(FragmentList&& other) noexcept;
  ~FragmentList() { release(); }
  void swap(FragmentList& other) noexcept;

  [[nodiscard]] std::size_t size() const { return records_.size(); }
  [[nodiscard]] bool empty() const { return records_.empty(); }
  /// Room for n fragments' records (corners are allocated as they come).
  void reserve(std::size_t n) { records_.reserve(n); }

  [[nodiscard]] FragmentRef operator[](std::size_t i) const {
    const Record& r = records_[i];
    return {{r.support, {chunks_[r.chunk].corners + r.offset, r.count}}, r.flip != 0};
  }
  [[nodiscard]] FragmentRef back() const { return (*this)[size() - 1]; }

  void push_back(kernel::PolygonView polygon, bool flip);
  void push_back(const BoundaryFragment& f) { push_back(f.polygon, f.flip); }
  void pop_back();
  /// Drops the fragments from n on (n <= size()).
  void truncate(std::size_t n) {
    while (size() > n) pop_back();
  }
  void clear();
  /// Fragment i becomes `polygon` on side `flip` (may be read from this list: the corners are
  /// copied before the old ones are given up).
  void replace(std::size_t i, kernel::PolygonView polygon, bool flip);
  void set_flip(std::size_t i, bool flip) { records_[i].flip = flip; }
  /// Moves the fragments of `other` to the end of this list, in order (their corner blocks are
  /// taken over, not copied, when they are many); `other` becomes empty.
  void append(FragmentList&& other);

  /// Renumbers every plane a fragment refers to (supports, edges, vertex planes): each index p
  /// becomes map(p).
  template <class Map>
  void renumber_planes(Map&& map) {
    for (std::size_t i = 0; i < records_.size(); ++i) renumber_planes(i, map);
  }
  /// The same for fragment i.
  template <class Map>
  void renumber_planes(std::size_t i, Map&& map) {
    Record& r = records_[i];
    r.support = map(r.support);
    for (kernel::Corner& c : std::span(chunks_[r.chunk].corners + r.offset, r.count))
      c.edge = map(c.edge), c.p = map(c.p), c.q = map(c.q);
  }

  /// Packs the corners anew (as a copy does) when the room that replaced and removed fragments
  /// left unused is at least a quarter of the corners in use.
  void pack_if_sparse();

  /// Bytes the list holds (records, corner blocks and their table), for memory reports.
  [[nodiscard]] std::size_t bytes() const;

  using Iterator = IndexIterator<const FragmentList, FragmentRef>;
  [[nodiscard]] Iterator begin() const { return {this, 0}; }
  [[nodiscard]] Iterator end() const { return {this, size()}; }

 private:
  /// Where fragment i is: its corners are chunks_[chunk].corners[offset, offset + count).
  struct Record {
    std::int32_t support;
    std::uint32_t chunk;
    std::uint32_t offset;
    std::uint32_t count : 31;
    std::uint32_t flip : 1;
  };
  static_assert(sizeof(Record) == 16);
  /// A block of corners; only [0, used) is written.
  struct Chunk {
    kernel::Corner* corners;
    std::uint32_t capacity, used;
  };
  /// Room for n more corners in one block: the place of the first.
  std::pair<std::uint32_t, std::uint32_t> allot(std::size_t n);
  void release();

  ChunkedVector<Record> records_;
  std::vector<Chunk> chunks_;
};

}  // namespace sculpt
