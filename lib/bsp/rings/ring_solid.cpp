#include "bsp/rings/ring_solid.hpp"

#include "base/cancel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

#include "base/errors.hpp"
#include "bsp/local/deferred_build.hpp"
#include "bsp/rings/ring_boundary.hpp"
#include "bsp/rings/sector_tree.hpp"
#include "bsp/tree/solid_access.hpp"
#include "bsp/tree_builder.hpp"

namespace sculpt::bsp::detail {

using kernel::Int128;
using kernel::Plane;

namespace {

constexpr int kPathNormalBits = 26;  // integer 2D normals of the path edges (docs/kernel.md)
constexpr double kPathScale = double(std::int64_t(1) << kPathNormalBits);  // scaling by it is exact

/// Rings whose heights snap to the same grid value become one ring with the group's largest scale
/// (the polar rings of a fine sphere: a flat cap). Each height of the group lay within half a step
/// of the kept value, so the surface moves by at most half a step. Heights that decrease are an
/// error; a ring of scale 0 inside the stack too, unless it merges into a ring of positive scale.
std::vector<Ring> merge_rings_on_grid(const std::vector<Ring>& rings, const kernel::Grid& grid) {
  std::vector<Ring> merged;
  merged.reserve(rings.size());
  std::int64_t last = 0;
  for (std::size_t k = 0; k < rings.size(); ++k) {
    if (!(rings[k].scale >= 0) || !std::isfinite(rings[k].scale) || !std::isfinite(rings[k].z))
      throw InvalidInput("ring height must be finite and ring scale finite and >= 0");
    if (k > 0 && !(rings[k].z > rings[k - 1].z)) throw InvalidInput("ring heights must increase");
    const std::int64_t z = grid.snap(rings[k].z);
    if (!merged.empty() && z == last) {
      merged.back().scale = std::max(merged.back().scale, rings[k].scale);
      continue;
    }
    merged.push_back({.z = grid.to_world(double(z)), .scale = rings[k].scale});
    last = z;
  }
  for (std::size_t k = 1; k + 1 < merged.size(); ++k)
    if (merged[k].scale == 0) throw InvalidInput("only the first and the last ring may have scale 0");
  if (merged.size() < 2) {
    // Name a grid that resolves it: 256 steps across its height, so that the snapped rings keep
    // its shape to about 1 % (docs/language.md, "World range").
    std::ostringstream s;
    s << "revolved solid is thinner than one grid step (" << grid.name() << " = " << grid.step() << ")";
    const double height = rings.back().z - rings.front().z;
    const int shift = static_cast<int>(std::ceil(std::log2(256 / height)));
    if (height > 0 && shift > grid.shift() && shift <= kernel::Grid::kMaxShift) {
      const kernel::Grid finer = kernel::Grid::from_shift(shift);
      s << ": its height " << height << " needs a finer grid, e.g. grid(pow(2, " << -shift << ")) (step "
        << finer.step() << ", coordinates up to " << finer.max_world() << ")";
    }
    throw InvalidInput(s.str());
  }
  return merged;
}

/// The reference ring's polygon snapped to the grid (issue 35, "flush stays flush"): vertex j is
/// the grid point nearest to scale * path[j], so a vertex the user's numbers put on a grid point
/// (a cylinder's vertex on a box face) is exactly there. Empty when the snapped polygon is not
/// strictly convex, counter-clockwise around the axis (fine paths at small scales: snapping moves
/// a vertex by up to half a step, more than a nearly straight turn); the caller then keeps the
/// path's own vertices.
std::vector<kernel::GridPoint> snapped_ring(const std::vector<Eigen::Vector2d>& path, double scale,
                                            const kernel::Grid& grid) {
  const std::size_t n = path.size();
  std::vector<kernel::GridPoint> g(n);
  for (std::size_t j = 0; j < n; ++j) g[j] = grid.snap(Eigen::Vector3d(scale * path[j].x(), scale * path[j].y(), 0.0));
  for (std::size_t j = 0; j < n; ++j) {
    const kernel::GridPoint &a = g[(j + n - 1) % n], &b = g[j], &c = g[(j + 1) % n];
    // Every turn strictly left (coordinates below 2^25: the products fit Int128 easily) and the
    // axis strictly inside every edge's line.
    const Int128 turn = Int128(b.x - a.x) * (c.y - b.y) - Int128(b.y - a.y) * (c.x - b.x);
    const Int128 inside = Int128(b.x) * (c.y - b.y) - Int128(b.y) * (c.x - b.x);
    if (!(turn > 0) || !(inside > 0)) return {};
  }
  return g;
}

// The solid of revolution (revolve_rings). With `boundary_only`, its direct boundary alone,
// without the tree (nothing when the boundary must be extracted from the tree).
std::optional<Solid> build_rings(const std::vector<Eigen::Vector2d>& given_path, const std::vector<Ring>& given_rings,
                                 const kernel::Grid& grid, bool snap_reference, bool boundary_only) {
  if (given_rings.size() < 2) throw InvalidInput("revolution needs at least 2 rings");
  const std::vector<Ring> rings = merge_rings_on_grid(given_rings, grid);
  const int n = int(given_path.size());
  if (n < 3) throw InvalidInput("revolution path needs at least 3 vertices");
  // The reference ring (the first of largest scale) has its vertices on grid points and its edge
  // lines through them, exactly (integer normals and offsets); every other ring's edge lines are
  // parallel to those (planar band faces), offsets scaled and rounded. Without a valid snapped
  // polygon, normals and offsets are rounded from the path (below).
  std::size_t ref = 0;
  for (std::size_t k = 1; k < rings.size(); ++k)
    if (rings[k].scale > rings[ref].scale) ref = k;
  const double ref_scale = rings[ref].scale;
  for (const Eigen::Vector2d& v : given_path)
    if (!v.allFinite()) throw InvalidInput("revolution path vertex is not finite");
  // The reach check first (its message names the solid): each edge line's distance from the axis
  // at the largest ring, with a margin of 1.5.
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d& v = given_path[std::size_t(j)];
    const Eigen::Vector2d e = given_path[std::size_t((j + 1) % n)] - v;
    if (!(e.norm() > 0)) continue;  // refused below
    const double c = grid.to_grid(ref_scale * std::fabs(Eigen::Vector2d(e.y(), -e.x()).normalized().dot(v)));
    if (c * 1.5 > double(kernel::kMaxCoord)) {
      const double reach = grid.to_world(c * 1.5);
      std::ostringstream what;
      what << "revolved solid (reach " << reach << ")";
      throw RangeError(grid.out_of_range(what.str(), reach));
    }
  }
  const std::vector<kernel::GridPoint> snapped =
      snap_reference && ref_scale > 0 ? snapped_ring(given_path, ref_scale, grid) : std::vector<kernel::GridPoint>{};
  std::vector<Eigen::Vector2d> snapped_path;
  if (!snapped.empty()) {  // the snapped polygon in the path's units, for angles and lengths
    const double unit = grid.to_grid(ref_scale);
    for (const kernel::GridPoint& g : snapped) snapped_path.emplace_back(double(g.x) / unit, double(g.y) / unit);
  }
  const std::vector<Eigen::Vector2d>& path = snapped.empty() ? given_path : snapped_path;
  std::vector<Int128> c_ref(static_cast<std::size_t>(n));
  // Path edges: integer outward normals and offsets (the origin must be strictly inside).
  std::vector<Eigen::Vector2d> normal(static_cast<std::size_t>(n));
  std::vector<std::int64_t> nx(static_cast<std::size_t>(n)), ny(static_cast<std::size_t>(n));
  std::vector<double> offset(static_cast<std::size_t>(n)), start(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d& v = path[std::size_t(j)];
    const Eigen::Vector2d& w = path[std::size_t((j + 1) % n)];
    Eigen::Vector2d e = w - v;
    if (!(e.norm() > 0)) throw InvalidInput("revolution path has repeated vertices");
    Eigen::Vector2d m(e.y(), -e.x());
    m.normalize();
    normal[std::size_t(j)] = m;
    if (!snapped.empty()) {  // exact: (dy, -dx) of the grid edge, through its grid points
      const kernel::GridPoint &a = snapped[std::size_t(j)], &c = snapped[std::size_t((j + 1) % n)];
      nx[std::size_t(j)] = c.y - a.y;
      ny[std::size_t(j)] = a.x - c.x;
      // Scaled by a power of two up to 26 bits like the rounded normals, so that the other rings'
      // rounded offsets move their lines by at most 2^-27 grid units as before.
      const std::int64_t top = std::max(std::llabs(nx[std::size_t(j)]), std::llabs(ny[std::size_t(j)]));
      int shift = 0;
      while ((top << (shift + 1)) <= (std::int64_t(1) << kPathNormalBits)) ++shift;
      nx[std::size_t(j)] *= std::int64_t(1) << shift;
      ny[std::size_t(j)] *= std::int64_t(1) << shift;
      c_ref[std::size_t(j)] = Int128(nx[std::size_t(j)]) * a.x + Int128(ny[std::size_t(j)]) * a.y;
    } else {
      nx[std::size_t(j)] = std::llround(std::ldexp(m.x(), kPathNormalBits));
      ny[std::size_t(j)] = std::llround(std::ldexp(m.y(), kPathNormalBits));
    }
    offset[std::size_t(j)] = m.dot(v);
    if (!(offset[std::size_t(j)] > 0))
      throw InvalidInput("revolution path must be convex, counter-clockwise and contain the axis");
    start[std::size_t(j)] = std::atan2(v.y(), v.x());
  }
  double min_edge = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) min_edge = std::min(min_edge, (path[std::size_t((j + 1) % n)] - path[std::size_t(j)]).norm());
  for (int j = 1; j < n; ++j)  // unwrap to increasing angles
    while (start[std::size_t(j)] <= start[std::size_t(j - 1)]) start[std::size_t(j)] += 2 * std::numbers::pi;
  if (start[std::size_t(n - 1)] - start[0] >= 2 * std::numbers::pi)
    throw InvalidInput("revolution path must be convex and counter-clockwise");

