#include "bsp/from_mesh.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "base/assert.hpp"
#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "base/parallel.hpp"
#include "bsp/local/deferred_build.hpp"
#include "bsp/partition/autopartition.hpp"
#include "bsp/partition/mesh_build_options.hpp"
#include "bsp/tree/solid_access.hpp"
#include "bsp/tree/triangle_fragment.hpp"
#include "mesh/edge_incidence.hpp"
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

/// The mesh at its snapped vertices (used ones only), when every face is a triangle that became
/// one fragment (`fragments` of them): the fragments' boundary as a mesh (DeferredTree::source_mesh).
std::shared_ptr<const TriangleMesh> source_triangles(const PolygonMesh& mesh, const std::vector<GridPoint>& g,
                                                     std::size_t fragments, const kernel::Grid& grid) {
  if (fragments != mesh.faces.size()) return nullptr;  // a face was split or left out
  auto source = std::make_shared<TriangleMesh>();
  std::vector<int> index(g.size(), -1);
  source->triangles.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    if (f.size() != 3) return nullptr;
    std::array<int, 3>& out = source->triangles.emplace_back(std::array<int, 3>{f[0], f[1], f[2]});
    for (int& v : out) {
      int& at = index[std::size_t(v)];
      if (at < 0) {
        at = int(source->vertices.size());
        source->vertices.push_back(grid.to_world(g[std::size_t(v)]));
      }
      v = at;
    }
  }
  return source;
}

/// What a run of faces makes (from_mesh): planes and triangles numbered within the run, the six-fold
/// signed volume of its triangles, and the first face that cannot be made, with its error.
struct FaceRun {
  std::vector<Plane> planes;
  std::vector<ConvexPolygon> polys;      ///< plane ids within the run, or neighbour_ref() (join_planes)
  std::vector<std::int32_t> support_of;  ///< each face's one support plane in `planes`, or -1
  Int128 volume6 = 0;
  std::size_t bad_face = SIZE_MAX;
  std::function<void()> error;  // throws that face's error
};

/// A face's plane (from_mesh's first pass), for the face itself and for its neighbours' sides.
struct FacePlane {
  Plane plane{};
  bool made = false;  ///< false: a face with too few corners or an index out of range (make_faces reports it)
  Int128 normal = 0;  ///< |a| + |b| + |c| of the largest corner triple's normal; 0: degenerate
  Int128 along = 0;   ///< the face's area vector along the plane's normal, before orienting; 0: it folds
};

/// The corner triple with the largest normal (robust for nearly straight corners), oriented by the
/// face's area vector (Newell's method, exact on the snapped grid points): the largest corner may
/// be a reflex corner of a non-convex face.
FacePlane face_plane(const std::vector<int>& f, const std::vector<GridPoint>& g) {
  FacePlane out;
  if (f.size() < 3) return out;
  for (int i : f)
    if (i < 0 || std::size_t(i) >= g.size()) return out;
  out.made = true;
  const std::size_t m = f.size();
  for (std::size_t i = 0; i < m; ++i) {
    const GridPoint& a = g[std::size_t(f[(i + m - 1) % m])];
    const GridPoint& b = g[std::size_t(f[i])];
    const GridPoint& c = g[std::size_t(f[(i + 1) % m])];
    const GridPoint u = sub(b, a), w = sub(c, b);
    const Int128 nx = Int128(u.y) * w.z - Int128(u.z) * w.y, ny = Int128(u.z) * w.x - Int128(u.x) * w.z,
                 nz = Int128(u.x) * w.y - Int128(u.y) * w.x;
    const Int128 len = (nx < 0 ? -nx : nx) + (ny < 0 ? -ny : ny) + (nz < 0 ? -nz : nz);
    if (len > out.normal) {
      out.normal = len;
      out.plane = kernel::plane_through(a, b, c);
    }
  }
  if (out.normal == 0) return out;
  Int128 area[3] = {0, 0, 0};
  for (std::size_t i = 0; i < m; ++i) {
    const GridPoint& a = g[std::size_t(f[i])];
    const GridPoint& b = g[std::size_t(f[(i + 1) % m])];
    area[0] += Int128(a.y) * b.z - Int128(a.z) * b.y;
    area[1] += Int128(a.z) * b.x - Int128(a.x) * b.z;
    area[2] += Int128(a.x) * b.y - Int128(a.y) * b.x;
  }
  out.along = area[0] * out.plane.a + area[1] * out.plane.b + area[2] * out.plane.c;
  if (out.along < 0) out.plane = out.plane.opposite();
  return out;
}

