// Built-ins of the splines area: B-spline curves, fitting without given parameters, degree
// reduction, distances, sampling into digitized curves, and the spline text file (Pottmann,
// Leopoldseder & Hofer 2002, sec. 1-3; Wang, Pottmann & Liu 2006; lib/splines). See docs/splines.md.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bsp/polygon_offset.hpp"
#include "curves/digitized_curve.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"
#include "language/spline_values.hpp"
#include "mesh/mesh_io.hpp"
#include "splines/splines.hpp"

namespace sculpt::language {
namespace {

using splines::BSpline;

/// Largest degree a script may ask for (the basis work grows with the square of the degree).
constexpr long long kMaxDegree = 50;

Value fitted_value(splines::FitResult r) {
  auto v = std::make_shared<SplineValue>(std::move(r.curve));
  v->history = std::move(r.history);
  v->converged = r.converged;
  return Value(std::shared_ptr<const Object>(std::move(v)));
}

const SplineValue& spline_arg(const Arguments& args, std::string_view i) {
  return args.object<SplineValue>(i, "a spline");
}

/// Points given as a digitized curve or as a (non-empty) list of [x, y] / [x, y, z], all of one kind.
curves::DigitizedCurve curve_points_arg(const Arguments& args, std::string_view i, const char* what) {
  if (const auto* c = args.value(i).object<CurveValue>()) return c->curve;
  if (!args.value(i).list()) args.fail_type(i, what);
  curves::DigitizedCurve c = curve_from_points(args, i);
  if (c.points.empty()) args.fail(i, "the list of points is empty");
  return c;
}

/// A point as the script sees it: [x, y] for a 2D spline, [x, y, z] for a 3D one.
Value point_value(const Eigen::Vector3d& p, int dimension) {
  if (dimension == 2) return List{p.x(), p.y()};
  return List{p.x(), p.y(), p.z()};
}

/// The parameter of a spline argument named `name`.
Param spline_param(std::string name) { return arg(std::move(name)).of<SplineValue>("a spline"); }

/// The same curve run the other way: controls reversed, knots mirrored in the domain (open), or
/// for a closed curve with uniform break points the controls reversed alone (its basis functions
/// are translates of one another). Returns null for a closed curve with other break points.
std::optional<BSpline> reversed(const BSpline& s) {
  std::vector<Eigen::Vector3d> controls(s.controls().rbegin(), s.controls().rend());
  const std::vector<double>& k = s.knots();
  if (s.closed()) {
    const double step = (k.back() - k.front()) / double(k.size() - 1);
    for (std::size_t i = 0; i < k.size(); ++i)
      if (std::abs(k[i] - (k.front() + double(i) * step)) > 1e-12 * std::max(1.0, std::abs(k.back())))
        return std::nullopt;
    return BSpline(s.degree(), k, std::move(controls), true, s.dimension());
  }
  std::vector<double> knots(k.size());
  for (std::size_t i = 0; i < k.size(); ++i) knots[i] = k.front() + k.back() - k[k.size() - 1 - i];
  return BSpline(s.degree(), std::move(knots), std::move(controls), false, s.dimension());
}

/// A fitted curve in the order of its data (issue 36: a fit ran from the last point to the
/// first, which turned offset's side): open, it starts nearer the first point than the last;
/// closed, it turns the way the points do (the sign of the polygon's area in its plane, 2D).
BSpline in_data_order(BSpline s, const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 2) return s;
  bool backwards = false;
  if (!s.closed()) {
    const Eigen::Vector3d start = s.point(s.domain().first);
    backwards = (start - points.back()).norm() < (start - points.front()).norm();
  } else if (s.dimension() == 2) {
    const auto area = [](const std::vector<Eigen::Vector3d>& p) {
      double a = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const Eigen::Vector3d& u = p[i];
        const Eigen::Vector3d& v = p[(i + 1) % p.size()];
        a += u.x() * v.y() - v.x() * u.y();
      }
      return a;
    };
    backwards = area(points) * area(splines::sample(s, 256)) < 0;
  }
  if (!backwards) return s;
  std::optional<BSpline> r = reversed(s);
  return r ? std::move(*r) : s;
}