  // Rings on the grid: z in grid units, offsets c = scale * offset in grid units * normal scale.
  const std::size_t r = rings.size();
  std::vector<std::int64_t> z(r);
  for (std::size_t k = 0; k < r; ++k) z[k] = grid.snap(rings[k].z);
  auto c_of = [&](std::size_t k, int j) -> Int128 {
    if (!snapped.empty()) {  // the reference ring's exact offset, scaled (|C| < 2^52: exact double)
      if (rings[k].scale == ref_scale) return c_ref[std::size_t(j)];
      return Int128(std::llround(double(c_ref[std::size_t(j)]) * (rings[k].scale / ref_scale)));
    }
    const double c = grid.to_grid(rings[k].scale * offset[std::size_t(j)]);
    if (std::fabs(c) * 1.5 > double(kernel::kMaxCoord)) {
      const double reach = grid.to_world(std::fabs(c) * 1.5);  // with the margin of the check
      std::ostringstream what;
      what << "revolved solid (reach " << reach << ")";
      throw RangeError(grid.out_of_range(what.str(), reach));
    }
    return Int128(std::llround(c * kPathScale));
  };

  // Path vertices on the axes whose ring vertices lie exactly on y = 0 or x = 0 (SectorOptions):
  // at ring k, edges p = j - 1 and q = j meet where nx_p x + ny_p y = C_p and nx_q x + ny_q y = C_q
  // (C = c_of(k, .), |C| < 2^51, |n| <= 2^26: the products are exact), so the vertex has y = 0 iff
  // nx_p C_q = nx_q C_p, and x = 0 iff C_p ny_q = C_q ny_p. A ring of scale 0 is on the axis.
  std::array<int, 4> axis_vertex = {-1, -1, -1, -1};  // +x, +y, -x, -y
  for (int j = 0; j < n; ++j) {
    // Candidates: path vertices within 1e-9 rad of an axis (no trigonometry: |other| <= 1e-9 |own|).
    const double x = path[std::size_t(j)].x(), y = path[std::size_t(j)].y();
    const int d = std::fabs(y) <= 1e-9 * std::fabs(x) ? (x > 0 ? 0 : 2) : (std::fabs(x) <= 1e-9 * std::fabs(y) ? (y > 0 ? 1 : 3) : -1);
    if (d >= 0) {
      const std::size_t p = std::size_t((j + n - 1) % n), q = std::size_t(j);
      bool on = true;
      for (std::size_t k = 0; k < rings.size() && on; ++k) {
        const Int128 cp = c_of(k, int(p)), cq = c_of(k, int(q));
        on = d % 2 == 0 ? Int128(nx[p]) * cq == Int128(nx[q]) * cp : cp * ny[q] == cq * ny[p];
      }
      if (on) axis_vertex[std::size_t(d)] = j;
    }
  }

