#include "bsp/transform.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/local/deferred_build.hpp"
#include "bsp/tree/solid_access.hpp"
#include "bsp/tree_builder.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {

using bsp::detail::SolidAccess;
using kernel::Int128;
using kernel::Plane;

namespace {

// Integer matrix if every entry is within 1e-12 of a small integer (90° rotations, mirrors,
// integer scales): then planes map exactly through the cofactor matrix.
std::optional<Eigen::Matrix<std::int64_t, 3, 3>> integer_matrix(const Eigen::Matrix3d& m) {
  Eigen::Matrix<std::int64_t, 3, 3> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double v = std::nearbyint(m(i, j));
      if (std::fabs(m(i, j) - v) > 1e-12 || std::fabs(v) > 1024) return std::nullopt;
      r(i, j) = std::int64_t(v);
    }
  return r;
}

// `exact`: the map is exact, so the image of a plane that carries no face carries none either
// and the auxiliary marks are kept. Re-quantized planes no longer meet where they did, and the
// image tree can have sliver faces on any plane: then no plane is auxiliary.
// Fragments on the images of their planes: `mapped(p)` is plane p's index in the image table and
// image[p] the image plane. A mirror (negative determinant) reverses the corner order about the
// mapped support planes.
FragmentList map_fragments(const FragmentList& fragments, auto&& mapped, const std::vector<kernel::Plane>& image,
                           bool mirror) {
  FragmentList boundary;
  boundary.reserve(fragments.size());
  for (const FragmentRef f : fragments) {
    kernel::ConvexPolygon poly;
    poly.support = mapped(f.polygon.support);
    const auto& c = f.polygon.corners;
    const std::size_t m = c.size();
    for (std::size_t i = 0; i < m; ++i) {
      // A corner is the vertex support ∩ p ∩ q and the edge leaving it. Mirrored, the cycle is
      // reversed: the edge leaving old vertex k is the old edge arriving there, that of k - 1.
      const std::size_t k = mirror ? m - 1 - i : i;
      const kernel::Corner& old = c[k];
      const std::int32_t edge = mirror ? c[(k + m - 1) % m].edge : old.edge;
      const std::int32_t p = mapped(old.p), q = mapped(old.q), e = mapped(edge);
      poly.corners.push_back({e, p, q,
                              kernel::approximate_vertex(image[std::size_t(f.polygon.support)],
                                                         image[std::size_t(old.p)], image[std::size_t(old.q)])});
    }
    boundary.push_back({std::move(poly), f.flip});
  }
  return boundary;
}

// An exact map of a solid whose tree is deferred and whose far status is known: its boundary
// alone, the tree again deferred (an exact map keeps the far status and the plane triples).
Solid map_deferred(const Solid& solid, auto&& map_plane, bool mirror) {
  const Solid::BoundaryView view = solid.boundary_view();
  const kernel::PlaneTable& planes = *view.planes;
  kernel::PlaneTable table;
  std::vector<std::int32_t> plane_map(std::size_t(planes.size()), -1);
  std::vector<kernel::Plane> image(std::size_t(planes.size()));
  auto mapped = [&](std::int32_t p) {
    if (plane_map[std::size_t(p)] < 0) {
      image[std::size_t(p)] = map_plane(planes[p]);
      plane_map[std::size_t(p)] = table.add(image[std::size_t(p)], planes.auxiliary(p));
    }
    return plane_map[std::size_t(p)];
  };
  FragmentList boundary = map_fragments(*view.fragments, mapped, image, mirror);
  return SolidAccess::at_grid(
      bsp::detail::solid_from_boundary(std::move(table), std::move(boundary), *bsp::detail::far_status(solid)),
      solid.grid());
}

