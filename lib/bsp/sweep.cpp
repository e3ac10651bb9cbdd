#include "bsp/sweep.hpp"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/cells.hpp"
#include "bsp/hull.hpp"
#include "bsp/merge/convex_union.hpp"
#include "bsp/rebuild.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "kernel/convex_hull.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_measures.hpp"

namespace sculpt {
namespace {

/// The convex pieces of the tool as vertex lists: the tool itself when it is convex, else its
/// tree's in-cells. A tool counts as convex when its hull adds no more than the rounding of its
/// vertices to the grid can (curved primitives' vertices are plane intersections, not grid
/// points): at most its area times sqrt(3)/2 grid steps.
std::vector<std::vector<Eigen::Vector3d>> convex_pieces(const Solid& tool) {
  const PolygonMesh mesh = to_mesh(tool, {.clean = false});
  const std::vector<Eigen::Vector3d>& vertices = mesh.vertices;
  if (vertices.empty()) return {};
  // The hull of the vertices on the grid (what the sweep's hulls are made of), its volume from
  // its triangles (no tree is built for it).
  std::vector<kernel::GridPoint> snapped;
  snapped.reserve(vertices.size());
  for (const Eigen::Vector3d& v : vertices) snapped.push_back(tool.grid().snap(v));
  const kernel::ConvexHull h = kernel::convex_hull(snapped);
  double hull_volume = 0;
  if (h.dimension == 3) {
    const Eigen::Vector3d o = tool.grid().to_world(h.vertices[0]);
    for (const auto& t : h.triangles)
      hull_volume += (tool.grid().to_world(h.vertices[std::size_t(t[0])]) - o)
                         .dot((tool.grid().to_world(h.vertices[std::size_t(t[1])]) - o)
                                  .cross(tool.grid().to_world(h.vertices[std::size_t(t[2])]) - o)) / 6;
  }
  // The tool lies in its hull up to that rounding, so the volumes alone tell (no set operation).
  if (hull_volume - mesh_volume(mesh) <= mesh_surface_area(mesh) * tool.grid().step()) return {vertices};
  Eigen::AlignedBox3d box = mesh_bounding_box(mesh);
  box.extend(box.min() - Eigen::Vector3d::Constant(1.0));
  box.extend(box.max() + Eigen::Vector3d::Constant(1.0));
  std::vector<std::vector<Eigen::Vector3d>> pieces;
  for (LeafCell& cell : leaf_cells(tool, box))
    if (cell.inside) pieces.push_back(std::move(cell.vertices));
  return pieces;
}

/// The hull of a convex piece's grid vertices with, for each hull vertex, the outward normals of
/// the hull triangles at it (their positive combinations are the directions in which the vertex
/// is extreme). Empty for a flat piece.
struct ToolHull {
  std::vector<kernel::GridPoint> vertices;
  std::vector<std::array<std::int64_t, 3>> normals;   ///< per triangle
  std::vector<std::int32_t> start, triangles;          ///< triangles at vertex v: triangles[start[v] .. start[v + 1])
};

ToolHull tool_hull_of(const std::vector<kernel::GridPoint>& points) {
  ToolHull out;
  const kernel::ConvexHull h = kernel::convex_hull(points);
  if (h.dimension != 3) return out;
  out.vertices = h.vertices;
  for (const auto& t : h.triangles) {
    const kernel::GridPoint &p = h.vertices[std::size_t(t[0])], &q = h.vertices[std::size_t(t[1])], &r = h.vertices[std::size_t(t[2])];
    const std::int64_t u[3] = {q.x - p.x, q.y - p.y, q.z - p.z}, w[3] = {r.x - p.x, r.y - p.y, r.z - p.z};
    // |components| <= 2^(kCoordBits + 1): the cross product fits 64 bits (convex_hull.cpp).
    out.normals.push_back({u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]});
  }
  out.start.assign(h.vertices.size() + 1, 0);
  for (const auto& t : h.triangles)
    for (const int v : t) ++out.start[std::size_t(v) + 1];
  for (std::size_t v = 0; v < h.vertices.size(); ++v) out.start[v + 1] += out.start[v];
  out.triangles.resize(3 * h.triangles.size());
  std::vector<std::int32_t> at(out.start.begin(), out.start.end() - 1);
  for (std::size_t t = 0; t < h.triangles.size(); ++t)
    for (const int v : h.triangles[t]) out.triangles[std::size_t(at[std::size_t(v)]++)] = std::int32_t(t);
  return out;
}

}  // namespace

