#include "bsp/extrude.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <tuple>

#include "base/errors.hpp"
#include "bsp/from_mesh.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/predicates.hpp"

namespace sculpt {
namespace {

/// The polygon snapped to the grid (z = 0), repeated points dropped, counter-clockwise.
std::vector<kernel::GridPoint> extrude_ring(const std::vector<Eigen::Vector2d>& polygon, const kernel::Grid& grid) {
  std::vector<kernel::GridPoint> ring;
  for (const Eigen::Vector2d& p : polygon) {
    const kernel::GridPoint g = grid.snap(Eigen::Vector3d(p.x(), p.y(), 0.0));
    if (ring.empty() || !(g == ring.back())) ring.push_back(g);
  }
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) throw InvalidInput("extrude: the polygon needs at least 3 distinct points");
  // Twice the signed area, exactly (grid coordinates: products fit 128 bits).
  kernel::Int128 area = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const auto& a = ring[i];
    const auto& b = ring[(i + 1) % ring.size()];
    area += kernel::Int128(a.x) * b.y - kernel::Int128(b.x) * a.y;
  }
  if (area == 0) throw InvalidInput("extrude: the polygon has zero area");
  if (area < 0) std::reverse(ring.begin(), ring.end());
  return ring;
}

/// The right prism's mesh over `ring` from grid height `bottom` to `top` (bottom < top).
PolygonMesh prism_mesh(const std::vector<kernel::GridPoint>& ring, std::int64_t bottom, std::int64_t top,
                       const kernel::Grid& grid) {
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
  return mesh;
}

/// The polygon's own faults show up as a self-crossing roof or as faces meeting at a pinch.
void check_prism(const PolygonMesh& mesh) {
  if (const ValidationReport r = check_closed_manifold(mesh); !r.ok())
    throw GeometryError("extrude: the polygon's boundary crosses or touches itself (" + r.summary(1) + ")");
}

/// The layered mesh: layer k of n at grid height z0 + (z1 - z0) k / n, the ring turned and
/// scaled as ExtrudeOptions says, snapped; equal snapped points share one vertex, so side quads
/// whose ends collapse become triangles and a layer scaled to a point is an apex.
PolygonMesh layered_mesh(const std::vector<kernel::GridPoint>& ring, std::int64_t z0, std::int64_t z1, int slices,
                         const ExtrudeOptions& options) {
  const kernel::Grid& grid = options.grid;
  const int n = static_cast<int>(ring.size());
  PolygonMesh mesh;
  std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, int> index;
  std::vector<std::vector<int>> layers(static_cast<std::size_t>(slices) + 1);
  for (int k = 0; k <= slices; ++k) {
    const double t = double(k) / double(slices);
    // Clockwise seen from +z for a positive twist (OpenSCAD): a turn by -twist * t.
    const double angle = -options.twist * t * std::numbers::pi / 180.0;
    const double c = std::cos(angle), s = std::sin(angle);
    const Eigen::Vector2d factor = (1.0 - t) * Eigen::Vector2d(1.0, 1.0) + t * options.scale;
    const std::int64_t z = k == slices ? z1 : z0 + static_cast<std::int64_t>(std::llround(double(z1 - z0) * t));
    for (const kernel::GridPoint& g : ring) {
      kernel::GridPoint q = g;
      if (k > 0) {
        const double x = grid.to_world(double(g.x)), y = grid.to_world(double(g.y));
        q = grid.snap(Eigen::Vector3d(factor.x() * (c * x - s * y), factor.y() * (s * x + c * y), 0.0));
      }
      q.z = z;
      const auto [it, added] = index.try_emplace(std::tuple{q.x, q.y, q.z}, int(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(grid.to_world(q));
      layers[std::size_t(k)].push_back(it->second);
    }
  }
  // A loop of vertex indices without repeats next to each other (cyclically); fewer than 3: none.
  auto add_face = [&](std::vector<int> face) {
    face.erase(std::unique(face.begin(), face.end()), face.end());
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    if (face.size() >= 3) mesh.faces.push_back(std::move(face));
  };
  for (int k = 0; k < slices; ++k) {
    const auto& low = layers[std::size_t(k)];
    const auto& high = layers[std::size_t(k) + 1];
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const int a = low[std::size_t(i)], b = low[std::size_t(j)], c = high[std::size_t(j)], d = high[std::size_t(i)];
      const bool distinct = a != b && b != c && c != d && d != a && a != c && b != d;
      const auto& v = mesh.vertices;
      if (distinct && orient3d(v[std::size_t(a)], v[std::size_t(b)], v[std::size_t(c)], v[std::size_t(d)]) != 0) {
        // Not planar: split by the diagonal along which the side bulges outwards (extrude.hpp).
        if (options.twist > 0) {
          add_face({a, b, c});
          add_face({a, c, d});
        } else {
          add_face({a, b, d});
          add_face({b, c, d});
        }
      } else {
        add_face({a, b, c, d});
      }
    }
  }
  add_face(std::vector<int>(layers.front().rbegin(), layers.front().rend()));
  add_face(layers.back());
  if (z1 < z0)  // built upside down: turn every face around
    for (std::vector<int>& f : mesh.faces) std::reverse(f.begin(), f.end());
  return mesh;
}

}  // namespace