Solid map_planes(const Solid& solid, auto&& map_plane, bool exact, bool mirror = false) {
  if (exact && solid.tree_deferred() && !solid.boundary_view().fragments->empty() && bsp::detail::far_status(solid))
    return map_deferred(solid, map_plane, mirror);
  if (is_leaf(solid.root())) return solid;
  TreeBuilder b;
  std::vector<std::int32_t> plane_map(std::size_t(solid.planes().size()), -1);
  std::vector<kernel::Plane> image(std::size_t(solid.planes().size()));
  auto mapped = [&](std::int32_t p) {
    if (plane_map[std::size_t(p)] < 0) {
      image[std::size_t(p)] = map_plane(solid.planes()[p]);
      plane_map[std::size_t(p)] = b.add_plane(image[std::size_t(p)], exact && solid.planes().auxiliary(p));
    }
    return plane_map[std::size_t(p)];
  };
  // Children have larger indices than their parents? Not guaranteed: build bottom-up by
  // an explicit post-order.
  const auto& nodes = solid.nodes();
  std::vector<TreeRef> made(nodes.size(), kOut);
  std::vector<std::pair<TreeRef, bool>> stack{{solid.root(), false}};
  while (!stack.empty()) {
    auto [r, expanded] = stack.back();
    stack.pop_back();
    const BspNode& n = nodes[std::size_t(r)];
    if (!expanded) {
      stack.push_back({r, true});
      if (!is_leaf(n.negative)) stack.push_back({n.negative, false});
      if (!is_leaf(n.positive)) stack.push_back({n.positive, false});
      continue;
    }
    auto child = [&](TreeRef c) { return is_leaf(c) ? c : made[std::size_t(c)]; };
    made[std::size_t(r)] = b.add_node(mapped(n.plane), child(n.negative), child(n.positive));
  }
  const TreeRef root = made[std::size_t(solid.root())];
  const kernel::Grid grid = solid.grid();  // the image is at the solid's grid
  if (!exact) return SolidAccess::at_grid(std::move(b).build(root), grid);
  // An exact map takes each plane to its exact image (an affine bijection): every node still cuts its cell.
  if (!solid.has_boundary()) return SolidAccess::at_grid(std::move(b).build(root, BuildOptions{.nodes_cut_cells = true}), grid);
  // An exact map takes the boundary along: same plane triples on the mapped planes.
  FragmentList boundary = map_fragments(solid.boundary(), mapped, image, mirror);
  return SolidAccess::at_grid(std::move(b).build(root, std::move(boundary), {.nodes_cut_cells = true}), grid);
}

// n' = M^-T n, offset' = d * step - n' . t (world units), then re-quantized: every plane moves
// by about 2^-50 of the range and planes that met in one point generally no longer do.
Solid map_planes_approximately(const Solid& solid, const Eigen::Matrix3d& m, const Eigen::Vector3d& tv) {
  const Eigen::Matrix3d inv_t = m.inverse().transpose();
  return map_planes(solid, [&](const Plane& p) {
    const Eigen::Vector3d n = inv_t * p.normal();
    const double scale = n.cwiseAbs().maxCoeff();
    // Keep magnitudes moderate before quantizing: divide normal and offset by the same factor.
    const double offset = (solid.grid().to_world(double(p.d)) - n.dot(tv)) / scale;
    return kernel::plane_from_normal(n / scale, offset, solid.grid());
  }, false);
}

// The boundary mesh mapped vertex by vertex and rebuilt (from_mesh snaps each vertex to the grid
// and gives every face whose snapped vertices are not coplanar one plane per triangle). Empty
// when the solid is unbounded (its mesh reaches past the world range) or when snapping would
// fold a face or make faces cross (features below the grid step); faces that snapping flattens
// to a line are left out.
/// Largest feature (in grid steps) that the boundary route may collapse after snapping.
constexpr double kSnapFeatureSteps = 4;

/// Sub-step shifts of a general map's translation tried when snapping its image folds (in grid
/// steps; each coordinate within half a step, so a shift is at most sqrt(3) / 2 steps).
/// Three: each failed try costs a snap and a repair of the whole boundary (six made the slowest
/// of 3000 random cases several times slower for no case more).
const std::array<Eigen::Vector3d, 3> kSnapShifts = {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(-0.25, 0.25, 0.5),
                                                    Eigen::Vector3d(0.25, -0.5, -0.25)};

/// `exact`: the solid's boundary, `to_mesh(solid, {.clean = false})` (computed once for every try).
std::optional<Solid> map_boundary(const Solid& solid, const PolygonMesh& exact, const Eigen::Affine3d& map) {
  const kernel::Grid& grid = solid.grid();
  PolygonMesh mesh = exact;
  for (const Eigen::Vector3d& v : mesh.vertices)
    if (v.cwiseAbs().maxCoeff() > grid.max_world()) return std::nullopt;
  for (Eigen::Vector3d& v : mesh.vertices) v = grid.to_world(grid.snap(map * v));
  if (map.linear().determinant() < 0)
    for (auto& f : mesh.faces) std::reverse(f.begin(), f.end());
  // Snapping can fold faces, make them cross or collapse them below the grid step: features
  // below a few grid steps are collapsed (mesh/output_rounding.hpp) so that the snapped surface
  // bounds a solid again. Copies of a vertex where the solid touches itself stay.
  // A mesh of triangles already (an import's, DeferredTree::source_mesh) is judged as it is first:
  // asking for triangles would rebuild it through the repairing cleaner even where it is clean.
  const bool triangles = std::all_of(mesh.faces.begin(), mesh.faces.end(), [](const auto& f) { return f.size() == 3; });
  OutputRoundingReport rounding;
  mesh = round_for_output(std::move(mesh),
                          {.precision = OutputPrecision::Grid,
                           .max_feature = kSnapFeatureSteps * grid.step(),
                           .triangles = !triangles,
                           .grid_step = grid.step(),
                           .keep_copies = true},
                          &rounding);
  if (!rounding.clean) return std::nullopt;
  // round_for_output judged the snapped surface clean: closed, oriented, no two faces crossing.
  // It is then exactly the boundary of the tree from_mesh builds, which carries it. (Before that
  // check existed, snapping could make two nearly touching faces cross, and the rebuilt solid was
  // compared with the surface by volume and box; round_for_output's check rules that out.)
  std::optional<Solid> result;
  try {
    result = from_mesh(mesh, {.skip_degenerate_faces = true, .snapped_mesh_is_clean = true, .grid = grid});
  } catch (const GeometryError&) {  // a face folds when snapped
    return std::nullopt;
  } catch (const InvalidInput&) {  // not expected of to_mesh's output: the plane route still works
    return std::nullopt;
  }
  return result;
}

}  // namespace

