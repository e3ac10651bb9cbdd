// Built-ins of the surfaces area: tensor-product B-spline surfaces, active-surface fitting to a
// point cloud, distances, a triangle mesh at a tolerance, and solids from surfaces (thickened, or
// closed both ways) (Pottmann, Leopoldseder & Hofer 2002, sec. 4; lib/splines). See docs/splines.md.
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "bsp/from_mesh.hpp"
#include "language/builtins.hpp"
#include "language/solid_values.hpp"
#include "language/surface_values.hpp"
#include "mesh/mesh_validation.hpp"
#include "splines/bspline_surface.hpp"
#include "splines/fit_surface.hpp"
#include "splines/tessellate_surface.hpp"

namespace sculpt::language {
namespace {

using splines::BSplineSurface;


Value surface_value(BSplineSurface s) {
  return Value(std::shared_ptr<const Object>(std::make_shared<SurfaceValue>(std::move(s))));
}

const SurfaceValue& surface_arg(const Arguments& args, std::string_view i) {
  return args.object<SurfaceValue>(i, "a surface");
}

Eigen::Vector3d point_of(const Arguments& args, std::string_view i, const Value& v) {
  const List* xyz = v.list();
  if (!xyz || xyz->size() != 3) args.fail(i, "points must be [x, y, z]");
  Eigen::Vector3d p;
  for (int a = 0; a < 3; ++a) {
    const double* x = (*xyz)[static_cast<std::size_t>(a)].get<double>();
    if (!x || !std::isfinite(*x)) args.fail(i, "points must be [x, y, z] of finite numbers");
    p[a] = *x;
  }
  return p;
}

std::vector<Eigen::Vector3d> points_arg(const Arguments& args, std::string_view i) {
  std::vector<Eigen::Vector3d> out;
  for (const Value& v : args.list(i)) out.push_back(point_of(args, i, v));
  if (out.empty()) args.fail(i, "the list of points is empty");
  return out;
}

/// [a, b] of integers in [low, high], or one integer for both.
std::array<int, 2> pair_arg(const Arguments& args, std::string_view i, long long low, long long high,
                            const char* name) {
  if (args.value(i).get<double>()) {
    const int n = static_cast<int>(args.integer(i));
    return {n, n};
  }
  const List& l = args.list(i);
  if (l.size() != 2) args.fail(i, std::string(name) + " must be a number or a pair [u, v]");
  std::array<int, 2> out{};
  for (int d = 0; d < 2; ++d) {
    const double* x = l[static_cast<std::size_t>(d)].get<double>();
    if (!x || *x != std::floor(*x) || *x < static_cast<double>(low) || *x > static_cast<double>(high))
      args.fail(i, std::string(name) + " must be whole numbers in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
    out[d] = static_cast<int>(*x);
  }
  return out;
}

/// The chord tolerance parameter of a surface's mesh.
Param tolerance_param() { return arg("tol").positive().defaults(kDefaultSurfaceTolerance); }

/// The parameter of a surface argument named `name`.
Param surface_param(std::string name) { return arg(std::move(name)).of<SurfaceValue>("a surface"); }

/// A parameter that takes a whole number in [low, high] for both directions or a pair [u, v] of them.
Param pair_param(std::string name, double low, double high) {
  Param p = arg(std::move(name)).integer(low, high);  // the bounds args.integer reads
  p.kind = Kind::Any;                                 // a pair is checked by pair_arg
  p.what = "a whole number from " + std::to_string(int(low)) + " to " + std::to_string(int(high)) +
           " or a pair [u, v] of them";
  return p;
}

splines::SurfaceTriangles triangles_of(const Arguments& args, const BSplineSurface& s, double tol) {
  splines::SurfaceTriangles m = splines::tessellate(s, {.tolerance = tol});
  args.charge(m.points.size());
  return m;
}

PolygonMesh mesh_of(const splines::SurfaceTriangles& m) {
  PolygonMesh mesh;
  mesh.vertices = m.points;
  for (const auto& t : m.triangles) mesh.faces.push_back({t[0], t[1], t[2]});
  return mesh;
}

/// Unit normals at the mesh's vertices: the surface's, or where it is singular the mean of the
/// adjacent triangles' normals.
std::vector<Eigen::Vector3d> vertex_normals(const BSplineSurface& s, const splines::SurfaceTriangles& m) {
  std::vector<Eigen::Vector3d> face_sum(m.points.size(), Eigen::Vector3d::Zero());
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]);
    for (int k = 0; k < 3; ++k) face_sum[t[k]] += n;
  }
  std::vector<Eigen::Vector3d> out(m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Eigen::Vector3d n = s.normal(m.parameters[i][0], m.parameters[i][1]);
    out[i] = n.squaredNorm() > 0 ? n : face_sum[i].normalized();
  }
  return out;
}