/// The fit's stopping test, relative change of the mean squared distance below the tolerance,
/// cannot hold once that distance is rounding noise: a fit of exact data to 3e-11 said "not
/// converged" (issue 36). A largest distance below 1e-9 of the data's size counts as converged.
bool at_rounding_floor(const splines::FitResult& r, const std::vector<Eigen::Vector3d>& points) {
  if (r.history.empty() || points.empty()) return false;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  return r.history.back().max_distance <= 1e-9 * std::max(box.diagonal().norm(), 1e-300);
}

/// offset(polygon, d, ...): the polygon's offset (bsp/polygon_offset.hpp) as a closed 2D curve (at
/// the polygon's z when its points were [x, y, z] with one z).
Value polygon_offset_value(const Arguments& args) {
  for (const char* name : {"controls", "tol"})
    if (args.has(name))
      args.fail(name, std::string("'") + name + "' applies to the offset of a spline, not of a polygon");
  const PlanePolygon plane = plane_polygon_arg(args, "s", "a spline, or a polygon (a curve or a list of points)",
                                               "the polygon is not in a plane z = constant");
  const std::vector<Eigen::Vector2d>& polygon = plane.points;
  args.charge(polygon.size());
  PolygonOffsetOptions options{.segments = static_cast<int>(args.integer("segments")),
                               .miter_limit = args.number("miter_limit"),
                               .grid = args.grid()};
  const std::string& join = args.string("join");
  if (join == "round")
    options.join = OffsetJoin::Round;
  else if (join == "miter")
    options.join = OffsetJoin::Miter;
  else
    args.fail("join", "join must be \"round\" or \"miter\", not \"" + join + "\"");
  const double d = args.number("d");
  const auto loops = offset_polygon(polygon, d, options);
  if (loops.empty()) args.fail("d", "the inward offset by " + format_number(d) + " makes the polygon vanish");
  if (loops.size() > 1) {
    const auto holes = std::count_if(loops.begin(), loops.end(), [](const auto& l) {
      double a = 0;
      for (std::size_t i = 0; i < l.size(); ++i)
        a += l[i].x() * l[(i + 1) % l.size()].y() - l[(i + 1) % l.size()].x() * l[i].y();
      return a < 0;
    });
    args.fail("d", "the offset by " + format_number(d) + " gives " + std::to_string(loops.size() - std::size_t(holes)) +
                       " polygons and " + std::to_string(holes) + " holes; only a single polygon is supported");
  }
  curves::DigitizedCurve out{.points = {}, .dimension = 2, .closed = true, .name = "offset"};
  for (const Eigen::Vector2d& p : loops.front()) out.points.emplace_back(p.x(), p.y(), plane.z);
  if (plane.dimension == 3) out.dimension = 3;
  return Value(std::shared_ptr<const Object>(std::make_shared<CurveValue>(std::move(out))));
}

}  // namespace

std::string SplineValue::repr() const {
  const auto [t0, t1] = spline.domain();
  std::string s = "<spline: degree " + std::to_string(spline.degree()) + ", " + (spline.closed() ? "closed" : "open") +
                  ", " + std::to_string(spline.dimension()) + "D, " + std::to_string(spline.control_count()) +
                  " controls, domain [" + format_number(t0) + ", " + format_number(t1) + "]";
  if (!history.empty())
    s += ", fitted in " + std::to_string(history.size() - 1) + (history.size() == 2 ? " step" : " steps") +
         (converged ? "" : " (not converged)");
  return s + ">";
}