/// A side's edge plane that is the support of the face across it (or that support's opposite):
/// a reference until the runs are joined and every face's support has its id (from_mesh).
/// References are negative; plane ids within a run are not.
constexpr std::int32_t neighbour_ref(std::size_t face, bool opposite) {
  return -2 - std::int32_t(2 * face + (opposite ? 1 : 0));
}
constexpr bool is_neighbour_ref(std::int32_t id) { return id <= -2; }
constexpr std::size_t ref_face(std::int32_t ref) { return std::size_t(-2 - ref) / 2; }
constexpr bool ref_opposite(std::int32_t ref) { return (-2 - ref) % 2 == 1; }

/// Neighbouring supports closer to parallel than this (the sine of their angle) do not serve as
/// each other's edge planes: a corner that a later cut makes on such a side would be the meeting
/// point of two nearly parallel planes, its approximation ill-conditioned (by 1 / sine).
constexpr double kSharedEdgeSine = 1.0 / 256;

/// Side i of triangle v on plane s (from v[i] to v[i + 1]) lies on the support of the triangle
/// across it, which contains the side's two grid points: that support (or its opposite, so that
/// v is on its negative side) is the side's edge plane unless the two are nearly parallel
/// (Bernstein & Fussell 2009, sec. 3: a polygon's edges are any planes through them). One plane
/// per face instead of one per side: an import has fewer than half the planes it had.
std::optional<std::int32_t> shared_edge(const Plane& s, const GridPoint* v, int i, int across,
                                        const std::vector<FacePlane>& planes) {
  if (across < 0) return std::nullopt;
  const FacePlane& other = planes[std::size_t(across)];
  if (!other.made || other.normal == 0 || other.along == 0) return std::nullopt;
  const Plane& t = other.plane;
  const Eigen::Vector3d n = s.normal(), m = t.normal();
  if (!(n.cross(m).squaredNorm() >= kSharedEdgeSine * kSharedEdgeSine * n.squaredNorm() * m.squaredNorm()))
    return std::nullopt;
  const Int128 side = t.eval(v[(i + 2) % 3]);
  if (side == 0) return std::nullopt;
  return neighbour_ref(std::size_t(across), side > 0);
}