Value solid_from(const Arguments& args, const PolygonMesh& mesh, const std::string& what) {
  const ValidationReport report = check_closed_manifold(mesh);
  if (!report.ok()) args.fail(what + " is not a closed manifold: " + report.summary(3));
  if (const std::string e = snapped_self_intersection(mesh, args.grid()); !e.empty()) args.fail(what + ": " + e);
  return solid_value(from_mesh(mesh, {.skip_degenerate_faces = true, .grid = args.grid()}));
}

/// thicken(s, t): the surface's mesh moved by +t/2 and -t/2 along the surface normal, joined
/// along the boundary by walls of two triangles per boundary edge.
Value thicken(const Arguments& args) {
  const BSplineSurface& s = surface_arg(args, "s").surface;
  const double t = args.number("t");
  const splines::SurfaceTriangles m = triangles_of(args, s, args.number("tol"));
  const std::vector<Eigen::Vector3d> normals = vertex_normals(s, m);
  const int n = static_cast<int>(m.points.size());
  PolygonMesh mesh;
  for (int i = 0; i < n; ++i) mesh.vertices.push_back(m.points[i] + 0.5 * t * normals[i]);
  for (int i = 0; i < n; ++i) mesh.vertices.push_back(m.points[i] - 0.5 * t * normals[i]);
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : m.triangles) {
    mesh.faces.push_back({f[0], f[1], f[2]});          // top: faces along +n
    mesh.faces.push_back({f[0] + n, f[2] + n, f[1] + n});  // bottom: turned over
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  for (const auto& [e, count] : directed) {
    if (directed.count({e.second, e.first})) continue;  // interior edge
    const int a = e.first, b = e.second;                 // boundary edge a -> b of the top sheet
    mesh.faces.push_back({b, a, a + n});
    mesh.faces.push_back({b, a + n, b + n});
  }
  return solid_from(args, mesh, "the thickened surface (t larger than a curvature radius makes the sheets cross)");
}

Value surface_solid(const Arguments& args) {
  const BSplineSurface& s = surface_arg(args, "s").surface;
  if (!s.closed(0) || !s.closed(1)) args.fail("s", "the surface must be closed in both directions (else use thicken)");
  PolygonMesh mesh = mesh_of(triangles_of(args, s, args.number("tol")));
  double volume6 = 0;
  for (const auto& f : mesh.faces) volume6 += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]]));
  if (volume6 < 0)
    for (auto& f : mesh.faces) std::swap(f[1], f[2]);
  return solid_from(args, mesh, "the surface's mesh");
}