void register_splines(BuiltinTable& table) {
  table.add({.name = "bspline",
             .doc = "A B-spline curve from a list of [x, y] (a 2D spline) or [x, y, z] control points. Open: "
                    "clamped (through the first and last control point) with uniform knots on [0, 1], or the "
                    "given `knots` (n + degree + 1 non-decreasing values). closed=true: periodic, the control "
                    "polygon closes; uniform break points 0, 1, ..., n or the given n + 1 break points.",
             .params = {arg("controls").list(), arg("degree").integer(1, kMaxDegree).defaults(3.0),
                        arg("closed").boolean().defaults(false), arg("knots").list().optional("uniform")},
             .run = [](const Arguments& args) -> Value {
               const curves::DigitizedCurve controls = curve_points_arg(args, "controls", "a list of points");
               const int degree = static_cast<int>(args.integer("degree"));
               const bool closed = args.boolean("closed");
               if (!args.has("knots")) {
                 return spline_value(closed ? BSpline::periodic(degree, controls.points, controls.dimension)
                                            : BSpline::clamped(degree, controls.points, controls.dimension));
               }
               std::vector<double> knots;
               for (const Value& k : args.list("knots")) {
                 const double* x = k.get<double>();
                 if (!x) args.fail("knots", "knots must be numbers");
                 knots.push_back(*x);
               }
               return spline_value(BSpline(degree, std::move(knots), controls.points, closed, controls.dimension));
             }});
  table.add({.name = "bezier",
             .doc = "The Bezier curve of degree n - 1 over [0, 1] with the n control points [x, y] or [x, y, z].",
             .params = {arg("controls").list()},
             .run = [](const Arguments& args) -> Value {
               const curves::DigitizedCurve controls = curve_points_arg(args, "controls", "a list of points");
               return spline_value(BSpline::bezier(controls.points, controls.dimension));
             }});

  table.add(
      {.name = "fit",
       .doc = "A B-spline with `controls` control points fitted to curve c (its points) or a list of points, "
              "without given parameters: foot points, a local quadratic model of each squared distance, "
              "a linear solve, repeated (Wang, Pottmann & Liu 2006). method: \"sdm\" (curvature-based), "
              "\"pdm\" (point distance) or \"tdm\" (tangent distance); a closed \"sdm\" fit switches to Newton's "
              "model near the optimum (docs/splines.md). closed: true, false, or by default "
              "the curve's own flag (a list is open). smoothing: the weight of the bending term in the "
              "first step (halved each step). start: a spline to start from (default: an ellipse or a "
              "chord along the data's main axis); controls then defaults to its count. fit_history() "
              "gives the convergence figures.",
       .params = {arg("c").any("a curve or a list of points"), arg("controls").integer(1, 1'000'000).optional("n"),
                  arg("degree").integer(1, kMaxDegree).defaults(double(splines::FitOptions{}.degree)),
                  arg("closed").any("true, false or \"auto\"").optional("auto"), arg("method").string().defaults("sdm"),
                  arg("iterations").integer(0, 100'000).defaults(double(splines::FitOptions{}.iterations)),
                  arg("smoothing").at_least(0).defaults(splines::FitOptions{}.smoothing),
                  spline_param("start").optional("s")},
       .run = [](const Arguments& args) -> Value {
         const curves::DigitizedCurve data = curve_points_arg(args, "c", "a curve or a list of points");
         splines::FitOptions options;
         options.dimension = data.dimension;
         options.closed = data.closed;
         if (args.has("start")) {
           options.start = spline_arg(args, "start").spline;
           options.closed = options.start->closed();
         }
         if (args.has("controls")) options.controls = static_cast<int>(args.integer("controls"));
         if (!args.has("controls") && !args.has("start"))
           args.fail("give controls=n (the number of control points) or start=s");
         options.degree = static_cast<int>(args.integer("degree"));
         if (args.has("closed")) {
           if (const std::string* mode = args.value("closed").get<std::string>()) {
             if (*mode != "auto") args.fail("closed", "closed must be true, false or \"auto\"");
           } else {
             options.closed = args.boolean("closed");
           }
         }
         options.method = splines::method_from_name(args.string("method"));
         options.iterations = static_cast<int>(args.integer("iterations"));
         options.smoothing = args.number("smoothing");
         // Each step finds every data point's foot point on every span.
         args.charge(data.points.size() * static_cast<std::uint64_t>(options.iterations + 1));
         splines::FitResult r = splines::fit_curve(data.points, options);
         if (!args.has("start")) r.curve = in_data_order(std::move(r.curve), data.points);
         r.converged = r.converged || at_rounding_floor(r, data.points);
         return fitted_value(std::move(r));
       }});
  table.add({.name = "fit_history",
             .doc = "The convergence of the fit (or degree reduction) that made spline s: one row "
                    "[objective, max, rms] per step, row 0 for the start curve. For fit, objective is the mean "
                    "squared distance of the data to the curve, max and rms the largest and root-mean-square "
                    "distance (exact foot points); for reduce_degree the same figures for the samples of each "
                    "curve against the other. len(fit_history(s)) - 1 is the number of steps taken. A closed fit of "
                    "many points (at least 4000 and 64 per control point) takes its first steps on a subset: "
                    "those rows describe the subset, the later ones all points.",
             .params = {spline_param("s")},
             .run = [](const Arguments& args) -> Value {
               const SplineValue& s = spline_arg(args, "s");
               if (s.history.empty()) args.fail("s", "this spline was not made by fit or reduce_degree");
               List rows;
               for (const splines::FitIteration& row : s.history)
                 rows.emplace_back(List{row.objective, row.max_distance, row.rms_distance});
               return rows;
             }});

  table.add({.name = "sample",
             .doc = "A digitized curve of n points of spline s at uniform parameters (open: from its start to "
                    "its end; closed: once around, a closed curve), for linearize, revolve, points and fit.",
             .params = {spline_param("s"), arg("n").integer(1, 1'000'000)},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, "s").spline;
               const int n = static_cast<int>(args.integer("n"));
               args.charge(static_cast<std::uint64_t>(n));
               curves::DigitizedCurve curve;
               curve.points = splines::sample(s, n);
               curve.dimension = s.dimension();
               curve.closed = s.closed();
               curve.name = "spline sample";
               return Value(std::shared_ptr<const Object>(std::make_shared<CurveValue>(std::move(curve))));
             }});
  table.add({.name = "reduce_degree",
             .doc = "Bezier curve b reduced to degree k < degree(b) with its end points kept. method \"active\": "
                    "the active-curve method (Pottmann, Leopoldseder & Hofer 2002, sec. 3.1), the curves come "
                    "close as point sets, and fit_history() gives the convergence; \"l2\": Eck's constrained "
                    "L2 reduction (the difference as functions of the parameter), for comparison.",
             .params = {spline_param("b"), arg("k").integer(0, kMaxDegree), arg("method").string().defaults("active")},
             .run = [](const Arguments& args) -> Value {
               const BSpline& b = spline_arg(args, "b").spline;
               const int k = static_cast<int>(args.integer("k"));
               const std::string& method = args.string("method");
               if (method == "l2") return spline_value(splines::reduce_degree_l2(b, k));
               if (method != "active") args.fail("method", "method must be \"active\" or \"l2\"");
               return fitted_value(splines::reduce_degree(b, k));
             }});
  table.add({.name = "distance",
             .doc = "[max, rms]: the largest and the root-mean-square distance from the points of curve c (or a "
                    "list of points) to spline s, with exact foot points.",
             .params = {spline_param("s"), arg("c").any("a curve or a list of points")},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, "s").spline;
               const curves::DigitizedCurve data = curve_points_arg(args, "c", "a curve or a list of points");
               const splines::DistanceSummary d = splines::distance(s, data.points);
               return List{d.max, d.rms};
             }});
  table.add({.name = "control_points",
             .doc = "The control points of spline s: [x, y] each for a 2D spline, [x, y, z] for a 3D one "
                    "(a closed spline's are not repeated).",
             .params = {spline_param("s")},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, "s").spline;
               List out;
               for (const auto& p : s.controls()) out.push_back(point_value(p, s.dimension()));
               return out;
             }});
  table.add({.name = "knots",
             .doc = "The knots of spline s: open, n + degree + 1 values; closed, the n + 1 break points of one "
                    "period (the form bspline(..., knots=) takes).",
             .params = {spline_param("s")},
             .run = [](const Arguments& args) -> Value {
               List out;
               for (double k : spline_arg(args, "s").spline.knots()) out.emplace_back(k);
               return out;
             }});
  table.add({.name = "degree",
             .doc = "The degree of spline s.",
             .params = {spline_param("s")},
             .run = [](const Arguments& args) -> Value {
               return static_cast<double>(spline_arg(args, "s").spline.degree());
             }});

  table.add({.name = "save_spline",
             .doc = "Writes spline s in the text form of docs/splines.md (degree, closed, dimension, knots, "
                    "controls; full precision). The file is replaced atomically; folders are created.",
             .params = {spline_param("s"), arg("file").string().shown_as("\"file\"")},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, "s").spline;
               const std::filesystem::path path = args.file_path("file");
               if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
               write_file_atomically(path, splines::format_spline(s));
               return {};
             }});
  table.add({.name = "load_spline",
             .doc = "Reads a spline in the text form save_spline writes (hand-written files are fine: `#` comments, "
                    "knots may be left out for uniform ones). Errors name the file, line and column.",
             .params = {arg("file").string().shown_as("\"file\"")},
             .run = [](const Arguments& args) -> Value {
               return spline_value(splines::load_spline(args.input_path("file")));
             }});

  table.add({.name = "offset",
             .signature = "offset(s, d, controls=auto, tol=1e-3) or offset(polygon, d, join=\"round\", segments=32, "
                          "miter_limit=2)",
             .doc = "The offset of planar spline s at signed distance d (positive: to the right of the direction "
                    "of travel, outwards for a counter-clockwise closed curve), approximated by an active curve "
                    "(Pottmann, Leopoldseder & Hofer 2002, sec. 3.2). Where the offset crosses the medial axis "
                    "its swallowtail is trimmed and the result gets a sharp corner (a knot of multiplicity = "
                    "degree). controls: the control-point count, by default the fewest (up to 64) within tol of "
                    "the exact offset. An offset that would vanish or split into several loops is an error. "
                    "Given a polygon instead (a curve or a list of [x, y] points, simple, either orientation), "
                    "the polygon offset outwards by d > 0 or inwards by d < 0 (the points within d of it, or "
                    "farther than |d| from its outside), as a closed 2D curve: join=\"round\" rounds opening corners "
                    "with arcs of `segments` edges per "
                    "turn, join=\"miter\" extends the edges until they meet, cut off at miter_limit * |d| from "
                    "the vertex. Decided exactly; a result that vanishes, splits or has holes is an error.",
             .params = {arg("s").any("a spline, or a polygon (a curve or a list of points)"), arg("d").finite_number(),
                        arg("controls").integer(1, 10'000).optional("auto"),
                        arg("tol").positive().defaults(splines::OffsetOptions{}.tolerance),
                        arg("join").string().defaults("round"),
                        arg("segments").integer(3, 100000).defaults(double(PolygonOffsetOptions{}.segments)),
                        arg("miter_limit").at_least(1).defaults(PolygonOffsetOptions{}.miter_limit)},
             .run = [](const Arguments& args) -> Value {
               if (const auto* sv = args.value("s").object<SplineValue>()) {
                 for (const char* name : {"join", "segments", "miter_limit"})
                   if (args.has(name))
                     args.fail(name, std::string("'") + name + "' applies to the offset of a polygon, not of a spline");
                 const BSpline& s = sv->spline;
                 const double d = args.number("d");
                 splines::OffsetOptions options;
                 if (args.has("controls")) options.controls = static_cast<int>(args.integer("controls"));
                 options.tolerance = args.number("tol");
                 splines::OffsetResult r = splines::offset_curve(s, d, options);
                 return fitted_value({.curve = std::move(r.curve),
                                      .history = std::move(r.history),
                                      .iterations = int(r.history.size()) - 1,
                                      .converged = true});
               }
               return polygon_offset_value(args);
             }});
}

}  // namespace sculpt::language