Solid sweep(const Solid& tool, std::span<const Eigen::Vector3d> path) {
  if (path.empty()) throw InvalidInput("sweep: the path has no points");
  std::vector<Eigen::Vector3d> at;  // the path on the grid, repeated points dropped
  for (const Eigen::Vector3d& p : path) {
    const Eigen::Vector3d g = tool.grid().to_world(tool.grid().snap(p));
    if (at.empty() || g != at.back()) at.push_back(g);
  }
  if (at.size() == 1) return translate(tool, at[0]);
  const kernel::Grid& grid = tool.grid();
  // Each convex piece's vertices on the grid; translated by grid points, they stay there (exact).
  // Each hull's core (convex_union.hpp): the piece's vertex centroid moved from a to b.
  std::vector<std::vector<kernel::GridPoint>> sets;
  std::vector<bsp::detail::HullCore> cores;
  for (const auto& piece : convex_pieces(tool)) {
    std::vector<kernel::GridPoint> snapped;
    snapped.reserve(piece.size());
    double centroid[3] = {0, 0, 0};
    for (const Eigen::Vector3d& v : piece) {
      snapped.push_back(grid.snap(v));
      centroid[0] += double(snapped.back().x), centroid[1] += double(snapped.back().y), centroid[2] += double(snapped.back().z);
    }
    for (double& c : centroid) c /= double(snapped.size());
    const ToolHull tool_hull = tool_hull_of(snapped);
    for (std::size_t i = 0; i + 1 < at.size(); ++i) {
      const kernel::GridPoint a = grid.snap(at[i]), b = grid.snap(at[i + 1]);
      const kernel::GridPoint d{b.x - a.x, b.y - a.y, b.z - a.z};
      std::vector<kernel::GridPoint> ends;
      ends.reserve(2 * snapped.size());
      auto add = [&](const kernel::GridPoint& v, const kernel::GridPoint& t) {  // snap() checks the range of the sum
        ends.push_back(grid.snap(grid.to_world(kernel::GridPoint{v.x + t.x, v.y + t.y, v.z + t.z})));
      };
      if (tool_hull.vertices.empty()) {  // a flat piece: every point at both ends
        for (const kernel::GridPoint& v : snapped) add(v, a), add(v, b);
      } else {
        // v + a is a corner of the segment's hull only if a direction in v's normal cone (the
        // normals of the tool hull's triangles at v) prefers a to b (n.d < 0 for one of them):
        // a corner is strictly extreme in a direction of its cone. Likewise for v + b. The
        // others lie in the hull of the rest, which is the same hull.
        for (std::size_t v = 0; v < tool_hull.vertices.size(); ++v) {
          bool toward_a = false, toward_b = false;
          for (std::int32_t k = tool_hull.start[v]; k < tool_hull.start[v + 1]; ++k) {
            const auto& n = tool_hull.normals[std::size_t(tool_hull.triangles[std::size_t(k)])];
            const kernel::Int128 nd = kernel::Int128(n[0]) * d.x + kernel::Int128(n[1]) * d.y + kernel::Int128(n[2]) * d.z;
            toward_a |= nd <= 0;
            toward_b |= nd >= 0;
          }
          if (toward_a) add(tool_hull.vertices[v], a);
          if (toward_b) add(tool_hull.vertices[v], b);
        }
      }
      sets.push_back(std::move(ends));
      bsp::detail::HullCore core;
      for (int k = 0; k < 3; ++k) {
        core.ends[0][std::size_t(k)] = centroid[k] + double(k == 0 ? a.x : (k == 1 ? a.y : a.z));
        core.ends[1][std::size_t(k)] = centroid[k] + double(k == 0 ? b.x : (k == 1 ? b.y : b.z));
      }
      cores.push_back(core);
    }
  }
  return bsp::detail::unite_convex_hulls(sets, grid, {.cores = cores});
}

Solid sweep(const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  if (poses.empty()) throw InvalidInput("sweep: the motion has no poses");
  std::vector<Eigen::Isometry3d> at;  // repeated poses dropped
  for (const Eigen::Isometry3d& p : poses) {
    if (!p.matrix().allFinite()) throw InvalidInput("sweep: a pose is not finite");
    if (at.empty() || p.matrix() != at.back().matrix()) at.push_back(p);
  }
  if (at.size() == 1) return transform(tool, Eigen::Affine3d(at[0].matrix()));
  const auto pieces = convex_pieces(tool);
  std::vector<Solid> parts;
  parts.reserve(pieces.size() * (at.size() - 1));
  std::vector<Eigen::Vector3d> ends;
  for (const auto& piece : pieces)
    for (std::size_t i = 0; i + 1 < at.size(); ++i) {
      ends.clear();
      for (const Eigen::Vector3d& v : piece) {
        ends.push_back(at[i] * v);
        ends.push_back(at[i + 1] * v);
      }
      parts.push_back(hull(ends, tool.grid()));
    }
  return unite_all(std::move(parts));
}

// Strokes: the result with the subtrees the stroke touched rebuilt where that makes them smaller
// (rebuild.hpp, rebuild_region), so the tree stays in check over many strokes.

Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  const Solid swept = sweep(tool, poses);
  return rebuild_region(work - swept, swept);
}

Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  const Solid swept = sweep(tool, poses);
  return rebuild_region(work | swept, swept);
}

Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path) {
  const Solid swept = sweep(tool, path);
  return rebuild_region(work - swept, swept);
}

Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path) {
  const Solid swept = sweep(tool, path);
  return rebuild_region(work | swept, swept);
}

Solid carve(Solid&& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  const Solid swept = sweep(tool, poses);
  return rebuild_region(std::move(work) - swept, swept);
}

Solid add(Solid&& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  const Solid swept = sweep(tool, poses);
  return rebuild_region(std::move(work) | swept, swept);
}

Solid carve(Solid&& work, const Solid& tool, std::span<const Eigen::Vector3d> path) {
  const Solid swept = sweep(tool, path);
  return rebuild_region(std::move(work) - swept, swept);
}

Solid add(Solid&& work, const Solid& tool, std::span<const Eigen::Vector3d> path) {
  const Solid swept = sweep(tool, path);
  return rebuild_region(std::move(work) | swept, swept);
}

}  // namespace sculpt