Value fit_surface(const Arguments& args) {
  const std::vector<Eigen::Vector3d> points = points_arg(args, "points");
  splines::FitSurfaceOptions options;
  if (args.has("controls")) options.controls = pair_arg(args, "controls", 2, 1000, "controls");
  if (args.has("degree")) options.degree = pair_arg(args, "degree", 1, splines::kMaxFastDegree, "degree");
  options.method = splines::method_from_name(args.string("method"));
  options.iterations = static_cast<int>(args.integer("iterations"));
  options.smoothing = args.number("smoothing");
  if (args.has("start")) options.start = surface_arg(args, "start").surface;
  args.charge(points.size() * static_cast<std::uint64_t>(options.iterations + 1));
  splines::FitSurfaceResult r = splines::fit_surface(points, options);
  auto v = std::make_shared<SurfaceValue>(std::move(r.surface));
  v->history = std::move(r.history);
  v->converged = r.converged;
  return Value(std::shared_ptr<const Object>(std::move(v)));
}

}  // namespace

PolygonMesh surface_triangle_mesh(const Arguments& args, const splines::BSplineSurface& s, double tol) {
  return mesh_of(triangles_of(args, s, tol));
}

std::string SurfaceValue::repr() const {
  std::string s = "<surface: degree " + std::to_string(surface.degree(0)) + " x " + std::to_string(surface.degree(1)) + ", " +
                  (surface.closed(0) ? "closed" : "open") + " x " + (surface.closed(1) ? "closed" : "open") + ", " +
                  std::to_string(surface.count(0)) + " x " + std::to_string(surface.count(1)) + " controls";
  if (!history.empty())
    s += ", fitted in " + std::to_string(history.size() - 1) + (history.size() == 2 ? " step" : " steps") +
         (converged ? "" : " (not converged)");
  return s + ">";
}

