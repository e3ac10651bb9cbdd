// Built-ins of the solids area: primitives, transforms, classification, measures, mesh export
// and import (lib/bsp, lib/mesh; Ihm & Naylor 1990 sec. 6, Naylor et al. 1990).
#include <cmath>
#include <exception>
#include <filesystem>
#include <optional>
#include <span>
#include <sstream>

#include "base/parallel.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/extrude.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/hull.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/sweep.hpp"
#include "bsp/transform.hpp"
#include "bsp/winding_solid.hpp"
#include "curves/linearization.hpp"
#include "curves/linearize.hpp"
#include "kernel/grid.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"
#include "language/motion_values.hpp"
#include "language/solid_values.hpp"
#include "language/spline_values.hpp"
#include "language/surface_values.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/self_intersection.hpp"
#include "splines/foot_point.hpp"

namespace sculpt::language {
namespace {

const Solid& solid_arg(const Arguments& args, std::string_view i) {
  return args.object<SolidValue>(i, "a solid").solid;
}

/// The parameter of a solid argument named `name`.
Param solid_param(std::string name) { return arg(std::move(name)).of<SolidValue>("a solid"); }

/// The path of a stroke and its tol=e (path_arg, motion_tolerance).
Param path_param() { return arg("path").any("a curve, a spline, a linearization, a motion or a list of points"); }
Param stroke_tolerance_param() { return arg("tol").positive().optional("e"); }

/// A stroke's path (argument i): a linearization's vertices, or a curve, a spline (sampled at 32
/// points per control point) or a list of points, linearized with the fewest segments within
/// tol=e (argument `tol`) when it is given, else taken as it is. A closed path returns to its start.
std::vector<Eigen::Vector3d> path_arg(const Arguments& args, std::string_view i, std::string_view tol) {
  if (const auto* la = args.value(i).object<LinearizationValue>())
    return curves::linearization_points(la->curve->curve, la->result);
  curves::DigitizedCurve c;
  if (const auto* cv = args.value(i).object<CurveValue>()) {
    c = cv->curve;
  } else if (const auto* sv = args.value(i).object<SplineValue>()) {
    c.points = splines::sample(sv->spline, std::max(256, 32 * sv->spline.control_count()));
    c.dimension = sv->spline.dimension();
    c.closed = sv->spline.closed();
  } else if (args.value(i).list()) {
    c = curve_from_points(args, i);
  } else {
    args.fail_type(i, "a curve, a spline, a linearization or a list of points");
  }
  if (c.points.empty()) args.fail(i, "the path has no points");
  std::vector<Eigen::Vector3d> path = c.points;
  if (args.has(tol) && c.points.size() >= 3)
    path = curves::linearization_points(c, curves::linearize(c, {.tolerance = args.number(tol)}));
  if (c.closed && path.back() != path.front()) path.push_back(path.front());
  return path;
}

/// The tol=e of a stroke along a motion: 0 when not given (motion_poses' default).
double motion_tolerance(const Arguments& args) { return args.has("tol") ? args.number("tol") : 0.0; }

/// carve and add: the tool moved along a path (bsp/sweep.hpp). The workpiece is taken in place
/// (the in-place set operations reuse its tree) when the call alone holds it: a temporary, or
/// the variable of `w = carve(w, ...)`, which the interpreter hands over (Builtin::takes_arguments).
template <typename Stroke>
void add_stroke(BuiltinTable& table, const char* name, const char* signature, const char* doc, Stroke stroke) {
  table.add({.name = name,
             .signature = signature,
             .doc = doc,
             .params = {solid_param("work"), solid_param("tool"), path_param(), stroke_tolerance_param()},
             .takes_arguments = true,
             .run = [stroke](const Arguments& args) -> Value {
               const Solid& work = solid_arg(args, "work");
               const Solid& tool = solid_arg(args, "tool");
               // Every argument is checked before the workpiece is taken (Arguments::sole_object).
               auto run = [&](const auto& path) {
                 SolidValue* sole = args.sole_object<SolidValue>("work");
                 return solid_value(sole ? stroke(sole->handed_over(), tool, path) : stroke(work, tool, path));
               };
               if (const auto* m = args.value("path").object<MotionValue>()) {
                 const auto poses = motion_poses(*m, tool, motion_tolerance(args));
                 args.charge(poses.size());
                 return run(poses);
               }
               const auto path = path_arg(args, "path", "tol");
               args.charge(path.size());
               return run(path);
             }});
}

/// The parameters of a round primitive: r= or d=, `segments`, center= (with_center: cylinder, cone).
std::vector<Param> circular_params(bool with_height, bool with_center) {
  std::vector<Param> params{arg("r").positive().optional()};
  if (with_height) params.push_back(arg("h").number());
  params.push_back(arg("segments").integer(3, 100000).defaults(double(CircularOptions{}.segments)));
  if (with_center) params.push_back(arg("center").boolean().defaults(CircularOptions{}.center));
  params.push_back(arg("d").positive().optional("diameter"));
  return params;
}

/// The segments and center=true (if declared) of a round primitive.
CircularOptions circular(const Arguments& args, bool with_center) {
  CircularOptions options{.grid = args.grid()};
  options.segments = static_cast<int>(args.integer("segments"));
  if (with_center) options.center = args.boolean("center");
  return options;
}

/// The radius given as r or as the diameter d=: exactly one of them.
double radius_arg(const Arguments& args) {
  if (args.has("r") && args.has("d")) args.fail("d", "give the radius r or the diameter d=, not both");
  if (args.has("r")) return args.number("r");
  if (args.has("d")) return args.number("d") / 2;
  args.fail("missing argument 'r' (or the diameter d=)");
}

/// box(min, max), box(size) or box(size=v), with center=true centring it on the origin; a size is
/// [sx, sy, sz] or one number for a cube.
Solid box_arg(const Arguments& args) {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi;
  const auto size = [&](std::string_view i) -> Eigen::Vector3d {
    if (const double* s = args.value(i).get<double>()) return Eigen::Vector3d::Constant(*s);
    return args.point(i);
  };
  if (args.has("size")) {
    if (args.has("min") || args.has("max")) args.fail("size", "give size= or the corners min and max, not both");
    hi = size("size");
  } else if (args.has("min") && args.has("max")) {
    lo = args.point("min");
    hi = args.point("max");
  } else if (args.has("min")) {
    hi = size("min");
  } else {
    args.fail("give the corners min and max, or a size");
  }
  if (args.boolean("center")) {
    const Eigen::Vector3d middle = (lo + hi) / 2;
    lo -= middle;
    hi -= middle;
  }
  return box(lo, hi, args.grid());
}

// grid(step): the names of global solids made at another grid than `grid` (they cannot be
// combined with the solids made from now on), at most `limit` of them, and how many there are.
std::pair<std::string, std::size_t> solids_at_other_grids(const Arguments& args, const kernel::Grid& grid,
                                                          std::size_t limit) {
  std::string names;
  std::size_t count = 0;
  for (const auto& [name, value] : args.globals())
    if (const SolidValue* s = value.object<SolidValue>(); s && !is_leaf(s->solid.root()) && s->solid.grid() != grid) {
      if (count++ < limit) names += (names.empty() ? "" : ", ") + name;
    }
  return {names, count};
}

}  // namespace

// The exact kernel snaps vertices to its grid (docs/kernel.md). A valid mesh with features below
// the grid step can become self-intersecting that way (faces 1e-6 apart now touch) without any
// face turning over, which from_mesh would catch: check the snapped copy as well.
PolygonMesh snapped_to_grid(const PolygonMesh& mesh, const kernel::Grid& grid) {
  PolygonMesh snapped = mesh;
  for (Eigen::Vector3d& v : snapped.vertices) v = grid.to_world(grid.snap(v));
  return snapped;
}

std::string snapped_self_intersection(const PolygonMesh& mesh, const kernel::Grid& grid) {
  return snapped_self_intersection(mesh, snapped_to_grid(mesh, grid), grid);
}

std::string snapped_self_intersection(const PolygonMesh& mesh, const PolygonMesh& snapped, const kernel::Grid& grid) {
  if (snapped.vertices == mesh.vertices) return {};  // nothing moved: the caller's validation holds
  const std::vector<FacePair> pairs = find_self_intersections(snapped, {.max_pairs = 1});
  return pairs.empty() ? std::string() : snapped_crossing_message(mesh, pairs[0], grid);
}

std::string snapped_crossing_message(const PolygonMesh& mesh, const FacePair& pair, const kernel::Grid& grid) {
  const Eigen::Vector3d& near = mesh.vertices[std::size_t(mesh.faces[std::size_t(pair.face_a)][0])];
  std::ostringstream out;
  out << "faces " << pair.face_a << " and " << pair.face_b << " (near " << near.x() << ", " << near.y() << ", "
      << near.z() << ") meet when the vertices are snapped to the exact kernel's grid (step " << grid.name()
      << "): the mesh has features smaller than the grid step";
  return out.str();
}

std::string SolidValue::repr() const {
  // The grid is shown when it is not the default (docs/language.md, "World range").
  const std::string grid = solid.grid() == kernel::Grid{} ? "" : ", grid " + solid.grid().name();
  // A set operation's result whose tree is not built yet: printing never builds it (issue 35:
  // `:vars` after a large union ran for minutes); its first use that needs the tree does.
  if (solid.tree_deferred()) return "<solid: tree pending" + grid + ">";
  if (solid.is_empty()) return "<solid: empty" + grid + ">";
  const TreeStats stats = tree_stats(solid);
  return "<solid: " + std::to_string(stats.nodes) + " nodes, height " + std::to_string(stats.height) + grid + ">";
}

double SolidValue::volume() const { return exact_boundary ? mesh_volume(*exact_boundary) : sculpt::volume(solid); }

double SolidValue::area() const {
  return exact_boundary ? mesh_surface_area(*exact_boundary) : surface_area(solid);
}

std::optional<Value> SolidValue::binary(ast::Op op, const Value& other, bool self_on_left) const {
  const SolidValue* that = other.object<SolidValue>();
  if (!that) return std::nullopt;
  const Solid& a = self_on_left ? solid : that->solid;
  const Solid& b = self_on_left ? that->solid : solid;
  switch (op) {
    case ast::Op::Union: return solid_value(unite(a, b));
    case ast::Op::Intersect: return solid_value(intersect(a, b));
    case ast::Op::Sub: return solid_value(subtract(a, b));
    default: return std::nullopt;
  }
}

std::optional<Value> SolidValue::binary_sole(ast::Op op, const Value& other) {
  const SolidValue* that = other.object<SolidValue>();
  if (!that) return std::nullopt;
  // Nothing else holds this value (Value::sole_object): its tree is reused (the in-place set
  // operations), which leaves this object empty; `that` is another object (it holds its own).
  switch (op) {
    case ast::Op::Union: return solid_value(unite(handed_over(), that->solid));
    case ast::Op::Intersect: return solid_value(intersect(handed_over(), that->solid));
    case ast::Op::Sub: return solid_value(subtract(handed_over(), that->solid));
    default: return std::nullopt;
  }
}

Value solid_value(Solid solid) {
  return Value(std::shared_ptr<const Object>(std::make_shared<SolidValue>(std::move(solid))));
}

void write_mesh_file(const PolygonMesh& mesh, const std::filesystem::path& path, std::optional<bool> binary) {
  const MeshFormat format = mesh_format_from_path(path);  // an unknown extension is refused before folders are made
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::size_t triangles = 0;  // as the STL writer splits the faces
  for (const auto& face : mesh.faces) triangles += face.size() >= 3 ? face.size() - 2 : 0;
  write_mesh(mesh, path, {.binary = binary.value_or(format == MeshFormat::Stl && triangles > kAutoBinaryStlTriangles)});
}

std::string export_solid(const SolidValue& s, const std::filesystem::path& path, std::optional<bool> binary) {
  write_mesh_file(s.boundary(), path, binary);
  // Written all the same (the exact solid is fine; other tools may stumble on it).
  if (s.boundary_problem().empty()) return "";
  return path.string() + ": the mesh is not known to be clean for other tools (" + s.boundary_problem() +
         "; docs/kernel.md, \"Clean output\")";
}

std::string latest_solid_global(const Interpreter& interpreter) {
  std::string latest;
  std::uint64_t serial = 0;
  for (const std::string& name : interpreter.global_names()) {
    const std::uint64_t at = interpreter.assigned_at(name);
    if (at > serial && interpreter.global(name)->object<SolidValue>()) serial = at, latest = name;
  }
  return latest;
}

namespace {

/// What snap rounding removed to make an imported mesh fit the grid ("2 short edges contracted, 1
/// sliver flipped"), or "" when it did nothing but snap and triangulate.
std::string removed_features(const OutputRoundingReport& r) {
  std::string out;
  auto add = [&](int n, const char* one, const char* many) {
    if (n > 0) out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + (n == 1 ? one : many);
  };
  add(r.collapsed_edges, "short edge contracted", "short edges contracted");
  add(r.flipped_edges, "sliver flipped", "slivers flipped");
  add(r.separated_vertices, "touching vertex moved apart", "touching vertices moved apart");
  add(r.nudged_vertices, "corner moved off a crossing face", "corners moved off crossing faces");
  return out;
}

/// What the winding-number import resolved, from the validation's defects: "12 face pairs
/// intersect, 3 edges have more than two faces".
std::string resolved_defects(const ValidationReport& report) {
  std::string out;
  auto add = [&](DefectKind kind, const char* what) {
    const std::size_t n = report.count(kind);
    if (n == 0) return;
    out += (out.empty() ? "" : ", ") + std::to_string(n) +
           (n >= ValidationOptions{}.max_defects_per_kind ? " or more " : " ") + what;
  };
  add(DefectKind::SelfIntersection, "face pairs intersect");
  add(DefectKind::NonManifoldEdge, "edges have more than two faces");
  add(DefectKind::NonManifoldVertex, "vertices join separate fans of faces");
  add(DefectKind::InconsistentOrientation, "edges run the same way in both of their faces");
  add(DefectKind::DegenerateFace, "faces have zero area");
  add(DefectKind::NonPlanarFace, "faces are not planar");
  add(DefectKind::SelfCrossingFace, "faces cross themselves");
  return out;
}

/// import's solid of a closed mesh that is no clean 2-manifold: where its winding number is positive
/// (bsp/winding_solid.hpp), with a line that says what was resolved. A mesh that turns out not to be
/// closed after all is refused with `refusal` (or the library's message, which lists open edges).
Value winding_import(const Arguments& args, const PolygonMesh& mesh, const std::string& path,
                     const std::string& resolved, const std::string& refusal) {
  WindingSolid w;
  try {
    w = positive_winding_solid(mesh, {.grid = args.grid()});
  } catch (const GeometryError& e) {
    args.fail(refusal.empty() ? path + ": " + e.what() : refusal);
  }
  args.err() << "import: " << path << ": " << resolved << ": imported the region of positive winding number";
  if (w.multiple_cells > 0 || w.negative_cells > 0) {
    args.err() << " (";
    if (w.multiple_cells > 0) args.err() << "parts enclosed more than once count once";
    if (w.multiple_cells > 0 && w.negative_cells > 0) args.err() << "; ";
    if (w.negative_cells > 0) args.err() << "parts enclosed by inward-facing shells are left out";
    args.err() << ")";
  }
  args.err() << "\n";
  return solid_value(std::move(w.solid));
}

}  // namespace

void register_solids(BuiltinTable& table) {
  table.add({.name = "grid",
             .doc = "The world range (docs/kernel.md, \"World range\"): solids made after grid(step) snap their "
                    "coordinates to multiples of step, a power of two 2^-k with k in [-32, 64] (pow(2, -10)), and "
                    "hold coordinates up to 2^25 steps: the default 2^-15 gives [-1024, 1024], 2^-13 gives "
                    "[-4096, 4096]. Returns the step in effect (grid() only reads it). Call it before the first "
                    "solid: solids made at different grids cannot be combined (a later call says which solids "
                    "are at the old grid). `sculpt --grid STEP` sets it for a whole run.",
             .params = {arg("step").number().optional()},
             .run = [](const Arguments& args) -> Value {
               if (!args.has("step")) return args.grid().step();
               kernel::Grid grid;
               try {
                 grid = kernel::Grid::from_step(args.number("step"));
               } catch (const InvalidInput& e) {
                 args.fail("step", e.what());
               }
               const kernel::Grid old = args.grid();
               args.set_grid(grid);
               if (grid != old) {
                 const auto [names, count] = solids_at_other_grids(args, grid, 5);
                 if (count > 0)
                   args.err() << "note: grid(" << grid.name() << "): " << count << (count == 1 ? " solid" : " solids")
                              << " (" << names << (count > 5 ? ", ..." : "") << ") made at another grid cannot be "
                              << "combined with solids made from now on\n";
               }
               return grid.step();
             }});
  table.add({.name = "box",
             .doc = "The axis-aligned box with corners min and max ([x, y, z] each, min < max); or, given one "
                    "vector (or size=), the box of that size ([sx, sy, sz], or one number for a cube) with a "
                    "corner at the origin. center=true centres the box on the origin.",
             .params = {arg("min").any("a vector [x, y, z] or a size").optional(), arg("max").vector(3).optional(),
                        arg("center").boolean().defaults(false),
                        arg("size").any("a vector [sx, sy, sz] or a number").optional("v")},
             .run = [](const Arguments& args) { return solid_value(box_arg(args)); }});
  table.add(
      {.name = "sphere",
       .doc = "Sphere of radius r (or diameter d) at the origin: a polyhedron with `segments` edges around "
              "the equator, (segments + 1) / 2 rings as OpenSCAD's and a vertex at each pole, its vertices on "
              "the sphere.",
       .params = circular_params(false, false),
       .run = [](const Arguments& args) { return solid_value(sphere(radius_arg(args), circular(args, false))); }});
  table.add({.name = "cylinder",
             .doc = "Cylinder of radius r (or diameter d) around the z axis from z = 0 to z = h, or from -h/2 "
                    "to h/2 with center=true (a prism over a regular polygon with `segments` vertices on the "
                    "circle).",
             .params = circular_params(true, true),
             .run = [](const Arguments& args) {
               return solid_value(cylinder(radius_arg(args), args.number("h"), circular(args, true)));
             }});
  table.add({.name = "cone",
             .doc = "Cone around the z axis: base of radius r (or diameter d) at z = 0, apex at z = h; with "
                    "center=true the base is at z = -h/2 and the apex at h/2.",
             .params = circular_params(true, true),
             .run = [](const Arguments& args) {
               const CircularOptions c = circular(args, true);
               return solid_value(cone(radius_arg(args), args.number("h"),
                                       {.segments = c.segments, .center = c.center, .grid = c.grid}));
             }});
  table.add({.name = "union_all",
             .doc = "The union of a list of solids, computed at once: each solid's boundary is clipped "
                    "by the others and one tree is built from the union's boundary (much faster than "
                    "chaining | over many solids; the same set, exactly).",
             .params = {arg("solids").list()},
             .run = [](const Arguments& args) {
               const List& items = args.list("solids");
               args.charge(items.size());
               std::vector<Solid> solids;
               solids.reserve(items.size());
               for (std::size_t i = 0; i < items.size(); ++i) {
                 const SolidValue* s = items[i].object<SolidValue>();
                 if (!s)
                   args.fail("solids",
                             "item " + std::to_string(i + 1) + " is " + type_name(items[i]) + ", not a solid");
                 solids.push_back(s->solid);
               }
               return solid_value(unite_all(std::move(solids)));
             }});
  table.add(
      {.name = "extrude",
       .doc = "The prism over a closed polygon in the xy-plane (a curve or a list of [x, y] or "
              "[x, y, z] points with one z; convex or not, either orientation) from its plane up by "
              "`height` (down if negative). As OpenSCAD's linear_extrude, the far end may be turned by "
              "`twist` degrees (clockwise seen from above for a positive twist, OpenSCAD's sign) and "
              "scaled about the z axis by `scale` (a number or [sx, sy], >= 0; 0 gives an apex), "
              "linearly over `slices` layers (default: 1 without twist, else one per 5 degrees).",
       .params = {arg("profile").any("a curve or a list of points"), arg("height").non_zero(),
                  arg("twist").finite_number().defaults(ExtrudeOptions{}.twist),
                  arg("scale").any("a number >= 0 or [sx, sy]").defaults(1.0),
                  arg("slices").integer(1, 100000).optional("auto")},
       .run = [](const Arguments& args) -> Value {
         const PlanePolygon profile =
             plane_polygon_arg(args, "profile", "a curve or a list of points",
                               "the profile is not in a plane z = constant (rotate the result instead)");
         const std::vector<Eigen::Vector2d>& polygon = profile.points;
         const double z = profile.z, h = args.number("height");
         ExtrudeOptions options{.twist = args.number("twist"), .grid = args.grid()};
         if (args.value("scale").list()) {
           const std::vector<double> v = args.vector("scale", 2);
           options.scale = {v[0], v[1]};
         } else {
           options.scale.setConstant(args.number("scale"));
         }
         if (!std::isfinite(options.scale.x()) || !std::isfinite(options.scale.y()) || options.scale.minCoeff() < 0)
           args.fail("scale", "the scale must be finite and >= 0");
         if ((options.scale.x() == 0) != (options.scale.y() == 0))
           args.fail("scale", "one zero factor alone would end in an edge: use 0 (or [0, 0]) for an apex");
         options.slices = args.has("slices") ? static_cast<int>(args.integer("slices")) : default_slices(options.twist);
         args.charge(polygon.size() * static_cast<std::size_t>(options.slices));
         if (options.twist == 0 && options.scale == Eigen::Vector2d(1, 1) && options.slices == 1)
           return solid_value(extrude(polygon, std::min(z, z + h), std::max(z, z + h), args.grid()));
         return solid_value(extrude(polygon, z, z + h, options));
       }});
  table.add({.name = "hull",
             .doc = "The convex hull of x: a list of points [x, y, z], a curve, a solid, or a list of "
                    "solids, as a convex solid with one plane per face (exact on the kernel grid).",
             .params = {arg("x").any("a list of points, a curve, a solid or a list of solids")},
             .run = [](const Arguments& args) -> Value {
               const Value& x = args.value("x");
               if (const auto* s = x.object<SolidValue>()) return solid_value(hull(std::span(&s->solid, 1)));
               if (const auto* c = x.object<CurveValue>()) return solid_value(hull(c->curve.points, args.grid()));
               const List& items = args.list("x");
               if (!items.empty() && items.front().object<SolidValue>()) {
                 std::vector<Solid> solids;
                 for (std::size_t i = 0; i < items.size(); ++i) {
                   const SolidValue* s = items[i].object<SolidValue>();
                   if (!s)
                     args.fail("x", "item " + std::to_string(i + 1) + " is " + type_name(items[i]) + ", not a solid");
                   solids.push_back(s->solid);
                 }
                 args.charge(solids.size());
                 return solid_value(hull(solids));
               }
               return solid_value(hull(curve_from_points(args, "x").points, args.grid()));
             }});
  table.add({.name = "sweep",
             .doc = "The volume swept by solid `tool` moved along `path` (a curve, a spline, a linearization "
                    "or a list of points; all but a linearization are first linearized with the fewest segments "
                    "within tol=e when tol is given): the union of the hulls of the tool's convex pieces at the "
                    "ends of each segment. `path` may be a motion (motion(...)): the tool, in body coordinates "
                    "(its origin follows the motion), is carried along it turning, sampled so that the result "
                    "is within tol (default 1 % of the tool's size) of the true swept volume (docs/motions.md).",
             .params = {solid_param("tool"), path_param(), stroke_tolerance_param()},
             .run = [](const Arguments& args) -> Value {
               if (const auto* m = args.value("path").object<MotionValue>()) {
                 const auto poses = motion_poses(*m, solid_arg(args, "tool"), motion_tolerance(args));
                 args.charge(poses.size());
                 return solid_value(sweep(solid_arg(args, "tool"), poses));
               }
               const auto path = path_arg(args, "path", "tol");
               args.charge(path.size());
               return solid_value(sweep(solid_arg(args, "tool"), path));
             }});
  add_stroke(table, "carve", "carve(work, tool, path, tol=e)",
             "Solid `work` minus `tool` swept along `path` (see sweep): a carving stroke. `w = carve(w, ...)` "
             "carves w in place (no copy of its tree) unless another variable holds the same solid. The "
             "subtrees the stroke touched are then rebuilt from the boundary where that makes them smaller "
             "(the same solid, a smaller tree: docs/sculpting.md).",
             [](auto&& w, const Solid& t, const auto& p) { return carve(std::forward<decltype(w)>(w), t, p); });
  add_stroke(table, "add", "add(work, tool, path, tol=e)",
             "Solid `work` united with `tool` swept along `path` (see sweep): an adding stroke. `w = add(w, ...)` "
             "works in place like carve.",
             [](auto&& w, const Solid& t, const auto& p) { return add(std::forward<decltype(w)>(w), t, p); });
  table.add({.name = "transform",
             .doc = "Solid s mapped by the affine map given as 3 rows of 4 numbers [[a, b, c, tx], ...] "
                    "(x' = a x + b y + c z + tx); integer linear parts are exact, others move vertices to "
                    "the grid like rotate. A singular map is an error.",
             .params = {solid_param("s"), arg("matrix").list()},
             .run = [](const Arguments& args) -> Value {
               const List& rows = args.list("matrix");
               if (rows.size() != 3) args.fail("matrix", "the matrix must have 3 rows of 4 numbers");
               Eigen::Affine3d m = Eigen::Affine3d::Identity();
               for (int r = 0; r < 3; ++r) {
                 const List* row = rows[std::size_t(r)].list();
                 if (!row || row->size() != 4)
                   args.fail("matrix", "row " + std::to_string(r + 1) + " must have 4 numbers");
                 for (int c = 0; c < 4; ++c) {
                   const double* x = (*row)[std::size_t(c)].get<double>();
                   if (!x || !std::isfinite(*x))
                     args.fail("matrix", "row " + std::to_string(r + 1) + " must have 4 finite numbers");
                   m.matrix()(r, c) = *x;
                 }
               }
               return solid_value(transform(solid_arg(args, "s"), m));
             }});
  table.add(
      {.name = "translate",
       .doc = "Solid s moved by the vector v (exact: v is snapped to the kernel grid).",
       .params = {solid_param("s"), arg("v").vector(3)},
       .run = [](const Arguments& args) { return solid_value(translate(solid_arg(args, "s"), args.point("v"))); }});
  table.add({.name = "mirror",
             .doc = "Solid s reflected in the plane through the origin with the given normal. Mirrors in "
                    "the coordinate planes are exact; others move vertices to the grid like rotate.",
             .params = {solid_param("s"), arg("normal").vector(3)},
             .run = [](const Arguments& args) -> Value {
               const Eigen::Vector3d n = args.point("normal");
               if (!(n.squaredNorm() > 0) || !n.allFinite())
                 args.fail("normal", "the normal must be a non-zero finite vector");
               const int axis = n.x() != 0 ? (n.y() == 0 && n.z() == 0 ? 0 : -1)
                                           : (n.y() != 0 ? (n.z() == 0 ? 1 : -1) : 2);
               if (axis >= 0) {  // an integer map: exact
                 Eigen::Vector3d f = Eigen::Vector3d::Ones();
                 f[axis] = -1;
                 return solid_value(scale(solid_arg(args, "s"), f));
               }
               const Eigen::Vector3d u = n.normalized();
               Eigen::Affine3d m = Eigen::Affine3d::Identity();
               m.linear() -= 2 * u * u.transpose();
               return solid_value(transform(solid_arg(args, "s"), m));
             }});
  table.add({.name = "rotate",
             .doc = "Solid s rotated by `degrees` about `axis` through the origin (right-handed). "
                    "Multiples of 90 degrees about a coordinate axis are exact.",
             .params = {solid_param("s"), arg("axis").vector(3), arg("degrees").finite_number()},
             .run = [](const Arguments& args) {
               return solid_value(rotate(solid_arg(args, "s"), args.point("axis"), args.number("degrees")));
             }});
  table.add({.name = "scale",
             .doc = "Solid s scaled by the factors [sx, sy, sz] (or one number for all three); "
                    "non-zero, negative factors mirror. Whole factors are exact.",
             .params = {solid_param("s"), arg("v").any("a vector [sx, sy, sz] or a number")},
             .run = [](const Arguments& args) {
               Eigen::Vector3d factors;
               if (const double* f = args.value("v").get<double>()) {
                 factors = Eigen::Vector3d::Constant(*f);
               } else {
                 factors = args.point("v");
               }
               return solid_value(scale(solid_arg(args, "s"), factors));
             }});
  table.add({.name = "classify",
             .doc = "Where the point p lies with respect to solid s: \"in\", \"out\" or \"on\" (the "
                    "boundary), decided exactly on the kernel grid.",
             .params = {solid_param("s"), arg("p").vector(3)},
             .run = [](const Arguments& args) -> Value {
               switch (classify(solid_arg(args, "s"), args.point("p")).location) {
                 case Location::Inside:
                   return "in";
                 case Location::Outside:
                   return "out";
                 case Location::Boundary:
                   return "on";
               }
               return "out";
             }});
  table.add({.name = "volume",
             .doc = "The volume of solid s (from its exact boundary).",
             .params = {solid_param("s")},
             .run = [](const Arguments& args) -> Value { return args.object<SolidValue>("s").volume(); }});
  table.add({.name = "area",
             .doc = "The surface area of solid s.",
             .params = {solid_param("s")},
             .run = [](const Arguments& args) -> Value { return args.object<SolidValue>("s").area(); }});
  table.add(
      {.name = "export",
       .doc = "Writes the boundary of solid s as a mesh (or a mesh value, such as a patch, as it is; or a "
              "surface's triangle mesh at chord tolerance `tol`, as surface_mesh); the format comes from "
              "the extension: .off, .obj, .stl, .ply, .om, .3mf (millimetres), .glb (binary glTF). The file is "
              "replaced atomically; folders are created. binary=true writes binary STL or PLY (STL: "
              "float32, a fifth of ASCII's size), binary=false ASCII; left out, an STL file of more than "
              "100,000 triangles is binary and every other file ASCII.",
       .params = {arg("s").any("a solid, a mesh or a surface"), arg("file").string().shown_as("\"file.off\""),
                  arg("tol").positive().defaults(kDefaultSurfaceTolerance), arg("binary").boolean().optional("auto")},
       .run = [](const Arguments& args) -> Value {
         const std::optional<bool> binary = args.has("binary") ? std::optional(args.boolean("binary")) : std::nullopt;
         if (binary == true) {
           const MeshFormat format = mesh_format_from_path(args.file_path("file"));
           if (format != MeshFormat::Stl && format != MeshFormat::Ply)
             args.fail("binary", "binary=true applies to .stl and .ply (the other formats have one encoding)");
         }
         if (const auto* surface = args.value("s").object<SurfaceValue>()) {
           write_mesh_file(surface_triangle_mesh(args, surface->surface, args.number("tol")), args.file_path("file"),
                           binary);
           return {};
         }
         if (args.has("tol")) args.fail("tol", "tol applies to surfaces only");
         if (const auto* m = args.value("s").object<MeshValue>()) {
           write_mesh_file(m->mesh, args.file_path("file"), binary);
           return {};
         }
         const auto& s = args.object<SolidValue>("s");
         if (const std::string warning = export_solid(s, args.file_path("file"), binary); !warning.empty())
           args.err() << "export: warning: " << warning << "\n";
         return {};
       }});
  table.add(
      {.name = "import",
       .doc = "Reads a mesh (.off, .obj, .stl, .ply, .om, .3mf, .glb) and builds its BSP solid. A closed, "
              "oriented 2-manifold that does not intersect itself bounds the solid; a closed mesh whose faces "
              "intersect or meet at non-manifold edges gives the region where its winding number is "
              "positive, and the import says what it resolved (strict=true refuses such a mesh instead).",
       .params = {arg("file").string().shown_as("\"file.off\""), arg("strict").boolean().defaults(false)},
       .run = [](const Arguments& args) -> Value {
         const std::string path = args.input_path("file");
         const bool strict = args.boolean("strict");
         const PolygonMesh mesh = read_mesh(path);
         // The topology, and the faces searched for crossings once, in the mesh snapped to
         // the grid (what the solid is built from); the mesh as read only when that finds one,
         // to tell its own crossings from those snapping made. (A crossing below the grid step
         // that snapping undoes is not reported.) The two run side by side where the search
         // can read the mesh; its answer (or error) counts only when the topology is clean.
         ValidationReport report;
         std::vector<FacePair> snapped_pairs;
         const auto topology = [&] { report = check_closed_manifold(mesh, {.check_self_intersections = false}); };
         const auto crossings = [&] {
           snapped_pairs = find_self_intersections(snapped_to_grid(mesh, args.grid()), {.max_pairs = 1});
         };
         std::exception_ptr search_error;
         if (indices_and_coordinates_valid(mesh))
           search_error = parallel_invoke_holding_second(topology, crossings);
         else
           topology();
         if (report.ok() && search_error) std::rethrow_exception(search_error);
         if (!report.ok()) snapped_pairs.clear();
         const bool snapped_crosses = !snapped_pairs.empty();
         if (!report.ok() || snapped_crosses) report = check_closed_manifold(mesh);
         if (!report.ok()) {
           // A shell turned the wrong way (all faces inwards, or a cavity facing outwards) is
           // closed and manifold but bounds the wrong side: say so in those words.
           const bool misoriented = report.count(DefectKind::MisorientedShell) == report.defects.size();
           const std::string refusal =
               path +
               (misoriented ? ": the faces of a shell are oriented the wrong way: " : " is not a closed manifold: ") +
               report.summary(3);
           // An open mesh (or one beyond reading) bounds nothing: refused with what is open.
           const bool closed = report.count(DefectKind::OpenEdge) == 0 && report.count(DefectKind::InvalidIndex) == 0 &&
                               report.count(DefectKind::NonFiniteCoordinate) == 0;
           if (strict || misoriented || !closed) args.fail(refusal);
           return winding_import(args, mesh, path, resolved_defects(report), refusal);
         }
         // Snapping to the grid can make faces meet or fold where the mesh has features
         // below the grid step; such features are collapsed as transforms do (every vertex
         // within 4 grid steps of its place, docs/kernel.md, "What transforms do"), and the
         // import fails only if that does not suffice.
         // (A crossing of the snapped mesh, the mesh as read being free of them: the first
         // search's pair names it.)
         std::string snap_error = snapped_crosses ? snapped_crossing_message(mesh, snapped_pairs[0], args.grid()) : "";
         if (snap_error.empty()) {
           try {  // checked before and after snapping: the faces are the boundary (from_mesh.hpp)
             return solid_value(from_mesh(mesh, {.snapped_mesh_is_clean = true, .grid = args.grid()}));
           } catch (const GeometryError& e) {
             snap_error = e.what();
           } catch (const InvalidInput& e) {
             // A face whose corners snap onto one line (two corners closer than a grid step,
             // as an exact solid's export can have): the collapse below removes it.
             snap_error = e.what();
           }
         }
         OutputRoundingReport rounding;
         const PolygonMesh collapsed = round_for_output(mesh,
                                                        {.precision = OutputPrecision::Grid,
                                                         .max_feature = 4 * args.grid().step(),
                                                         .triangles = true,
                                                         .grid_step = args.grid().step(),
                                                         .keep_copies = true},
                                                        &rounding);
         if (!rounding.clean) {
           // The snapped mesh still encloses a well-defined region: where its winding number is positive.
           if (strict) args.fail(path + ": " + snap_error);
           return winding_import(args, mesh, path,
                                 "features below the grid step (" + args.grid().name() +
                                     ") meet when its vertices are snapped to the grid",
                                 "");
         }
         // Only warn when a feature was removed: every import snaps each vertex to its grid
         // point (up to 0.87 steps), and the faces may only have been split into triangles
         // that fit the grid; that changes nothing the user made.
         if (const std::string removed = removed_features(rounding); !removed.empty())
           args.err() << "import: warning: " << path
                      << ": features below 4 grid steps were collapsed to fit the grid (step " << args.grid().name()
                      << "): " << removed << "; vertices moved by up to "
                      << format_number(rounding.max_move / args.grid().step()) << " grid steps\n";
         return solid_value(from_mesh(collapsed, {.snapped_mesh_is_clean = true, .grid = args.grid()}));
       }});
}

}  // namespace sculpt::language
