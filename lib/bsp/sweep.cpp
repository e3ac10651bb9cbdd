#include "bsp/sweep.hpp"

#include <vector>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/cells.hpp"
#include "bsp/hull.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "kernel/grid.hpp"

namespace sculpt {
namespace {

/// The convex pieces of the tool as vertex lists: the tool itself when it is convex, else its
/// tree's in-cells. A tool counts as convex when its hull adds no more than the rounding of its
/// vertices to the grid can (curved primitives' vertices are plane intersections, not grid
/// points): at most its area times sqrt(3)/2 grid steps.
std::vector<std::vector<Eigen::Vector3d>> convex_pieces(const Solid& tool) {
  const std::vector<Eigen::Vector3d> vertices = to_mesh(tool).vertices;
  if (vertices.empty()) return {};
  const Solid h = hull(vertices, tool.grid());
  // The tool lies in its hull up to that rounding, so the volumes alone tell (no set operation).
  if (volume(h) - volume(tool) <= surface_area(tool) * tool.grid().step()) return {vertices};
  Eigen::AlignedBox3d box = bounding_box(tool);
  box.extend(box.min() - Eigen::Vector3d::Constant(1.0));
  box.extend(box.max() + Eigen::Vector3d::Constant(1.0));
  std::vector<std::vector<Eigen::Vector3d>> pieces;
  for (LeafCell& cell : leaf_cells(tool, box))
    if (cell.inside) pieces.push_back(std::move(cell.vertices));
  return pieces;
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
  const auto pieces = convex_pieces(tool);
  std::vector<Solid> parts;
  parts.reserve(pieces.size() * (at.size() - 1));
  std::vector<Eigen::Vector3d> ends;
  for (const auto& piece : pieces)
    for (std::size_t i = 0; i + 1 < at.size(); ++i) {
      ends.clear();
      for (const Eigen::Vector3d& v : piece) {
        ends.push_back(v + at[i]);
        ends.push_back(v + at[i + 1]);
      }
      parts.push_back(hull(ends, tool.grid()));
    }
  return unite_all(std::move(parts));
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

Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  return work - sweep(tool, poses);
}

Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Isometry3d> poses) {
  return work | sweep(tool, poses);
}

Solid carve(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path) {
  return work - sweep(tool, path);
}

Solid add(const Solid& work, const Solid& tool, std::span<const Eigen::Vector3d> path) {
  return work | sweep(tool, path);
}

}  // namespace sculpt
