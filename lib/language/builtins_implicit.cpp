// Built-ins of the implicit area: tracing the space curve f = g = 0 of two script functions
// (Ihm & Naylor 1990, sec. 5.1; lib/implicit) and implicit solids {f <= 0} in a box, meshed by
// lib/implicit (polygonize.hpp) and built into BSP solids here (the implicit layer knows no bsp).
// The functions are compiled once into expressions (implicit_compiler.hpp), so the tracer and
// the mesher never run the interpreter per point. See docs/implicit.md.
#include <cmath>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>

#include "curves/digitized_curve.hpp"
#include "bsp/from_mesh.hpp"
#include "implicit/patch.hpp"
#include "implicit/polygonize.hpp"
#include "implicit/trace.hpp"
#include "kernel/grid.hpp"
#include "language/solid_values.hpp"
#include "mesh/self_intersection.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"
#include "language/implicit_compiler.hpp"

namespace sculpt::language {
namespace {

/// Tolerances below this times the box diagonal are refused (the tracer's own floor: its
/// Newton residuals are held to 1e-12 of the diagonal, and the point count grows as tol^-1/2).
constexpr double kMinRelativeTolerance = 1e-9;
/// Largest step budget a script may give (about 150 s of tracing).
constexpr long long kMaxSteps = 10'000'000;

const UserFunction& function_arg(const Arguments& args, std::string_view i) {
  if (const auto* f = args.value(i).get<std::shared_ptr<const UserFunction>>()) return **f;
  args.fail_type(i, "a function fn f(x, y, z) or fn f(p)");
}

/// The script function of argument i compiled into an expression; a construct outside the
/// compiled subset is an error at the construct, with a note at this call.
implicit::Expression compiled_arg(const Arguments& args, std::string_view i) {
  const UserFunction& f = function_arg(args, i);
  ImplicitCompileOptions options;
  options.global = [&args](const std::string& name) { return args.global(name); };
  try {
    return compile_implicit(f, options);
  } catch (ScriptError& e) {
    e.add_note({args.call(), "in compiling '" + f.name + "' for this call"});
    throw;
  }
}

implicit::Box implicit_box_arg(const Arguments& args, std::string_view i) {
  const List& corners = args.list(i);
  implicit::Box box;
  if (corners.size() != 2) args.fail(i, "box must be [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
  for (int c = 0; c < 2; ++c) {
    const List* xyz = corners[c].list();
    if (!xyz || xyz->size() != 3) args.fail(i, "box must be [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
    for (int a = 0; a < 3; ++a) {
      const double* v = (*xyz)[a].get<double>();
      if (!v || !std::isfinite(*v)) args.fail(i, "box corners must be finite numbers");
      (c == 0 ? box.lo : box.hi)[a] = *v;
    }
  }
  for (int a = 0; a < 3; ++a) {
    if (!(box.lo[a] < box.hi[a])) {
      args.fail(i, std::string("the box is empty: its first corner must be below its second in x, y and z (") +
                       "xyz"[a] + ": " + format_number(box.lo[a]) + " >= " + format_number(box.hi[a]) + ")");
    }
  }
  return box;
}

implicit::TraceOptions options_arg(const Arguments& args) {
  implicit::TraceOptions options;
  if (!args.has("box")) args.fail("give box=[[xmin, ymin, zmin], [xmax, ymax, zmax]], the region to trace in");
  options.box = implicit_box_arg(args, "box");
  const double diagonal = (options.box.hi - options.box.lo).norm();
  if (args.has("tol")) {
    const double tol = args.number("tol");
    if (tol < kMinRelativeTolerance * diagonal) {
      args.fail("tol", "tol=" + format_number(tol) + " is below the floor of 1e-9 times the box diagonal (" +
                           format_number(kMinRelativeTolerance * diagonal) + " here)");
    }
    if (tol > diagonal) args.fail("tol", "tol=" + format_number(tol) + " is larger than the box diagonal");
    options.tolerance = tol;
  }
  options.max_steps = static_cast<long>(args.integer("steps"));
  return options;
}

/// Traces f = g = 0; a point where f or g is not finite is an error at that function's argument.
implicit::TraceResult run_trace(const Arguments& args) {
  const implicit::Expression f = compiled_arg(args, "f");
  const implicit::Expression g = compiled_arg(args, "g");
  const implicit::TraceOptions options = options_arg(args);
  implicit::TraceResult result;
  try {
    result = implicit::trace(f, g, options);
  } catch (const implicit::NonFiniteValue& e) {
    // Which of the two: evaluate both where the tracer stopped.
    std::string_view culprit = "g";
    try {
      (void)f.value_gradient(e.point());
    } catch (const implicit::NonFiniteValue&) {
      culprit = "f";
    }
    const std::string name = function_arg(args, culprit).name;
    args.fail(culprit, "'" + name + "' (or its gradient) is not finite at " + format_point(e.point()) +
                           " (a division by zero, the square root of a negative number or an overflow); trace in a "
                           "box where it is defined");
  }
  args.charge(static_cast<std::uint64_t>(result.steps));
  return result;
}

Value curves_value(const implicit::TraceResult& r) {
  List out;
  for (const implicit::TracedCurve& c : r.curves) {
    curves::DigitizedCurve curve;
    curve.points = c.points;
    curve.dimension = 3;
    curve.closed = c.closed;
    curve.name = "trace";
    out.emplace_back(std::shared_ptr<const Object>(std::make_shared<CurveValue>(std::move(curve))));
  }
  return out;
}

/// "trace: 2 curves (2 closed), 306 points, 0 singular points, 404 steps", and a warning when
/// the budget ran out or a singular point could not be passed.
void print_summary(const Arguments& args, const implicit::TraceResult& r, long max_steps) {
  std::size_t closed = 0, points = 0, unresolved = 0;
  for (const auto& c : r.curves) {
    closed += c.closed ? 1 : 0;
    points += c.points.size();
  }
  for (const auto& s : r.singular_points) unresolved += s.resolved ? 0 : 1;
  std::ostringstream s;
  s << "trace: " << r.curves.size() << (r.curves.size() == 1 ? " curve" : " curves");
  if (!r.curves.empty()) s << " (" << closed << " closed)";
  s << ", " << points << " points, " << r.singular_points.size()
    << (r.singular_points.size() == 1 ? " singular point" : " singular points");
  if (unresolved > 0) s << " (" << unresolved << " not passed)";
  s << ", " << r.steps << " steps\n";
  if (r.budget_exhausted) {
    s << "trace: warning: the step budget of " << max_steps
      << " ran out; the curves may be incomplete (give steps=n for more)\n";
  }
  args.err() << s.str();
}

/// The mesher's default work budget (cells; about 10 s on this machine) and the most a script may give.
constexpr long kDefaultCells = 2'000'000;
constexpr long long kMaxCells = 50'000'000;
/// tol must be at least this many grid steps of the exact kernel: snapping moves each vertex by
/// up to half a step's diagonal (0.87 steps).
constexpr double kMinToleranceSteps = 4.0;
/// Mesh vertices stay this many grid steps from the lattice points of the mesher's cells, so that
/// snapping cannot put one on a lattice point (a closing face's corner) or on its neighbour.
constexpr double kMinRootGapSteps = 2.0;
/// Triangles less high than this many grid steps are collapsed away by the mesher where it can.
constexpr double kMinHeightSteps = 8.0;

/// from_mesh's settings for the polygonizer's meshes (thousands of small triangles spread over
/// a curved surface): fewer candidates scored against a smaller sample, and axis-aligned planes
/// charged less than the defaults (tuned on the goblet, the bunny and the Menger sponge). On the
/// torus, the blend and a spherical shell (bench_from_mesh implicit_*; docs/benchmarks.md, issue
/// 16) the tree is built in about 0.8 of the time with an expected depth 0.7 of the defaults',
/// at 15-20 % more nodes. Zero-area triangles after snapping are left out (they bound nothing).
FromMeshOptions from_mesh_options(const kernel::Grid& grid) {
  return {.candidates = 3, .sample = 24, .auxiliary_cost = 0.2, .skip_degenerate_faces = true, .grid = grid};
}

/// What helps when the snapped mesh's faces meet: vertices moved less, by a finer grid, where the
/// box fits one (a larger or smaller tol only moves the mesh's vertices elsewhere).
std::string snapping_advice(const implicit::Box& box, const kernel::Grid& grid) {
  const double extent = std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff());
  const std::optional<kernel::Grid> finest = kernel::Grid::fitting(extent);
  if (!finest || finest->shift() <= grid.shift()) {
    return "the box needs the whole range of this grid, so no finer grid holds it: a smaller box, or a function "
           "without features that small";
  }
  const int shift = std::min(finest->shift(), grid.shift() + 8);  // 256 times finer at most
  return "a finer grid moves the vertices less: grid(pow(2, -" + std::to_string(shift) +
         ")) before implicit (its range, " +
         format_number(kernel::Grid::from_step(std::ldexp(1.0, -shift)).max_world()) + ", holds the box)";
}

/// implicit(f, box, tol): the solid {f <= 0} inside the box, meshed by implicit::polygonize and
/// built into a BSP tree from its boundary.
Value implicit_solid(const Arguments& args) {
  const implicit::Expression f = compiled_arg(args, "f");
  if (!args.has("box")) args.fail("give box=[[xmin, ymin, zmin], [xmax, ymax, zmax]], the region of the solid");
  implicit::PolygonizeOptions options{.box = implicit_box_arg(args, "box")};
  const double diagonal = (options.box.hi - options.box.lo).norm();
  options.tolerance = args.number("tol");
  const kernel::Grid grid = args.grid();
  const double floor = kMinToleranceSteps * grid.step();
  if (options.tolerance < floor) {
    args.fail("tol", "tol=" + format_number(options.tolerance) + " is below 4 steps of the exact kernel's grid (" +
                         format_number(floor) + "): the solid's vertices are snapped to that grid");
  }
  const double longest = (options.box.hi - options.box.lo).maxCoeff();
  if (options.tolerance < 4e-6 * longest) {
    args.fail("tol", "tol=" + format_number(options.tolerance) + " is below 4e-6 of the box's longest side (" +
                         format_number(4e-6 * longest) + "), the mesher's finest cells");
  }
  if (options.tolerance > diagonal)
    args.fail("tol", "tol=" + format_number(options.tolerance) + " is larger than the box diagonal");
  // Slivers below a few grid steps could turn over when the vertices are snapped to the grid.
  options.min_height = kMinHeightSteps * grid.step();
  options.min_root_gap = kMinRootGapSteps * grid.step();
  options.max_cells = static_cast<long>(args.integer("cells"));
  // The solid is cut from the mesh with its vertices snapped to the kernel's grid (from_mesh), so
  // that copy is what must not intersect itself: polygonize tests it instead of the simplified
  // mesh itself (one exact test instead of two), and keeps its marched mesh if it fails.
  std::shared_ptr<PolygonMesh> snapped;
  options.accept_simplified = [&snapped, &grid](const PolygonMesh& m) {
    snapped = std::make_shared<PolygonMesh>(snapped_to_grid(m, grid));
    if (find_self_intersections(*snapped, {.max_pairs = 1}).empty()) return true;
    snapped.reset();
    return false;
  };
  implicit::PolygonizeResult r;
  try {
    r = implicit::polygonize(f, options);
  } catch (const implicit::NonFiniteValue& e) {
    args.fail("f", "'" + function_arg(args, "f").name + "' is not finite at " + format_point(e.point()) +
                       " (a division by zero, the square root of a negative number or an overflow); give a box "
                       "where it is defined");
  } catch (const GeometryError& e) {
    args.fail(std::string(e.what()) + (args.has("cells") ? "" : " (give cells=n)"));
  }
  args.charge(static_cast<std::uint64_t>(r.cells + r.search_cells));
  const bool quiet = args.boolean("quiet");
  if (!quiet) {
    std::ostringstream s;
    s << "implicit: " << r.mesh.faces.size() << " triangles, " << r.leaves << " cells, depth " << r.max_level << "\n";
    if (r.mesh.faces.empty()) {
      s << "implicit: warning: '" << function_arg(args, "f").name
        << "' is > 0 everywhere the mesher looked in the box: the solid is empty\n";
    }
    args.err() << s.str();
  }
  if (r.mesh.faces.empty()) return solid_value(Solid::leaf(false, grid));
  // The mesher guarantees a closed, oriented manifold by construction (the same vertex indices
  // once snapped; polygonize_test checks it). Unintersecting: the snapped copy was tested when
  // polygonize accepted its simplified mesh; its marched mesh, unintersecting by construction,
  // can still have faces that meet once snapped where the surface has features near the grid step.
  if (!r.accepted || !snapped) {
    snapped = std::make_shared<PolygonMesh>(snapped_to_grid(r.mesh, grid));
    if (const std::string e = snapped_self_intersection(r.mesh, *snapped, grid); !e.empty()) {
      args.fail("the solid's mesh: " + e + "; " + snapping_advice(options.box, grid));
    }
  }
  // from_mesh is given the mesh before snapping: it snaps it the same way and checks that no
  // triangle turns over against it.
  auto value = std::make_shared<SolidValue>(from_mesh(r.mesh, from_mesh_options(grid)));
  // The snapped triangles bound the solid exactly (from_mesh cuts its tree from them; triangles
  // of zero area after snapping are left out there and add nothing here): volume and area read them.
  value->exact_boundary = std::move(snapped);
  return Value(std::shared_ptr<const Object>(std::move(value)));
}

/// patch(f, corners, depth): the paper's adaptive polygonization of a triangular patch of f = 0
/// (sec. 5.2) as a mesh value.
Value surface_patch(const Arguments& args) {
  const implicit::Expression f = compiled_arg(args, "f");
  if (!args.has("corners")) args.fail("give corners=[P0, P1, P2], three points on f = 0");
  const List& corners = args.list("corners");
  if (corners.size() != 3) args.fail("corners", "corners must be three points [P0, P1, P2]");
  implicit::PatchOptions options;
  for (std::size_t c = 0; c < 3; ++c) {
    const List* xyz = corners[c].list();
    if (!xyz || xyz->size() != 3) args.fail("corners", "corners must be three points [x, y, z]");
    for (int a = 0; a < 3; ++a) {
      const double* v = (*xyz)[std::size_t(a)].get<double>();
      if (!v || !std::isfinite(*v)) args.fail("corners", "corners must be finite numbers");
      options.corners[c][a] = *v;
    }
  }
  options.depth = static_cast<int>(args.integer("depth"));
  if (args.has("tol")) options.tolerance = args.number("tol");
  implicit::PatchResult r;
  try {
    r = implicit::patch(f, options);
  } catch (const implicit::NonFiniteValue& e) {
    args.fail("f",
              "'" + function_arg(args, "f").name + "' (or its gradient) is not finite at " + format_point(e.point()));
  } catch (const InvalidInput& e) {
    args.fail(e.what());
  } catch (const GeometryError& e) {
    args.fail(e.what());
  }
  args.charge(static_cast<std::uint64_t>(r.steps));
  return Value(std::shared_ptr<const Object>(std::make_shared<MeshValue>(std::move(r.mesh))));
}

/// A function parameter of the implicit area (compiled: a user fn only).
Param function_param(std::string name) { return arg(std::move(name)).any("a function fn f(x, y, z) or fn f(p)"); }

Param box_param() { return arg("box").list().optional("[lo, hi]"); }

}  // namespace

void register_implicit(BuiltinTable& table) {
  table.add({.name = "patch",
             .doc = "The adaptive polygonization of the triangular patch of f = 0 with corners P0, P1, P2 on the "
                    "surface (Ihm & Naylor 1990, sec. 5.2): boundary curves traced on the planes through two "
                    "corners and the mean normal, split at the centres of their LAs of order 2^depth, four "
                    "triangles per level, depth 0..8: 4^depth triangles as a mesh value for export. tol is the "
                    "traced curves' chord height (0: 1e-3 of each curve's length).",
             .params = {function_param("f"), arg("corners").list().optional("[P0, P1, P2]"),
                        arg("depth").integer(0, 8).defaults(double(implicit::PatchOptions{}.depth)),
                        arg("tol").positive().optional(format_number(implicit::PatchOptions{}.tolerance))},
             .run = [](const Arguments& args) -> Value { return surface_patch(args); }});
  table.add({.name = "implicit",
             .doc = "The solid f <= 0 inside the box, as a BSP solid for | & -, volume, export. f is a function "
                    "fn f(x, y, z) or fn f(p), compiled once. Its boundary is meshed by an adaptive octree (interval "
                    "bounds prove cells empty or full; small parts are searched for) and marching tetrahedra: "
                    "closed and manifold, about tol from the surface, finer where it bends; the box faces close "
                    "it where the surface leaves the box. tol is at least 4 kernel grid steps (1.2e-4). Prints the "
                    "triangle and cell counts unless quiet=true; an f > 0 in the whole box gives the empty solid "
                    "with a warning; cells bounds the work (an error when it runs out).",
             .params = {function_param("f"), box_param(),
                        arg("tol").positive().defaults(implicit::PolygonizeOptions{}.tolerance),
                        arg("cells").integer(1, kMaxCells).defaults(double(kDefaultCells)),
                        arg("quiet").boolean().defaults(false)},
             .run = [](const Arguments& args) -> Value { return implicit_solid(args); }});
  const std::vector<Param> params = {
      function_param("f"), function_param("g"), box_param(),
      arg("tol").positive().defaults(implicit::TraceOptions{}.tolerance),
      arg("steps").integer(1, kMaxSteps).defaults(double(implicit::TraceOptions{}.max_steps))};
  std::vector<Param> trace_params = params;
  trace_params.push_back(arg("quiet").boolean().defaults(false));
  table.add({.name = "trace",
             .doc = "Every component of the space curve f = g = 0 inside the box, as a list of digitized curves "
                    "(closed loops marked closed; open pieces end on the box), for linearize, points, fit. f and g "
                    "are functions fn f(x, y, z) or fn f(p), compiled once (docs/language.md, \"Implicit "
                    "functions\"). Start points are found without seeds; each chord lies within tol of the "
                    "curve; singular points (crossings) are passed through and reported by trace_info. Prints "
                    "a summary (curves, points, singular points, steps) unless quiet=true, and a warning when "
                    "the step budget runs out.",
             .params = trace_params,
             .run = [](const Arguments& args) -> Value {
               const implicit::TraceResult r = run_trace(args);
               if (!args.boolean("quiet")) print_summary(args, r, static_cast<long>(args.integer("steps")));
               return curves_value(r);
             }});
  table.add({.name = "trace_info",
             .doc = "trace() with everything it found, printing nothing: [curves, singular, steps, "
                    "exhausted], where singular lists [[x, y, z], passes, resolved] per singular point "
                    "(passes: how many traced branches go through it, 0 for an isolated point; resolved: "
                    "false when a branch stopped there), steps the marching steps used and exhausted "
                    "whether the step budget ran out.",
             .params = params,
             .run = [](const Arguments& args) -> Value {
               const implicit::TraceResult r = run_trace(args);
               List singular;
               for (const implicit::SingularPoint& s : r.singular_points) {
                 singular.emplace_back(List{List{s.point.x(), s.point.y(), s.point.z()},
                                            static_cast<double>(s.passes), s.resolved});
               }
               return List{curves_value(r), Value(std::move(singular)), static_cast<double>(r.steps),
                           r.budget_exhausted};
             }});
}

}  // namespace sculpt::language
