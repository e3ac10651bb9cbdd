#include "revolution/revolve.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "base/errors.hpp"
#include "bsp/tree_builder.hpp"
#include "kernel/grid.hpp"
#include "kernel/plane.hpp"
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

/// Exact kernel plane of a PlaneTree node. Grid units: profile (R, Z), path (X, Y) / 2^shift.
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

/// A snapped revolution in grid and lattice integers.
struct ExactRevolution {
  LatticePath lattice;
  std::vector<std::int64_t> levels;                 // Z of each level
  std::vector<std::array<std::int64_t, 4>> slabs;   // Z0, Z1, R0, R1

  ExactRevolution(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path, int shift, const kernel::Grid& grid) {
    const double scale = std::ldexp(1.0, shift);
    lattice.shift = shift;
    for (const auto& p : path.vertices) {
      lattice.x.push_back(std::llround(p.x() * scale));
      lattice.y.push_back(std::llround(p.y() * scale));
    }
    for (double z : revolve_levels(profile)) levels.push_back(grid.snap(z));
    for (const auto& s : revolve_slabs(profile))
      slabs.push_back({grid.snap(s.z0), grid.snap(s.z1), grid.snap(s.r0), grid.snap(s.r1)});
  }
  [[nodiscard]] kernel::Plane plane(const PlaneTree::Node& node) const { return exact_plane(node, lattice, levels, slabs); }
};

}  // namespace

SnappedRevolution snap_revolution(const std::vector<Eigen::Vector2d>& profile_in, const ConvexPath& path,
                                  const RevolveOptions& options) {
  if (options.face_only_below < 2)
    throw InvalidInput("revolve: face_only_below must be >= 2, got " + std::to_string(options.face_only_below));
  std::vector<Eigen::Vector2d> profile = monotone_profile(profile_in);
  double reach = 0.0;
  for (const auto& v : path.vertices) reach = std::max(reach, v.cwiseAbs().maxCoeff());
  const kernel::Grid& grid = options.grid;
  for (auto& p : profile) {
    if (p.x() * reach > grid.max_world()) {
      std::ostringstream what;
      what << "revolved solid reaching " << p.x() * reach << " from the axis";
      throw RangeError(grid.out_of_range(what.str(), p.x() * reach));
    }
    p = Eigen::Vector2d(grid.to_world(double(grid.snap(p.x()))), grid.to_world(double(grid.snap(p.y()))));
  }
  monotone_profile(profile);  // snapping keeps z monotone but may flatten it: check again
  const int magnitude = std::max(0, static_cast<int>(std::ceil(std::log2(reach))));
  for (int bits = 18; bits >= 8; --bits) {
    const int shift = std::max(0, bits - magnitude);
    const double scale = std::ldexp(1.0, shift);
    std::vector<Eigen::Vector2d> v;
    for (const auto& p : path.vertices) v.emplace_back(std::round(p.x() * scale) / scale, std::round(p.y() * scale) / scale);
    try {
      SnappedRevolution out{profile, polygon_path(std::move(v)), shift};
      // Every plane must fit the kernel's bit budget. The largest coefficients come from the
      // largest path-line and slab factors (a = h 2^shift N, c = C dR, d = C (R0 Z1 - R1 Z0)):
      // one plane built from those maxima (before dividing by a gcd: conservative) decides.
      const ExactRevolution exact(out.profile, out.path, shift, grid);
      Int128 n_max = 0, c_max = 0, h_max = 0, dr_max = 0, e_max = 0;
      for (const auto& line : build_path_tree(out.path, {.face_only_below = options.face_only_below}).nodes) {
        const Int128 nx = exact.lattice.y[line.to] - exact.lattice.y[line.from];
        const Int128 ny = exact.lattice.x[line.from] - exact.lattice.x[line.to];
        const Int128 c = nx * exact.lattice.x[line.from] + ny * exact.lattice.y[line.from];
        n_max = std::max({n_max, nx < 0 ? -nx : nx, ny < 0 ? -ny : ny});
        c_max = std::max(c_max, c < 0 ? -c : c);
      }
      for (const auto& [z0, z1, r0, r1] : exact.slabs) {
        const Int128 e = Int128(r0) * z1 - Int128(r1) * z0;
        h_max = std::max(h_max, Int128(z1 - z0));
        dr_max = std::max(dr_max, Int128(r1 > r0 ? r1 - r0 : r0 - r1));
        e_max = std::max(e_max, e < 0 ? -e : e);
      }
      (void)kernel::make_plane((h_max << shift) * n_max, (h_max << shift) * n_max, c_max * dr_max, c_max * e_max);
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
  const PlaneTree tree = revolve_plane_tree(snapped.profile, snapped.path, options);
  const ExactRevolution exact(snapped.profile, snapped.path, snapped.path_bits, options.grid);

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

}  // namespace sculpt::revolution