/// Faces [begin, end) of `mesh` (vertices snapped: `g`; face planes: `planes`; the triangles
/// across each triangle's sides: `across`) as convex triangles on planes.
FaceRun make_faces(const PolygonMesh& mesh, const std::vector<GridPoint>& g, const FromMeshOptions& options,
                   const std::vector<FacePlane>& planes, const std::vector<std::array<int, 3>>& across,
                   std::size_t begin, std::size_t end) {
  const kernel::Grid& grid = options.grid;
  FaceRun run;
  run.planes.reserve(2 * (end - begin));
  run.polys.reserve(end - begin);
  run.support_of.assign(end - begin, -1);
  auto fail = [&](std::size_t fi, auto error) {
    run.bad_face = fi;
    run.error = error;
  };
  std::vector<Eigen::Vector3d> pts;
  std::vector<int> local;
  std::vector<IndexTriangle> tris;
  PolygonTriangulator triangulator;
  CancelPoll poll;
  for (std::size_t fi = begin; fi < end; ++fi) {
    poll.tick();  // Ctrl-C (base/cancel.hpp)
    const auto& f = mesh.faces[fi];
    if (f.size() < 3) {
      fail(fi, [fi] { throw InvalidInput("from_mesh: face " + std::to_string(fi) + " has fewer than 3 vertices"); });
      return run;
    }
    for (int i : f)
      if (i < 0 || std::size_t(i) >= g.size()) {
        fail(fi, [fi] {
          throw InvalidInput("from_mesh: face " + std::to_string(fi) + " has a vertex index out of range");
        });
        return run;
      }
    const FacePlane& face = planes[fi];
    const Plane best = face.plane;
    const std::size_t m = f.size();
    if (face.normal == 0) {
      if (options.skip_degenerate_faces) continue;
      {
        fail(fi, [fi] {
          throw InvalidInput("from_mesh: face " + std::to_string(fi) + " is degenerate (collinear vertices)");
        });
        return run;
      }
    }
    const Eigen::Vector3d near = mesh.vertices[std::size_t(f[0])];
    auto folded = [&](const Eigen::Vector3d& at) {
      return fail(fi, [fi, at, grid] { throw GeometryError(folded_message(fi, at, grid)); });
    };
    if (face.along == 0) {
      folded(near);
      return run;
    }
    // Orientation of the face before snapping: a snapped triangle turned against it is a fold.
    Eigen::Vector3d original = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < m; ++i)
      original += mesh.vertices[std::size_t(f[i])].cross(mesh.vertices[std::size_t(f[(i + 1) % m])]);
    // A face whose snapped vertices are not exactly coplanar is split into triangles, each on
    // its own plane, so that the polygons still close up exactly.
    bool planar = true;
    for (int i : f) planar = planar && best.eval(g[std::size_t(i)]) == 0;
    const auto support = std::int32_t(run.planes.size());
    run.planes.push_back(best);
    if (planar) run.support_of[fi - begin] = support;
    // Triangulate (faces may be non-convex); every triangle is a convex plane-based polygon. A
    // triangle is its own (as triangulate_polygon gives it), without the points or an allocation.
    tris.clear();
    if (m == 3) {
      tris.push_back({0, 1, 2});
    } else {
      pts.clear();
      local.clear();
      for (std::size_t i = 0; i < m; ++i) {
        pts.push_back(grid.to_world(g[std::size_t(f[i])]));
        local.push_back(int(i));
      }
      triangulator.append(pts, local, tris);
    }
    for (const IndexTriangle& tri : tris) {
      const GridPoint v[3] = {g[std::size_t(f[std::size_t(tri[0])])], g[std::size_t(f[std::size_t(tri[1])])],
                              g[std::size_t(f[std::size_t(tri[2])])]};
      const GridPoint u = sub(v[1], v[0]), w = sub(v[2], v[0]);
      if (Int128(u.y) * w.z - Int128(u.z) * w.y == 0 && Int128(u.z) * w.x - Int128(u.x) * w.z == 0 &&
          Int128(u.x) * w.y - Int128(u.y) * w.x == 0)
        continue;  // zero-area triangle after snapping
      const Eigen::Vector3d tn(double(Int128(u.y) * w.z - Int128(u.z) * w.y), double(Int128(u.z) * w.x - Int128(u.x) * w.z),
                               double(Int128(u.x) * w.y - Int128(u.y) * w.x));
      if (!(tn.dot(original) > 0)) {
        folded(mesh.vertices[std::size_t(f[std::size_t(tri[0])])]);
        return run;
      }
      std::int32_t on = support;
      if (!planar) {
        on = std::int32_t(run.planes.size());
        run.planes.push_back(kernel::plane_through(v[0], v[1], v[2]));
      }
      // A triangle face's sides take the neighbours' supports where they can (shared_edge);
      // other sides (and a polygon's triangles) their own transverse planes.
      std::array<std::int32_t, 3> edges{};
      const Plane s = run.planes[std::size_t(on)];  // (a copy: the pushes below may move the list)
      for (int i = 0; i < 3; ++i) {
        const std::optional<std::int32_t> shared =
            m == 3 ? shared_edge(s, v, i, across[fi][std::size_t(i)], planes) : std::nullopt;
        if (shared) {
          edges[std::size_t(i)] = *shared;
        } else {
          edges[std::size_t(i)] = std::int32_t(run.planes.size());
          run.planes.push_back(bsp::detail::transverse_edge_plane(s, v, i));
        }
      }
      run.polys.push_back(bsp::detail::triangle_polygon(on, v, edges));
      run.volume6 += Int128(v[0].x) * (Int128(v[1].y) * v[2].z - Int128(v[1].z) * v[2].y) -
                     Int128(v[0].y) * (Int128(v[1].x) * v[2].z - Int128(v[1].z) * v[2].x) +
                     Int128(v[0].z) * (Int128(v[1].x) * v[2].y - Int128(v[1].y) * v[2].x);
    }
  }
  return run;
}

/// Faces per run of make_faces (the runs are made in parallel and joined in order, so the planes
/// and fragments are the same for every thread count).
constexpr std::size_t kFacesPerRun = 8192;