int default_slices(double twist) {
  if (twist == 0.0) return 1;
  const double slices = std::ceil(std::abs(twist) / kMaxTwistPerSlice);
  if (!(slices <= 1e6)) throw InvalidInput("extrude: a twist of " + std::to_string(twist) + " degrees is too large");
  return std::max(1, static_cast<int>(slices));
}

Solid extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1, const kernel::Grid& grid) {
  const std::vector<kernel::GridPoint> ring = extrude_ring(polygon, grid);
  const std::int64_t bottom = grid.snap(z0), top = grid.snap(z1);
  if (bottom >= top) throw InvalidInput("extrude: the height is not positive on the grid");
  const PolygonMesh mesh = prism_mesh(ring, bottom, top, grid);
  check_prism(mesh);
  return from_mesh(mesh, {.grid = grid});
}

Solid extrude(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1, const ExtrudeOptions& options) {
  if (!std::isfinite(options.twist)) throw InvalidInput("extrude: the twist is not a finite number");
  const Eigen::Vector2d& scale = options.scale;
  if (!std::isfinite(scale.x()) || !std::isfinite(scale.y()))
    throw InvalidInput("extrude: the scale is not a finite number");
  if (scale.x() < 0 || scale.y() < 0) throw InvalidInput("extrude: the scale must not be negative");
  if ((scale.x() == 0) != (scale.y() == 0))
    throw InvalidInput("extrude: a scale with one zero factor would end in an edge; use [0, 0] for an apex");
  if (options.slices < 0) throw InvalidInput("extrude: the number of slices must not be negative");
  const kernel::Grid& grid = options.grid;
  const std::vector<kernel::GridPoint> ring = extrude_ring(polygon, grid);
  const std::int64_t from = grid.snap(z0), to = grid.snap(z1);
  if (from == to) throw InvalidInput("extrude: the height is zero on the grid");
  const int slices = options.slices > 0 ? options.slices : default_slices(options.twist);
  if (std::abs(to - from) < slices)
    throw InvalidInput("extrude: " + std::to_string(slices) + " slices do not fit in a height of " +
                       std::to_string(std::abs(to - from)) + " grid steps");
  const PolygonMesh mesh = layered_mesh(ring, from, to, slices, options);
  if (const ValidationReport r = check_closed_manifold(mesh); !r.ok()) {
    check_prism(prism_mesh(ring, std::min(from, to), std::max(from, to), grid));  // the polygon's own fault?
    // The remedy first: the summary may run over several lines.
    throw GeometryError(
        "extrude: the twisted or scaled sides cross or touch each other on the grid: use more slices for a large "
        "twist, or a larger scale (" +
        r.summary(1) + ")");
  }
  return from_mesh(mesh, {.grid = grid});
}

}  // namespace sculpt