void register_surfaces(BuiltinTable& table) {
  table.add({.name = "bspline_surface",
             .doc = "A tensor-product B-spline surface from a grid of control points: a list of rows (one per u "
                    "index) of [x, y, z]. Uniform knots over [0, 1] in both directions: clamped where open (the "
                    "corners are corner control points), periodic where closed (the grid wraps around). degree "
                    "and closed take a pair [u, v] or one value for both; degree at most 7.",
             .params = {arg("controls").list(), pair_param("degree", 1, splines::kMaxFastDegree).optional("[3, 3]"),
                        arg("closed").any("true, false or a pair [u, v] of them").optional("[false, false]")},
             .run = [](const Arguments& args) -> Value {
               const List& rows = args.list("controls");
               if (rows.empty()) args.fail("controls", "the control grid is empty");
               std::vector<Eigen::Vector3d> P;
               std::size_t columns = 0;
               for (const Value& row : rows) {
                 const List* r = row.list();
                 if (!r) args.fail("controls", "controls must be a list of rows of [x, y, z]");
                 if (columns == 0) columns = r->size();
                 if (r->size() != columns)
                   args.fail("controls", "every row of the control grid must have the same length");
                 for (const Value& p : *r) P.push_back(point_of(args, "controls", p));
               }
               const std::array<int, 2> degree = args.has("degree")
                                                     ? pair_arg(args, "degree", 1, splines::kMaxFastDegree, "degree")
                                                     : std::array<int, 2>{3, 3};
               std::array<bool, 2> closed{false, false};
               if (args.has("closed")) {
                 if (const List* l = args.value("closed").list()) {
                   if (l->size() != 2 || !(*l)[0].get<bool>() || !(*l)[1].get<bool>())
                     args.fail("closed", "closed must be true, false or a pair [u, v] of them");
                   closed = {*(*l)[0].get<bool>(), *(*l)[1].get<bool>()};
                 } else {
                   closed[0] = closed[1] = args.boolean("closed");
                 }
               }
               return surface_value(BSplineSurface::uniform(degree, static_cast<int>(rows.size()), static_cast<int>(columns),
                                                            std::move(P), closed));
             }});
  table.add({.name = "fit_surface",
             .doc =
                 "An active B-spline surface with a controls[0] x controls[1] grid fitted to a list of points "
                 "[x, y, z] (Pottmann, Leopoldseder & Hofer 2002, sec. 4): foot points, a local quadratic "
                 "model of each squared distance, one sparse linear solve, repeated. method: \"sdm\" (the "
                 "curvature-based model), \"pdm\" (point distance) or \"tdm\" (tangent plane). Starts from the "
                 "bilinear patch through the data's four corners (extreme along the diagonals of the two "
                 "main axes), which stay fixed, or from surface `start` (any closedness). smoothing: the "
                 "thin-plate weight of the first step (a tenth of it each further step). surface_history() gives the "
                 "convergence figures.",
             .params = {arg("points").list(), pair_param("controls", 2, 1000).optional("[8, 8]"),
                        pair_param("degree", 1, splines::kMaxFastDegree).optional("[3, 3]"),
                        arg("method").string().defaults("sdm"),
                        arg("iterations").integer(0, 10'000).defaults(double(splines::FitSurfaceOptions{}.iterations)),
                        arg("smoothing").at_least(0).defaults(splines::FitSurfaceOptions{}.smoothing),
                        surface_param("start").optional("s")},
             .run = [](const Arguments& args) -> Value { return fit_surface(args); }});
  table.add({.name = "surface_history",
             .doc = "The convergence of the fit that made surface s: one row [objective, max, rms] per step, row 0 "
                    "for the start (objective: mean squared distance; max, rms: exact foot points).",
             .params = {surface_param("s")},
             .run = [](const Arguments& args) -> Value {
               const SurfaceValue& s = surface_arg(args, "s");
               if (s.history.empty()) args.fail("s", "this surface was not made by fit_surface");
               List rows;
               for (const auto& row : s.history)
                 rows.emplace_back(List{row.objective, row.max_distance, row.rms_distance});
               return rows;
             }});
  table.add(
      {.name = "surface_point",
       .doc =
           "The point [x, y, z] of surface s at parameters u, v (open directions clamp to [0, 1], closed ones wrap).",
       .params = {surface_param("s"), arg("u").finite_number(), arg("v").finite_number()},
       .run = [](const Arguments& args) -> Value {
         const Eigen::Vector3d p = surface_arg(args, "s").surface.point(args.number("u"), args.number("v"));
         return List{p.x(), p.y(), p.z()};
       }});
  table.add({.name = "surface_distance",
             .doc = "[max, rms]: the largest and root-mean-square distance from a list of points [x, y, z] to "
                    "surface s, with exact foot points.",
             .params = {surface_param("s"), arg("points").list()},
             .run = [](const Arguments& args) -> Value {
               const std::vector<Eigen::Vector3d> points = points_arg(args, "points");
               args.charge(points.size());
               const splines::DistanceSummary d = splines::distance(surface_arg(args, "s").surface, points);
               return List{d.max, d.rms};
             }});
  table.add({.name = "surface_mesh",
             .doc = "Surface s as a triangle mesh value (for export) whose chord error is about tol: a uniform "
                    "grid per knot span sized by the second derivatives (docs/splines.md). Closed directions "
                    "share the seam's vertices.",
             .params = {surface_param("s"), tolerance_param()},
             .run = [](const Arguments& args) -> Value {
               const BSplineSurface& s = surface_arg(args, "s").surface;
               return Value(std::shared_ptr<const Object>(
                   std::make_shared<MeshValue>(mesh_of(triangles_of(args, s, args.number("tol"))))));
             }});
  table.add({.name = "thicken",
             .doc = "The solid of surface s thickened to t: its mesh (surface_mesh at tol) moved by t/2 both ways "
                    "along the surface normal and closed by walls along the boundary. A t beyond a curvature "
                    "radius makes the sheets cross: an error.",
             .params = {surface_param("s"), arg("t").positive(), tolerance_param()},
             .run = [](const Arguments& args) -> Value { return thicken(args); }});
  table.add({.name = "surface_solid",
             .doc = "The solid bounded by surface s, which must be closed in both directions (a torus-like "
                    "surface), from its mesh at tol.",
             .params = {surface_param("s"), tolerance_param()},
             .run = [](const Arguments& args) -> Value { return surface_solid(args); }});
}

}  // namespace sculpt::language