/// The runs' planes in one table (the world planes, then each run's in run order, then the
/// opposites of the supports that a neighbour's side needs reversed, in face order), and the
/// runs' polygons renumbered into it: run ids moved by the run's start, neighbour_ref()s
/// replaced by the support (or opposite) they name.
kernel::PlaneTable join_planes(std::vector<FaceRun>& runs) {
  // Every face's support id, from its run's start.
  std::size_t plane_count = 0, face_count = 0;
  std::vector<std::int32_t> base(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) {
    base[r] = std::int32_t(std::size_t(kernel::kWorldPlanes) + plane_count);
    plane_count += runs[r].planes.size();
    face_count += runs[r].support_of.size();
  }
  std::vector<std::int32_t> support_id(face_count, -1), opposite_id(face_count, -1);
  for (std::size_t r = 0, face = 0; r < runs.size(); ++r)
    for (const std::int32_t local : runs[r].support_of) support_id[face++] = local < 0 ? -1 : base[r] + local;
  // Which supports are needed reversed: marked, then numbered in face order after the runs' planes.
  for (const FaceRun& run : runs)
    for (const ConvexPolygon& p : run.polys)
      for (const auto& c : p.corners)
        if (is_neighbour_ref(c.edge) && ref_opposite(c.edge)) opposite_id[ref_face(c.edge)] = 0;
  kernel::PlaneTable table;
  std::size_t opposites = 0;
  for (const std::int32_t id : opposite_id) opposites += id == 0 ? 1 : 0;
  table.reserve(std::size_t(kernel::kWorldPlanes) + plane_count + opposites);
  for (const FaceRun& run : runs)
    for (const Plane& p : run.planes) table.add(p);
  for (std::size_t face = 0; face < face_count; ++face)
    if (opposite_id[face] == 0) {
      SCULPT_ASSERT(support_id[face] >= 0, "from_mesh: a side's neighbour has no support plane");
      opposite_id[face] = table.add(table[support_id[face]].opposite());
    }
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const auto id = [&](std::int32_t local) {
      if (!is_neighbour_ref(local)) return base[r] + local;
      return (ref_opposite(local) ? opposite_id : support_id)[ref_face(local)];
    };
    for (ConvexPolygon& p : runs[r].polys) {
      p.support = id(p.support);
      for (auto& c : p.corners) c.edge = id(c.edge), c.p = id(c.p), c.q = id(c.q);
    }
  }
  return table;
}

}  // namespace

Solid from_mesh(const PolygonMesh& mesh, const FromMeshOptions& options) {
  const kernel::Grid& grid = options.grid;
  if (mesh.faces.empty()) return Solid::leaf(false, grid);
  std::vector<GridPoint> g;
  g.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) g.push_back(grid.snap(v));

  std::vector<FacePlane> planes(mesh.faces.size());
  parallel_chunks(mesh.faces.size(), kFacesPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t fi = begin; fi < end; ++fi) planes[fi] = face_plane(mesh.faces[fi], g);
  });
  const std::vector<std::array<int, 3>> across = triangle_neighbours(mesh);
  std::vector<FaceRun> runs((mesh.faces.size() + kFacesPerRun - 1) / kFacesPerRun);
  parallel_chunks(mesh.faces.size(), kFacesPerRun, [&](std::size_t begin, std::size_t end) {
    runs[begin / kFacesPerRun] = make_faces(mesh, g, options, planes, across, begin, end);
  });
  // The first face that cannot be made, in face order, reports its error.
  for (const FaceRun& run : runs)
    if (run.error) run.error();
  std::size_t poly_count = 0;
  for (const FaceRun& run : runs) poly_count += run.polys.size();
  kernel::PlaneTable table = join_planes(runs);
  FragmentList fragments;
  fragments.reserve(poly_count);
  Int128 volume6 = 0;  // six times the signed volume of the snapped triangles (exact: |coords| < 2^26)
  for (FaceRun& run : runs) {
    for (ConvexPolygon& p : run.polys) fragments.push_back({std::move(p), false});
    volume6 += run.volume6;
    run = FaceRun();
  }

  // Thibault & Naylor 1987 (autopartition.hpp): each candidate scored against every polygon.
  bsp::detail::AutopartitionOptions build = bsp::detail::mesh_build_options(options);
  build.carry_boundary = options.snapped_mesh_is_clean;
  if (options.snapped_mesh_is_clean && !fragments.empty()) {
    // A clean closed surface: the tree waits for its first use. Far from it the solid is out when
    // the surface's orientation is outward (positive volume), in when it is turned inside out.
    std::optional<bool> far_in;
    if (volume6 != 0) far_in = volume6 < 0;
    std::shared_ptr<const TriangleMesh> source = source_triangles(mesh, g, fragments.size(), grid);
    return bsp::detail::SolidAccess::at_grid(
        bsp::detail::solid_from_boundary(std::move(table), std::move(fragments), far_in, build, std::move(source)),
        grid);
  }
  bsp::detail::Arena arena;
  arena.planes = std::move(table);
  Solid solid = bsp::detail::autopartition(arena, std::move(fragments), build);
  return bsp::detail::SolidAccess::at_grid(std::move(solid), grid);
}

namespace bsp::detail {

AutopartitionOptions mesh_build_options(const FromMeshOptions& options) {
  return {.candidates = options.candidates,
          .sample = options.sample,
          .split_weight = options.split_weight,
          .score = PartitionScore::ExpectedDepth,
          .volume_samples = options.volume_samples,
          .point_sample = options.point_sample,
          .auxiliary_cost = options.auxiliary_cost,
          .separating_planes = options.separating_planes,
          .auxiliary_splits = options.auxiliary_planes,
          .approximate_scores = true};
}

}  // namespace bsp::detail
}  // namespace sculpt