Solid translate(const Solid& solid, const Eigen::Vector3d& v) {
  const kernel::GridPoint t = solid.grid().snap(v);
  // A plane is kept normalized (gcd(a, b, c, d) = 1, kernel/plane.hpp) and a move by grid
  // steps changes d by a multiple of gcd(a, b, c): the image is normalized already, no gcd.
  return map_planes(solid, [&](const Plane& p) {
    return kernel::make_plane(p.a, p.b, p.c, p.d - (Int128(p.a) * t.x + Int128(p.b) * t.y + Int128(p.c) * t.z),
                              {.gcd = 1});
  }, true);
}

Solid transform(const Solid& solid, const Eigen::Affine3d& map) {
  const Eigen::Matrix3d m = map.linear();
  const double det = m.determinant();
  if (!std::isfinite(det) || std::fabs(det) < 1e-12) throw InvalidInput("transform: singular or non-finite matrix");
  const Eigen::Vector3d tv = map.translation();
  const auto exact = integer_matrix(m);
  if (exact) {
    // n'' = sign(det) cof(M) n, d'' = |det| d - n'' . t (grid units): f'(M x + t) = |det| f(x).
    const kernel::GridPoint t = solid.grid().snap(tv);
    const Eigen::Matrix<std::int64_t, 3, 3>& im = *exact;
    Eigen::Matrix<std::int64_t, 3, 3> cof;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        cof(i, j) = im(i1, j1) * im(i2, j2) - im(i1, j2) * im(i2, j1);
      }
    const std::int64_t idet = im(0, 0) * cof(0, 0) + im(0, 1) * cof(0, 1) + im(0, 2) * cof(0, 2);
    const std::int64_t sgn = idet > 0 ? 1 : -1;
    return map_planes(solid, [&](const Plane& p) {
      Int128 n[3];
      for (int i = 0; i < 3; ++i)
        n[i] = sgn * (Int128(cof(i, 0)) * p.a + Int128(cof(i, 1)) * p.b + Int128(cof(i, 2)) * p.c);
      const Int128 d = Int128(idet * sgn) * p.d - (n[0] * t.x + n[1] * t.y + n[2] * t.z);
      return kernel::make_plane(n[0], n[1], n[2], d);
    }, true, idet < 0);
  }
  // General map: through the boundary (docs/kernel.md, "What transforms do"). The vertices are
  // mapped and snapped to the grid and the solid is rebuilt from them, so planes that met in one
  // vertex still do: a rotated cone keeps one apex. Unbounded solids, and boundaries with
  // features below the grid step that would fold when snapped, take the plane route instead.
  const PolygonMesh boundary = to_mesh(solid, {.clean = false});
  if (auto through = map_boundary(solid, boundary, map)) return std::move(*through);
  // Where snapping folds the boundary, snapping the same image shifted by part of a step often
  // does not (the fold depends on how vertices fall between grid points): a few shifts are tried
  // before the plane route, each moves the result by at most sqrt(3) / 2 grid steps.
  for (const Eigen::Vector3d& shift : kSnapShifts) {
    Eigen::Affine3d shifted = map;
    shifted.translation() += shift * solid.grid().step();
    if (auto through = map_boundary(solid, boundary, shifted)) return std::move(*through);
  }
  return map_planes_approximately(solid, m, tv);
}

Solid rotate(const Solid& solid, const Eigen::Vector3d& axis, double degrees) {
  if (!(axis.norm() > 0) || !std::isfinite(degrees)) throw InvalidInput("rotate: zero axis or non-finite angle");
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  map.linear() = Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()).toRotationMatrix();
  return transform(solid, map);
}

Solid scale(const Solid& solid, const Eigen::Vector3d& factors) {
  if (factors.cwiseAbs().minCoeff() == 0 || !factors.allFinite()) throw InvalidInput("scale: factors must be non-zero and finite");
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  map.linear() = factors.asDiagonal();
  return transform(solid, map);
}

}  // namespace sculpt
