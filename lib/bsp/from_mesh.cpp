#include "bsp/from_mesh.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "base/errors.hpp"
#include "bsp/local/deferred_build.hpp"
#include "bsp/tree/autopartition.hpp"
#include "bsp/tree/solid_access.hpp"
#include "bsp/tree/triangle_fragment.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {

using kernel::ConvexPolygon;
using kernel::GridPoint;
using kernel::Int128;
using kernel::Plane;

namespace {

GridPoint sub(const GridPoint& a, const GridPoint& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

std::string folded_message(std::size_t face, const Eigen::Vector3d& near, const kernel::Grid& grid) {
  std::ostringstream s;
  s << "from_mesh: face " << face << " near (" << near.x() << ", " << near.y() << ", " << near.z()
    << ") folds when its vertices are snapped to the exact kernel's grid (step " << grid.name()
    << "): the mesh has features smaller than the grid step";
  return s.str();
}

}  // namespace

Solid from_mesh(const PolygonMesh& mesh, const FromMeshOptions& options) {
  const kernel::Grid& grid = options.grid;
  if (mesh.faces.empty()) return Solid::leaf(false, grid);
  std::vector<GridPoint> g;
  g.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) g.push_back(grid.snap(v));

  kernel::PlaneTable table;
  table.reserve(std::size_t(kernel::kWorldPlanes) + 4 * mesh.faces.size() + mesh.faces.size() / 2);
  std::vector<ConvexPolygon> polys;
  polys.reserve(mesh.faces.size());
  Int128 volume6 = 0;  // six times the signed volume of the snapped triangles (exact: |coords| < 2^26)
  for (std::size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const auto& f = mesh.faces[fi];
    if (f.size() < 3) throw InvalidInput("from_mesh: face " + std::to_string(fi) + " has fewer than 3 vertices");
    for (int i : f)
      if (i < 0 || std::size_t(i) >= g.size())
        throw InvalidInput("from_mesh: face " + std::to_string(fi) + " has a vertex index out of range");
    // Face plane: the corner triple with the largest normal (robust for nearly straight corners).
    Plane best{};
    Int128 best_len = 0;
    const std::size_t m = f.size();
    for (std::size_t i = 0; i < m; ++i) {
      const GridPoint& a = g[std::size_t(f[(i + m - 1) % m])];
      const GridPoint& b = g[std::size_t(f[i])];
      const GridPoint& c = g[std::size_t(f[(i + 1) % m])];
      const GridPoint u = sub(b, a), w = sub(c, b);
      const Int128 nx = Int128(u.y) * w.z - Int128(u.z) * w.y, ny = Int128(u.z) * w.x - Int128(u.x) * w.z,
                   nz = Int128(u.x) * w.y - Int128(u.y) * w.x;
      const Int128 len = (nx < 0 ? -nx : nx) + (ny < 0 ? -ny : ny) + (nz < 0 ? -nz : nz);
      if (len > best_len) {
        best_len = len;
        best = kernel::plane_through(a, b, c);
      }
    }
    if (best_len == 0) {
      if (options.skip_degenerate_faces) continue;
      throw InvalidInput("from_mesh: face " + std::to_string(fi) + " is degenerate (collinear vertices)");
    }
    // The largest corner may be a reflex corner of a non-convex face: orient the plane by the
    // face's area vector (Newell's method, exact on the snapped grid points) instead.
    Int128 area[3] = {0, 0, 0};
    for (std::size_t i = 0; i < m; ++i) {
      const GridPoint& a = g[std::size_t(f[i])];
      const GridPoint& b = g[std::size_t(f[(i + 1) % m])];
      area[0] += Int128(a.y) * b.z - Int128(a.z) * b.y;
      area[1] += Int128(a.z) * b.x - Int128(a.x) * b.z;
      area[2] += Int128(a.x) * b.y - Int128(a.y) * b.x;
    }
    const Int128 along = area[0] * best.a + area[1] * best.b + area[2] * best.c;
    if (along == 0) throw GeometryError(folded_message(fi, mesh.vertices[std::size_t(f[0])], grid));
    if (along < 0) best = best.opposite();
    // Orientation of the face before snapping: a snapped triangle turned against it is a fold.
    Eigen::Vector3d original = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < m; ++i)
      original += mesh.vertices[std::size_t(f[i])].cross(mesh.vertices[std::size_t(f[(i + 1) % m])]);
    // A face whose snapped vertices are not exactly coplanar is split into triangles, each on
    // its own plane, so that the polygons still close up exactly.
    bool planar = true;
    for (int i : f) planar = planar && best.eval(g[std::size_t(i)]) == 0;
    const std::int32_t support = table.add(best);
    // Triangulate (faces may be non-convex); every triangle is a convex plane-based polygon.
    std::vector<Eigen::Vector3d> pts;
    std::vector<int> local;
    for (std::size_t i = 0; i < m; ++i) {
      pts.push_back(grid.to_world(g[std::size_t(f[i])]));
      local.push_back(int(i));
    }
    for (const IndexTriangle& tri : triangulate_polygon(pts, local)) {
      const GridPoint v[3] = {g[std::size_t(f[std::size_t(tri[0])])], g[std::size_t(f[std::size_t(tri[1])])],
                              g[std::size_t(f[std::size_t(tri[2])])]};
      const GridPoint u = sub(v[1], v[0]), w = sub(v[2], v[0]);
      if (Int128(u.y) * w.z - Int128(u.z) * w.y == 0 && Int128(u.z) * w.x - Int128(u.x) * w.z == 0 &&
          Int128(u.x) * w.y - Int128(u.y) * w.x == 0)
        continue;  // zero-area triangle after snapping
      const Eigen::Vector3d tn(double(Int128(u.y) * w.z - Int128(u.z) * w.y), double(Int128(u.z) * w.x - Int128(u.x) * w.z),
                               double(Int128(u.x) * w.y - Int128(u.y) * w.x));
      if (!(tn.dot(original) > 0))
        throw GeometryError(folded_message(fi, mesh.vertices[std::size_t(f[std::size_t(tri[0])])], grid));
      polys.push_back(bsp::detail::triangle_polygon(
          table, planar ? support : table.add(kernel::plane_through(v[0], v[1], v[2])), v));
      volume6 += Int128(v[0].x) * (Int128(v[1].y) * v[2].z - Int128(v[1].z) * v[2].y) -
                 Int128(v[0].y) * (Int128(v[1].x) * v[2].z - Int128(v[1].z) * v[2].x) +
                 Int128(v[0].z) * (Int128(v[1].x) * v[2].y - Int128(v[1].y) * v[2].x);
    }
  }

  // Thibault & Naylor 1987 (autopartition.hpp): each candidate scored against every polygon.
  FragmentList fragments;
  fragments.reserve(polys.size());
  for (ConvexPolygon& p : polys) fragments.push_back({std::move(p), false});
  const bsp::detail::AutopartitionOptions build{.candidates = options.candidates,
                                                .sample = options.sample,
                                                .split_weight = options.split_weight,
                                                .score = bsp::detail::PartitionScore::ExpectedDepth,
                                                .volume_samples = options.volume_samples,
                                                .point_sample = options.point_sample,
                                                .auxiliary_cost = options.auxiliary_cost,
                                                .separating_planes = options.separating_planes,
                                                .carry_boundary = options.snapped_mesh_is_clean,
                                                .auxiliary_splits = options.auxiliary_planes,
                                                .approximate_scores = true};
  if (options.snapped_mesh_is_clean && !fragments.empty()) {
    // A clean closed surface: the tree waits for its first use. Far from it the solid is out when
    // the surface's orientation is outward (positive volume), in when it is turned inside out.
    std::optional<bool> far_in;
    if (volume6 != 0) far_in = volume6 < 0;
    return bsp::detail::SolidAccess::at_grid(
        bsp::detail::solid_from_boundary(std::move(table), std::move(fragments), far_in, build), grid);
  }
  bsp::detail::Arena arena;
  arena.planes = std::move(table);
  Solid solid = bsp::detail::autopartition(arena, std::move(fragments), build);
  return bsp::detail::SolidAccess::at_grid(std::move(solid), grid);
}

}  // namespace sculpt