  // The direct boundary needs every path edge on every ring of positive scale. Rounding moves an
  // edge's line by at most delta_k grid units at ring k, which moves its ends by at most
  // 2 delta_k / sin(exterior angle): edges much longer than that survive.
  std::vector<double> scale(r);
  for (std::size_t k = 0; k < r; ++k) scale[k] = rings[k].scale;
  double min_sin = 1, far = 0;
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector2d& a = normal[std::size_t(j)];
    const Eigen::Vector2d& c = normal[std::size_t((j + 1) % n)];
    min_sin = std::min(min_sin, std::fabs(a.x() * c.y() - a.y() * c.x()));
    far = std::max(far, path[std::size_t(j)].norm());
  }
  // Normals rounded to 2^-26 turn a line by 2^-26, moving it by R_k 2^-26 within ring k's radius
  // R_k (every ring shares the normals: a ring is the rounded polygon scaled); offsets are rounded
  // to 2^-27 grid units: delta_k below (R_k + 1) 2^-25, taken with a margin of 2. Two lines moved
  // by delta_k at exterior angle t meet at most 2 delta_k / sin t away, so an edge of length L_k
  // survives if L_k sin t > 4 delta_k; 8 delta_k leaves another factor of 2. Checked ring by ring:
  // with the largest ring's delta for all, a fine sphere's rings near its poles (edges under a
  // grid unit, but moved as little) failed, and its boundary came from the tree (1.2 s at 1000
  // segments).
  // With the snapped reference ring, normals are exact and the other rings' offsets are rounded to
  // integers: a line moves by at most 1 / (2 |n|) grid units (|n| >= 2^25); the bound holds too.
  const bool degenerate = r == 2 && !(scale[0] > 0) && !(scale[1] > 0);
  bool direct = !degenerate;
  for (std::size_t k = 0; k < r && direct; ++k) {
    if (!(scale[k] > 0)) continue;
    const double delta = (grid.to_grid(scale[k] * far) + 1) * std::ldexp(1.0, -24);
    direct = grid.to_grid(scale[k] * min_edge) * min_sin > 8 * delta;
  }
  if (boundary_only && !direct) return std::nullopt;

  TreeBuilder b;
  // Below that bound, rounding can move a face out of the wedge whose chain should hold it: the
  // solid then bends along an axial plane, which must then count as a face plane (not auxiliary)
  // for extraction to find that boundary. Chains are widened so that this stays rare.
  std::optional<SectorTree> sectors;
  if (!boundary_only)
    sectors.emplace(b, start,
                    SectorOptions{.auxiliary_axes = direct, .widen = direct ? 0 : 1, .axis_vertex = axis_vertex});
  // Exactly: the ring planes, per band n face planes, its axial planes and the opposite of its
  // lower ring plane; the two cap nodes, the inner ring nodes and each band's sector tree.
  b.reserve(
      std::size_t(kernel::kWorldPlanes) + r + (r - 1) * (std::size_t(n) + (sectors ? sectors->axial_planes() : 0) + 1),
      sectors ? r + (r - 1) * sectors->nodes() : 0);
  // Ring planes z = z_k: f = z - z_k.
  std::vector<std::int32_t> ring_plane(r);
  std::vector<std::vector<std::int32_t>> face_index(r - 1);
  // Inner rings only separate bands (auxiliary); the first and last ring planes are the caps.
  for (std::size_t k = 0; k < r; ++k) {
    ring_plane[k] = b.add_plane(kernel::make_plane(0, 0, 1, -Int128(z[k])), k > 0 && k + 1 < r);
  }
  // The x, y part of a face normal is dz (nx, ny): the gcd of those two is dz gcd(nx, ny), so
  // make_plane needs only the gcd with the z part (the same planes, one gcd per face less).
  std::vector<std::uint64_t> xy_gcd(static_cast<std::size_t>(n));
  for (std::size_t j = 0; j < std::size_t(n); ++j)
    xy_gcd[j] = std::gcd(std::uint64_t(std::llabs(nx[j])), std::uint64_t(std::llabs(ny[j])));
  std::vector<Int128> c_below(static_cast<std::size_t>(n)), c_above(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) c_above[std::size_t(j)] = c_of(0, j);
  // Band k's face planes and tree (bands come in increasing order).
  std::vector<Plane> face_plane(static_cast<std::size_t>(n));
  auto band = [&](std::size_t k) -> TreeRef {
    const Int128 dz = z[k + 1] - z[k];
    std::swap(c_below, c_above);  // ring k's offsets were ring k + 1's of the band below
    for (int j = 0; j < n; ++j) c_above[std::size_t(j)] = c_of(k + 1, j);
    std::vector<std::int32_t> faces(static_cast<std::size_t>(n));
    // All planes first, then into the table: one just returned by make_plane (written in 8-byte
    // parts) and copied at once by PlaneTable::add (16-byte loads) waited for its stores to leave
    // the store queue (failed store forwarding, ~6 % of sphere(32)). Placement new: made in place.
    for (std::size_t j = 0; j < std::size_t(n); ++j) {
      const Int128 c0 = c_below[j], dc = c_above[j] - c0;
      // dz (n . (x, y)) - dc z + (dc z_k - dz c_k) = 0, positive outside. The gcd of all four is
      // gcd(dz X, dc, dc z_k - dz c_k) = gcd(dc, dz gcd(X, c_k)) with X = gcd(nx, ny): a divisor of
      // dz X and dc divides d exactly when it divides dz c_k (|c| < 2^52, dz X < 2^53).
      const std::uint64_t x = xy_gcd[j], c0m = std::uint64_t(c0 < 0 ? -c0 : c0);
      const std::uint64_t y = std::uint64_t(dz) * (x == 1 ? 1 : std::gcd(x, c0m % x));
      const std::uint64_t dcm = std::uint64_t(dc < 0 ? -dc : dc);
      ::new (&face_plane[j]) Plane(kernel::make_plane(dz * nx[j], dz * ny[j], -dc, dc * z[k] - dz * c0,
                                                      {.gcd = y == 1 ? 1 : std::gcd(y, dcm % y)}));
    }
    for (std::size_t j = 0; j < std::size_t(n); ++j) faces[j] = b.add_plane(face_plane[j]);
    const double min_scale = std::min(rings[k].scale, rings[k + 1].scale);
    const TreeRef t = sectors ? sectors->build(faces, 0.05 * min_scale * min_edge, grid) : kOut;
    face_index[k] = std::move(faces);
    return t;
  };
  if (boundary_only) {
    // The face planes of every band, then the boundary on them; the tree when first used.
    CancelPoll poll;  // Ctrl-C and the memory limit (base/cancel.hpp)
    for (std::size_t k = 0; k + 1 < r; ++k) {
      poll.tick(std::uint32_t(n));
      band(k);
    }
    FragmentList boundary = ring_boundary(b, ring_plane, face_index, scale);
    return SolidAccess::at_grid(solid_with_tree_later(b.planes(), std::move(boundary), false,
                                                      [given_path, given_rings, grid, snap_reference] {
                                                        return *build_rings(given_path, given_rings, grid,
                                                                            snap_reference, false);
                                                      }),
                                grid);
  }
  // The tree top-down in pre-order (TreeBuilder::open_nodes), so the builder keeps it as laid out:
  // the bottom cap's plane, the top cap's, then a balanced tree over the bands split by the inner
  // ring planes (explicit recursion depth is log2 of the ring count), lower bands first.
  const TreeRef root = b.open_nodes(2), top = root + 1;
  auto slabs = [&](auto&& self, std::size_t lo, std::size_t hi) -> TreeRef {
    if (lo == hi) return band(lo);
    const std::size_t m = (lo + hi + 1) / 2;  // ring between band m - 1 and band m
    const TreeRef node = b.open_nodes(1);
    const TreeRef negative = self(self, lo, m - 1);
    b.set_node(node, ring_plane[m], negative, self(self, m, hi));
    return node;
  };
  b.set_node(top, ring_plane[r - 1], slabs(slabs, 0, r - 2), kOut);
  b.set_node(root, ring_plane[0], kOut, top);
  if (!direct) return SolidAccess::at_grid(std::move(b).build(root), grid);
  // Every node then cuts its cell: ring planes cut their slabs and axial planes their wedges (both
  // reach the world box), and each chain face keeps the middle part of its facet inside its wedge
  // (wedges end at face middles, facets are convex and survive rounding), so the tree is kept as
  // built. Widened chains may hold faces outside their wedges: those are left to the full build.
  FragmentList boundary = ring_boundary(b, ring_plane, face_index, scale);
  return SolidAccess::at_grid(std::move(b).build(root, std::move(boundary), {.nodes_cut_cells = !sectors->widened()}),
                              grid);
}

}  // namespace

Solid revolve_rings(const std::vector<Eigen::Vector2d>& path, const std::vector<Ring>& given_rings,
                    const kernel::Grid& grid, bool snap_reference) {
  // The direct boundary now, the section-6 tree when something first reads it (set operations by
  // cells, output and volume read the boundary alone).
  if (std::optional<Solid> later = build_rings(path, given_rings, grid, snap_reference, true)) return std::move(*later);
  return std::move(*build_rings(path, given_rings, grid, snap_reference, false));
}

}  // namespace sculpt::bsp::detail
