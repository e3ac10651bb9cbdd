#include "mesh/detail/moved_neighbourhood.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include <Eigen/Geometry>

#include "base/cancel.hpp"
#include "base/parallel.hpp"

namespace sculpt::mesh::detail {
namespace {

constexpr std::int64_t kMaxCells = 64;  ///< cells a box may meet at its level (else the next, coarser one)
constexpr int kLevels = 16;             ///< levels of cells: cell * 4^k
constexpr std::size_t kChunk = 4096;    ///< faces a piece

enum : char { kFar = 0, kMoved = 1, kNear = 2, kInvalid = 3 };

/// The box of a face with valid indices.
Eigen::AlignedBox3d face_box(const PolygonMesh& mesh, const std::vector<int>& face) {
  Eigen::AlignedBox3d box;
  for (const int v : face) box.extend(mesh.vertices[std::size_t(v)]);
  return box;
}

/// The cells a box meets, per axis [lo, hi] (cells of side `cell` from the origin).
struct CellRange {
  std::int64_t lo[3], hi[3];
  bool ok = false;  ///< finite and within the indices' range
  [[nodiscard]] std::int64_t count() const { return (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1); }
  /// The same box's cells at `level` levels coarser (cells 4^level times as large): the indices
  /// divided by 4^level, rounded down. x / (c 4^k) rounds as (x / c) / 4^k (a power of two), and
  /// floor(floor(a) / n) = floor(a / n) for an integer n.
  [[nodiscard]] CellRange coarser(int level) const {
    CellRange r = *this;
    for (int k = 0; k < 3; ++k) r.lo[k] >>= 2 * level, r.hi[k] >>= 2 * level;  // (arithmetic: rounds down)
    return r;
  }
};

/// Multiplication by a positive number and floor are monotone: closed boxes that meet share a cell.
CellRange cell_range(const Eigen::AlignedBox3d& box, double inverse_cell) {
  CellRange r;
  for (int k = 0; k < 3; ++k) {
    const double lo = std::floor(box.min()[k] * inverse_cell), hi = std::floor(box.max()[k] * inverse_cell);
    if (!(std::fabs(lo) < 0x1p40 && std::fabs(hi) < 0x1p40)) return r;
    r.lo[k] = std::int64_t(lo), r.hi[k] = std::int64_t(hi);
  }
  r.ok = true;
  return r;
}

/// A set of cells by a 64-bit hash of their indices (open addressing; a collision only keeps a
/// face that was not needed).
class CellSet {
 public:
  explicit CellSet(std::size_t cells) {
    std::size_t n = 64;
    while (n < 2 * cells) n *= 2;
    slots_.assign(n, 0);
  }
  void insert(std::uint64_t key) {
    std::size_t h = slot(key);
    while (slots_[h] != 0 && slots_[h] != key) h = (h + 1) & (slots_.size() - 1);
    slots_[h] = key;
  }
  [[nodiscard]] bool contains(std::uint64_t key) const {
    for (std::size_t h = slot(key); slots_[h] != 0; h = (h + 1) & (slots_.size() - 1))
      if (slots_[h] == key) return true;
    return false;
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z, int level) {
    std::uint64_t k = std::uint64_t(x) * 0x9E3779B97F4A7C15ull ^ std::uint64_t(y) * 0xC2B2AE3D27D4EB4Full ^
                      std::uint64_t(z) * 0x165667B19E3779F9ull ^ std::uint64_t(level) * 0x27D4EB2F165667C5ull;
    k ^= k >> 31;
    return k == 0 ? 1 : k;  // 0 marks a free slot
  }

 private:
  [[nodiscard]] std::size_t slot(std::uint64_t key) const {
    return std::size_t(key * 0xD6E8FEB86659FD93ull >> 17) & (slots_.size() - 1);
  }
  std::vector<std::uint64_t> slots_;
};

/// Calls visit(key) for each cell of the range at `level` while it returns true; false if a visit
/// stopped it.
template <typename Visit>
bool for_each_cell(const CellRange& r, int level, Visit&& visit) {
  for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x)
    for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
      for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z)
        if (!visit(CellSet::key(x, y, z, level))) return false;
  return true;
}

