#include "revolution/revolve.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "base/errors.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/tree_builder.hpp"
#include "kernel/grid.hpp"
#include "kernel/plane.hpp"
#include "revolution/trees/profile_pieces.hpp"
#include "revolution/trees/revolve_plane_tree.hpp"

namespace sculpt::revolution {

using namespace detail;  // the trees of trees/
namespace {

using kernel::Int128;

/// The path on the lattice 2^-shift (integer coordinates X, Y), with its snapped ConvexPath.
struct LatticePath {
  std::vector<std::int64_t> x, y;
  int shift = 0;
};

/// Exact kernel plane of a PlaneTree node. Grid units: profile (R, Z) (the ends of the slab's line,
/// RevolveSlab::line_*), path (X, Y) / 2^shift.
/// A path line from P to Q with N = (Qy - Py, Px - Qx), C = N.P gives 2^shift N.(x, y) = C r(z);
/// times h = Z1 - Z0 with r(z) = (R0 (Z1 - z) + R1 (z - Z0)) / h this is
///   h 2^shift N.(x, y) - C (R1 - R0) z - C (R0 Z1 - R1 Z0) = 0,
/// the same line at a level for the slabs on both sides of it (no cracks).
kernel::Plane exact_plane(const PlaneTree::Node& node, const LatticePath& lattice,
                          const std::vector<std::int64_t>& level_z,
                          const std::vector<std::array<std::int64_t, 4>>& slabs) {
  if (node.slab < 0) return kernel::make_plane(0, 0, 1, -Int128(level_z[node.from]));
  const auto [z0, z1, r0, r1] = slabs[node.slab];
  const Int128 nx = lattice.y[node.to] - lattice.y[node.from];
  const Int128 ny = lattice.x[node.from] - lattice.x[node.to];
  const Int128 c = nx * lattice.x[node.from] + ny * lattice.y[node.from];
  const Int128 hs = Int128(z1 - z0) << lattice.shift;
  return kernel::make_plane(hs * nx, hs * ny, -c * Int128(r1 - r0), -c * (Int128(r0) * z1 - Int128(r1) * z0));
}

LatticePath lattice_path(const ConvexPath& path, int shift) {
  const double scale = std::ldexp(1.0, shift);
  LatticePath lattice;
  lattice.shift = shift;
  for (const auto& p : path.vertices) {
    lattice.x.push_back(std::llround(p.x() * scale));
    lattice.y.push_back(std::llround(p.y() * scale));
  }
  return lattice;
}

/// A snapped revolution of contiguous slabs in grid and lattice integers; each slab's planes are
/// written with the ends of its line (RevolveSlab::line_*, grid points).
struct ExactRevolution {
  LatticePath lattice;
  std::vector<std::int64_t> levels;                 // Z of each level
  std::vector<std::array<std::int64_t, 4>> slabs;   // Z0, Z1, R0, R1 of each slab's line

