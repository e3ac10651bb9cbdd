#include "bsp/primitives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "base/errors.hpp"
#include "bsp/convex_path.hpp"
#include "bsp/rings/ring_solid.hpp"
#include "bsp/rings/sector_tree.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/solid_access.hpp"
#include "bsp/tree_builder.hpp"

namespace sculpt {

using bsp::detail::Ring;
using bsp::detail::SolidAccess;
using bsp::detail::SectorTree;
using kernel::Int128;
using kernel::Plane;

namespace {

void check_segments(int segments) {
  if (segments < 3 || segments > 1 << 16)
    throw InvalidInput("segments must be in [3, 65536], got " + std::to_string(segments));
}

void check_positive(double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v))
    throw InvalidInput(std::string(what) + " must be positive and finite");
}

// The regular polygon with `segments` vertices on the unit circle, the first at angle 0.
std::vector<Eigen::Vector2d> circle_points(int segments) {
  check_segments(segments);
  return circular_path(segments).vertices;
}

}  // namespace

Solid box(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const kernel::Grid& grid) {
  const kernel::GridPoint lo = grid.snap(min), hi = grid.snap(max);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    throw InvalidInput("box: min must be below max in every axis (after snapping to the grid)");
  TreeBuilder b;
  const Plane value[6] = {kernel::make_plane(1, 0, 0, -Int128(hi.x)), kernel::make_plane(-1, 0, 0, Int128(lo.x)),
                          kernel::make_plane(0, 1, 0, -Int128(hi.y)), kernel::make_plane(0, -1, 0, Int128(lo.y)),
                          kernel::make_plane(0, 0, 1, -Int128(hi.z)), kernel::make_plane(0, 0, -1, Int128(lo.z))};
  std::vector<std::int32_t> faces;
  for (const Plane& p : value) faces.push_back(b.add_plane(p));
  // The six faces, carried by the solid: face 2a + s (axis a, s = 0 for +, 1 for -) has the four
  // faces of the other two axes as edges, counter-clockwise about its outward normal.
  FragmentList boundary;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) right-handed
      // Counter-clockwise about +axis: +u, +v, -u, -v; about -axis the reverse cycle.
      int cycle[4] = {2 * u, 2 * v, 2 * u + 1, 2 * v + 1};
      if (side == 1) std::swap(cycle[1], cycle[3]);
      kernel::ConvexPolygon poly;
      poly.support = faces[std::size_t(2 * axis + side)];
      for (int i = 0; i < 4; ++i) {
        const int prev = cycle[(i + 3) % 4], edge = cycle[i];
        poly.corners.push_back({faces[std::size_t(edge)], faces[std::size_t(prev)], faces[std::size_t(edge)],
                                kernel::approximate_vertex(value[2 * axis + side], value[prev], value[edge])});
      }
      boundary.push_back({std::move(poly), false});
    }
  return SolidAccess::at_grid(std::move(b).build(b.add_convex_chain(faces), std::move(boundary), {.nodes_cut_cells = true}), grid);
}

Solid convex_polytope(const std::vector<HalfSpace>& half_spaces, const kernel::Grid& grid) {
  if (half_spaces.empty()) throw InvalidInput("convex_polytope needs at least one half-space");
  TreeBuilder b;
  std::vector<std::int32_t> faces;
  for (const HalfSpace& h : half_spaces) faces.push_back(b.add_plane(kernel::plane_from_normal(h.normal, h.offset, grid)));
  return SolidAccess::at_grid(std::move(b).build(b.add_convex_chain(faces)), grid);
}

Solid prism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1, const kernel::Grid& grid) {
  if (polygon.size() < 3) throw InvalidInput("prism: polygon needs at least 3 vertices");
  if (!(z0 < z1)) throw InvalidInput("prism: z0 must be below z1");
  // Exact side planes through grid points; a balanced tree needs the axis inside: build around
  // the snapped centroid, then translate (exact).
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : polygon) centroid += p;
  centroid /= double(polygon.size());
  const Eigen::Vector3d shift = grid.to_world(kernel::GridPoint{grid.snap(centroid.x()), grid.snap(centroid.y()), 0});
  const std::int64_t gz0 = grid.snap(z0), gz1 = grid.snap(z1);
  if (gz0 >= gz1) throw InvalidInput("prism: height below the grid step");
  std::vector<kernel::GridPoint> g;
  for (const auto& p : polygon) g.push_back(grid.snap(Eigen::Vector3d(p.x() - shift.x(), p.y() - shift.y(), 0.0)));
  TreeBuilder b;
  const int n = int(g.size());
  std::vector<std::int32_t> faces;
  std::vector<double> start;
  for (int j = 0; j < n; ++j) {
    const kernel::GridPoint& v = g[std::size_t(j)];
    const kernel::GridPoint& w = g[std::size_t((j + 1) % n)];
    const kernel::GridPoint up{v.x, v.y, v.z + 1};
    const Plane p = kernel::plane_through(v, w, up);
    if (!(p.d < 0)) throw InvalidInput("prism: polygon must be convex and counter-clockwise");
    faces.push_back(b.add_plane(p));
    start.push_back(std::atan2(double(v.y), double(v.x)));
  }
  for (int j = 1; j < n; ++j)
    while (start[std::size_t(j)] <= start[std::size_t(j - 1)]) start[std::size_t(j)] += 2 * std::numbers::pi;
  if (start[std::size_t(n - 1)] - start[0] >= 2 * std::numbers::pi)
    throw InvalidInput("prism: polygon must be convex and counter-clockwise");
  const TreeRef sides = SectorTree(b, start).build(faces);
  const std::int32_t bottom = b.add_plane(kernel::make_plane(0, 0, -1, Int128(gz0)));
  const std::int32_t top = b.add_plane(kernel::make_plane(0, 0, 1, -Int128(gz1)));
  const TreeRef root = b.add_node(bottom, b.add_node(top, sides, kOut), kOut);
  return translate(SolidAccess::at_grid(std::move(b).build(root), grid), shift);
}

Solid cylinder(double radius, double height, const CircularOptions& options) {
  return cone(radius, height, {.segments = options.segments, .center = options.center, .top_radius = radius, .grid = options.grid});
}

Solid cone(double radius, double height, const ConeOptions& options) {
  check_positive(radius, "cone radius");
  check_positive(height, "cone height");
  if (!(options.top_radius >= 0)) throw InvalidInput("cone top radius must be >= 0");
  const double z0 = options.center ? -height / 2 : 0.0;
  // The larger ring's vertices on grid points (a vertex on a box face stays on it; issue 35).
  return bsp::detail::revolve_rings(circle_points(options.segments), {{z0, radius}, {z0 + height, options.top_radius}},
                                    options.grid, /*snap_reference=*/true);
}

Solid sphere(double radius, const CircularOptions& options) {
  check_positive(radius, "sphere radius");
  check_segments(options.segments);
  const int rings = (options.segments + 1) / 2;
  // OpenSCAD's rings, and a vertex at each pole (issue 35: a sphere of radius r standing on a plane
  // at distance r touches it). Near the poles of a fine sphere the last ring and the pole snap to
  // one grid height; they merge into a flat cap at the pole's height (revolve_rings).
  std::vector<Ring> r{{-radius, 0}};
  for (int k = rings - 1; k >= 0; --k) {  // bottom to top
    const double phi = (k + 0.5) * std::numbers::pi / rings;
    r.push_back({radius * std::cos(phi), radius * std::sin(phi)});
  }
  r.push_back({radius, 0});
  return bsp::detail::revolve_rings(circle_points(options.segments), r, options.grid);
}

}  // namespace sculpt
