#include "bsp/extrude.hpp"

#include <algorithm>

#include "base/errors.hpp"
#include "bsp/from_mesh.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_validation.hpp"

namespace sculpt {

Solid extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1, const kernel::Grid& grid) {
  std::vector<kernel::GridPoint> ring;
  for (const Eigen::Vector2d& p : polygon) {
    const kernel::GridPoint g = grid.snap(Eigen::Vector3d(p.x(), p.y(), 0.0));
    if (ring.empty() || !(g == ring.back())) ring.push_back(g);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) throw InvalidInput("extrude: the polygon needs at least 3 distinct points");
  const std::int64_t bottom = grid.snap(z0), top = grid.snap(z1);
  if (bottom >= top) throw InvalidInput("extrude: the height is not positive on the grid");
  // Twice the signed area, exactly (grid coordinates: products fit 128 bits).
  kernel::Int128 area = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const auto& a = ring[i];
    const auto& b = ring[(i + 1) % ring.size()];
    area += kernel::Int128(a.x) * b.y - kernel::Int128(b.x) * a.y;
  }
  if (area == 0) throw InvalidInput("extrude: the polygon has zero area");
  if (area < 0) std::reverse(ring.begin(), ring.end());

  const int n = static_cast<int>(ring.size());
  PolygonMesh mesh;
  for (std::int64_t z : {bottom, top})
    for (const auto& g : ring) mesh.vertices.push_back(grid.to_world(kernel::GridPoint{g.x, g.y, z}));
  std::vector<int> floor, roof;
  for (int i = 0; i < n; ++i) {
    floor.push_back(n - 1 - i);
    roof.push_back(n + i);
    const int j = (i + 1) % n;
    mesh.faces.push_back({i, j, n + j, n + i});
  }
  mesh.faces.push_back(std::move(floor));
  mesh.faces.push_back(std::move(roof));
  // The polygon's own faults show up as a self-crossing roof or as faces meeting at a pinch.
  if (const ValidationReport r = check_closed_manifold(mesh); !r.ok())
    throw GeometryError("extrude: the polygon's boundary crosses or touches itself (" + r.summary(1) + ")");
  return from_mesh(mesh, {.grid = grid});
}

}  // namespace sculpt