  ExactRevolution(const std::vector<RevolveSlab>& profile_slabs, const ConvexPath& path, int shift,
                  const kernel::Grid& grid)
      : lattice(lattice_path(path, shift)) {
    for (double z : slab_levels(profile_slabs)) levels.push_back(grid.snap(z));
    for (const auto& s : profile_slabs)
      slabs.push_back({grid.snap(s.line_z0), grid.snap(s.line_z1), grid.snap(s.line_r0), grid.snap(s.line_r1)});
  }
  [[nodiscard]] kernel::Plane plane(const PlaneTree::Node& node) const { return exact_plane(node, lattice, levels, slabs); }
};

/// The lines a revolution's planes are written with: an open profile's segments, or a closed
/// profile's non-horizontal edges off the axis (its pieces' slabs lie on them; edges on the axis
/// bound empty slabs, which get no planes).
std::vector<RevolveSlab> profile_lines(const SnappedRevolution& snapped) {
  if (!snapped.closed) return revolve_slabs(snapped.profile);
  std::vector<RevolveSlab> lines;
  const auto& p = snapped.profile;
  for (std::size_t k = 0; k < p.size(); ++k) {
    Eigen::Vector2d a = p[k], b = p[(k + 1) % p.size()];
    if (a.y() == b.y() || (a.x() == 0 && b.x() == 0)) continue;
    if (a.y() > b.y()) std::swap(a, b);
    lines.push_back(segment_slab(a.y(), b.y(), a.x(), b.x()));
  }
  return lines;
}

/// Every plane must fit the kernel's bit budget. The largest coefficients come from the largest
/// path-line and slab factors (a = h 2^shift N, c = C dR, d = C (R0 Z1 - R1 Z0)): one plane built
/// from those maxima (before dividing by a gcd: conservative) decides. \throw RangeError
void check_plane_budget(const std::vector<RevolveSlab>& lines, const SnappedRevolution& snapped,
                        const RevolveOptions& options) {
  const LatticePath lattice = lattice_path(snapped.path, snapped.path_bits);
  const kernel::Grid& grid = options.grid;
  Int128 n_max = 0, c_max = 0, h_max = 0, dr_max = 0, e_max = 0;
  for (const auto& line : build_path_tree(snapped.path, {.face_only_below = options.face_only_below}).nodes) {
    const Int128 nx = lattice.y[line.to] - lattice.y[line.from];
    const Int128 ny = lattice.x[line.from] - lattice.x[line.to];
    const Int128 c = nx * lattice.x[line.from] + ny * lattice.y[line.from];
    n_max = std::max({n_max, nx < 0 ? -nx : nx, ny < 0 ? -ny : ny});
    c_max = std::max(c_max, c < 0 ? -c : c);
  }
  for (const auto& s : lines) {
    const std::int64_t z0 = grid.snap(s.line_z0), z1 = grid.snap(s.line_z1);
    const std::int64_t r0 = grid.snap(s.line_r0), r1 = grid.snap(s.line_r1);
    const Int128 e = Int128(r0) * z1 - Int128(r1) * z0;
    h_max = std::max(h_max, Int128(z1 - z0));
    dr_max = std::max(dr_max, Int128(r1 > r0 ? r1 - r0 : r0 - r1));
    e_max = std::max(e_max, e < 0 ? -e : e);
  }
  const int shift = snapped.path_bits;
  (void)kernel::make_plane((h_max << shift) * n_max, (h_max << shift) * n_max, c_max * dr_max, c_max * e_max);
}

/// The section 6 solid of contiguous slabs (an open profile, or one chain of a closed one's piece).
Solid chain_solid(const std::vector<RevolveSlab>& slabs, const SnappedRevolution& snapped,
                  const RevolveOptions& options) {
  const PlaneTree tree = revolve_slab_tree(slabs, snapped.path, options);
  const ExactRevolution exact(slabs, snapped.path, snapped.path_bits, options.grid);

  // Children have larger indices than their parents: build bottom-up.
  TreeBuilder builder;
  std::vector<TreeRef> ref(tree.nodes.size(), kOut);
  auto child = [&](int c) -> TreeRef { return c >= 0 ? ref[c] : c; };
  for (int k = static_cast<int>(tree.nodes.size()) - 1; k >= 0; --k) {
    const auto& node = tree.nodes[k];
    const std::int32_t plane = builder.add_plane(exact.plane(node));
    ref[k] = builder.add_node(plane, child(node.below), child(node.above));
  }
  return std::move(builder).build(tree.root >= 0 ? ref[tree.root] : tree.root, BuildOptions{.grid = options.grid});
}

/// A closed profile's region revolved: per z-monotone piece the outer solid minus the inner one
/// (the cross-section at z is b(z) P minus a(z) P), and the union of the pieces, which meet only
/// in horizontal faces at the profile's vertex heights (exact planes on both sides).
Solid revolve_region(const SnappedRevolution& snapped, const RevolveOptions& options) {
  const std::vector<ProfilePiece> pieces = monotone_pieces(snapped.profile, options.grid);
  // b(z) P minus a(z) P is the region swept by r P, a <= r <= b, only if a P lies in b P: the
  // path must contain the axis (origin inside or on it; exact on the lattice).
  const LatticePath lattice = lattice_path(snapped.path, snapped.path_bits);
  const std::size_t n = lattice.x.size();
  bool around_axis = true;
  for (std::size_t k = 0; k < n; ++k)
    around_axis = around_axis &&
                  Int128(lattice.x[k]) * lattice.y[(k + 1) % n] - Int128(lattice.y[k]) * lattice.x[(k + 1) % n] >= 0;
  std::vector<Solid> solids;
  for (const ProfilePiece& piece : pieces) {
    Solid s = chain_solid(piece.outer, snapped, options);
    if (!piece.inner.empty()) {
      if (!around_axis)
        throw InvalidInput("revolve: a closed profile that leaves the axis (here between z = " +
                           std::to_string(piece.inner.front().z0) +
                           " and z = " + std::to_string(piece.inner.back().z1) +
                           ") needs a path around the axis (the origin inside or on the path)");
      s = std::move(s) - chain_solid(piece.inner, snapped, options);
    }
    solids.push_back(std::move(s));
  }
  return unite_all(std::move(solids));
}

/// The part of a full revolution between the half-planes through the z axis at 0 and `angle`
/// degrees: its intersection with a wedge of one or two half-spaces (two planes through the axis).
Solid cut_to_angle(Solid solid, const ConvexPath& path, const SnappedRevolution& snapped,
                   const RevolveOptions& options) {
  const double angle = options.angle;
  if (angle == 360) return solid;
  const double t = angle * std::numbers::pi / 180, c = std::cos(t), s = std::sin(t);
  // The direction at `angle`: a path vertex there (its exact lattice point, so the cut runs through
  // the solid's edges, adding no sliver faces), else (cos, sin) rounded to 30 bits.
  Int128 dx = std::llround(std::ldexp(c, 30)), dy = std::llround(std::ldexp(s, 30));
  for (std::size_t k = 0; k < path.vertices.size(); ++k) {
    const Eigen::Vector2d& v = path.vertices[k];
    if (v.x() * c + v.y() * s > 0 && std::abs(v.x() * s - v.y() * c) <= 1e-9 * v.norm()) {
      const Eigen::Vector2d& w = snapped.path.vertices[k];
      dx = std::llround(std::ldexp(w.x(), snapped.path_bits));
      dy = std::llround(std::ldexp(w.y(), snapped.path_bits));
      break;
    }
  }
  TreeBuilder b;
  const std::int32_t start = b.add_plane(kernel::make_plane(0, 1, 0, 0));   // y > 0: past the start
  const std::int32_t end = b.add_plane(kernel::make_plane(-dy, dx, 0, 0));  // < 0: before the end
  TreeRef root = kOut;
  if (angle == 180)
    root = b.add_node(start, kOut, kIn);
  else if (angle < 180)
    root = b.add_node(start, kOut, b.add_node(end, kIn, kOut));
  else
    root = b.add_node(start, b.add_node(end, kIn, kOut), kIn);
  return std::move(solid) & std::move(b).build(root, BuildOptions{.grid = options.grid});
}

}  // namespace

bool is_closed_profile(const std::vector<Eigen::Vector2d>& profile, const RevolveOptions& options) {
  return options.closed || (profile.size() >= 3 && profile.front() == profile.back());
}

SnappedRevolution snap_revolution(const std::vector<Eigen::Vector2d>& profile_in, const ConvexPath& path,
                                  const RevolveOptions& options) {
  if (options.face_only_below < 2)
    throw InvalidInput("revolve: face_only_below must be >= 2, got " + std::to_string(options.face_only_below));
  if (!(options.angle > 0 && options.angle <= 360))
    throw InvalidInput("revolve: angle must be in (0, 360] degrees, got " + std::to_string(options.angle));
  const bool closed = is_closed_profile(profile_in, options);
  std::vector<Eigen::Vector2d> profile = closed ? profile_in : monotone_profile(profile_in);
  double reach = 0.0;
  for (const auto& v : path.vertices) reach = std::max(reach, v.cwiseAbs().maxCoeff());
  const kernel::Grid& grid = options.grid;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    auto& p = profile[i];
    if (closed) check_profile_point(i, p);
    if (p.x() * reach > grid.max_world()) {
      std::ostringstream what;
      what << "revolved solid reaching " << p.x() * reach << " from the axis";
      throw RangeError(grid.out_of_range(what.str(), p.x() * reach));
    }
    if (!closed) p = Eigen::Vector2d(grid.to_world(double(grid.snap(p.x()))), grid.to_world(double(grid.snap(p.y()))));
  }
  if (closed)
    profile = closed_profile(profile, grid);
  else
    monotone_profile(profile);  // snapping keeps z monotone but may flatten it: check again
  const int magnitude = std::max(0, static_cast<int>(std::ceil(std::log2(reach))));
  for (int bits = 18; bits >= 8; --bits) {
    const int shift = std::max(0, bits - magnitude);
    const double scale = std::ldexp(1.0, shift);
    std::vector<Eigen::Vector2d> v;
    for (const auto& p : path.vertices) v.emplace_back(std::round(p.x() * scale) / scale, std::round(p.y() * scale) / scale);
    try {
      SnappedRevolution out{profile, polygon_path(std::move(v)), shift, closed};
      check_plane_budget(profile_lines(out), out, options);
      return out;
    } catch (const InvalidInput&) {  // strict convexity lost on this lattice; coarser is worse
      break;
    } catch (const RangeError&) {    // planes too large: try a coarser lattice
    }
  }
  throw GeometryError("path of " + std::to_string(path.edges()) +
                      " edges cannot be represented exactly enough to stay convex within the kernel's plane "
                      "bit budget; use fewer edges or a smaller profile (docs/revolution.md)");
}

Solid revolve(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path, const RevolveOptions& options) {
  const SnappedRevolution snapped = snap_revolution(profile, path, options);
  Solid solid =
      snapped.closed ? revolve_region(snapped, options) : chain_solid(revolve_slabs(snapped.profile), snapped, options);
  return cut_to_angle(std::move(solid), path, snapped, options);
}

}  // namespace sculpt::revolution