/// Per face: moved (a corner unmarked), invalid (fewer than three corners, an index out of
/// range), or neither (kFar); and how many are moved.
std::size_t classify_faces(const PolygonMesh& mesh, std::span<const char> exact, std::vector<char>& state) {
  const std::size_t nf = mesh.faces.size(), nv = mesh.vertices.size();
  state.assign(nf, kFar);
  std::vector<std::size_t> moved_in(nf / kChunk + 1, 0);
  parallel_chunks(nf, kChunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      bool valid = mesh.faces[f].size() >= 3, moved = false;
      for (const int v : mesh.faces[f]) {
        valid = valid && v >= 0 && std::size_t(v) < nv;
        moved = moved || (valid && exact[std::size_t(v)] == 0);
      }
      state[f] = !valid ? kInvalid : moved ? kMoved : kFar;
      moved_in[begin / kChunk] += moved && valid ? 1 : 0;
    }
  });
  std::size_t moved = 0;
  for (const std::size_t m : moved_in) moved += m;
  return moved;
}

/// The cells that the moved faces' boxes meet, each box at the finest level where it meets at
/// most kMaxCells (long faces beside small ones: a sphere's cut through a fine mesh).
struct MarkedCells {
  double inverse_cell = 1;  ///< of the finest level's cells
  unsigned levels = 0;      ///< the levels that have marks
  CellSet cells{0};
};

/// Null when a moved box is not finite, or too large for every level (then every face is kept).
std::optional<MarkedCells> mark_moved(const PolygonMesh& mesh, const std::vector<char>& state, std::size_t moved) {
  // Cells of the power of two above the moved boxes' mean size (1-2 times it: a face meets fewer
  // cells, which costs fewer lookups than the faces it keeps in vain; armadillo's to_mesh: the
  // search 158 M -> 136 M instructions), so that x / cell is x times its inverse, exactly as
  // rounded.
  std::vector<Eigen::AlignedBox3d> boxes;  // the moved faces'
  boxes.reserve(moved);
  double extent = 0;
  for (std::size_t f = 0; f < state.size(); ++f)
    if (state[f] == kMoved) extent += boxes.emplace_back(face_box(mesh, mesh.faces[f])).sizes().maxCoeff();
  const double cell = moved > 0 && std::isfinite(extent) && extent > 0 ? extent / double(moved) : 1.0;
  MarkedCells out;
  out.inverse_cell = std::ldexp(1.0, -std::ilogb(cell) - 1);
  std::vector<std::pair<CellRange, int>> marks;  // (range, level)
  marks.reserve(moved);
  std::size_t count = 0;
  for (const Eigen::AlignedBox3d& box : boxes) {
    const CellRange finest = cell_range(box, out.inverse_cell);
    if (!finest.ok) return std::nullopt;
    int level = 0;
    CellRange r = finest;
    while (r.count() > kMaxCells && level + 1 < kLevels) r = finest.coarser(++level);
    if (r.count() > kMaxCells) return std::nullopt;
    marks.emplace_back(r, level);
    out.levels |= 1u << level;
    count += std::size_t(r.count());
  }
  out.cells = CellSet(count);
  for (const auto& [range, level] : marks)
    for_each_cell(range, level, [&](std::uint64_t key) {
      out.cells.insert(key);
      return true;
    });
  return out;
}

/// Whether a face's box meets a marked cell of some level (or meets too many cells to tell).
bool meets_marked(const Eigen::AlignedBox3d& box, const MarkedCells& marked) {
  const CellRange finest = cell_range(box, marked.inverse_cell);
  if (!finest.ok) return true;
  for (int level = 0; level < kLevels; ++level) {
    if ((marked.levels >> level & 1u) == 0) continue;
    const CellRange r = finest.coarser(level);
    if (r.count() > kMaxCells) return true;
    if (!for_each_cell(r, level, [&](std::uint64_t key) { return !marked.cells.contains(key); })) return true;
  }
  return false;
}

}  // namespace

std::vector<char> faces_near_moved(const PolygonMesh& mesh, std::span<const char> exact) {
  const std::size_t nf = mesh.faces.size();
  if (exact.size() != mesh.vertices.size() || nf == 0) return {};
  std::vector<char> state;
  const std::size_t moved = classify_faces(mesh, exact, state);
  if (2 * moved >= nf) return {};
  const std::optional<MarkedCells> marked = mark_moved(mesh, state, moved);
  if (!marked) return {};
  check_cancel();  // Ctrl-C (base/cancel.hpp)
  parallel_chunks(nf, kChunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f)
      if (state[f] == kFar && meets_marked(face_box(mesh, mesh.faces[f]), *marked)) state[f] = kNear;
  });
  return state;
}

}  // namespace sculpt::mesh::detail
