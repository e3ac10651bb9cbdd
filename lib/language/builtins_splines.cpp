// Built-ins of the splines area: B-spline curves, fitting without given parameters, degree
// reduction, distances, sampling into digitized curves, and the spline text file (Pottmann,
// Leopoldseder & Hofer 2002, sec. 1-3; Wang, Pottmann & Liu 2006; lib/splines). See docs/splines.md.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

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

Value spline_value(BSpline s) {
  return Value(std::shared_ptr<const Object>(std::make_shared<SplineValue>(std::move(s))));
}

Value fitted_value(splines::FitResult r) {
  auto v = std::make_shared<SplineValue>(std::move(r.curve));
  v->history = std::move(r.history);
  v->converged = r.converged;
  return Value(std::shared_ptr<const Object>(std::move(v)));
}

const SplineValue& spline_arg(const Arguments& args, std::size_t i) {
  return args.object<SplineValue>(i, "a spline");
}

/// Points given as a digitized curve or as a (non-empty) list of [x, y] / [x, y, z], all of one kind.
curves::DigitizedCurve points_arg(const Arguments& args, std::size_t i, const char* what) {
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

int degree_arg(const Arguments& args, std::size_t i) { return static_cast<int>(args.integer(i, 1, kMaxDegree)); }

double non_negative(const Arguments& args, std::size_t i, const char* name) {
  const double x = args.number(i);
  if (!(x >= 0) || !std::isfinite(x)) args.fail(i, std::string("argument '") + name + "' must be a finite number >= 0");
  return x;
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
             .signature = "bspline(controls, degree=3, closed=false, knots=uniform)",
             .doc = "A B-spline curve from a list of [x, y] (a 2D spline) or [x, y, z] control points. Open: "
                    "clamped (through the first and last control point) with uniform knots on [0, 1], or the "
                    "given `knots` (n + degree + 1 non-decreasing values). closed=true: periodic, the control "
                    "polygon closes; uniform break points 0, 1, ..., n or the given n + 1 break points.",
             .params = {{"controls"}, {"degree", false}, {"closed", false}, {"knots", false}},
             .run = [](const Arguments& args) -> Value {
               const curves::DigitizedCurve controls = points_arg(args, 0, "a list of points");
               const int degree = args.has(1) ? degree_arg(args, 1) : 3;
               const bool closed = args.has(2) && args.boolean(2);
               if (!args.has(3)) {
                 return spline_value(closed ? BSpline::periodic(degree, controls.points, controls.dimension)
                                            : BSpline::clamped(degree, controls.points, controls.dimension));
               }
               std::vector<double> knots;
               for (const Value& k : args.list(3)) {
                 const double* x = k.get<double>();
                 if (!x) args.fail(3, "knots must be numbers");
                 knots.push_back(*x);
               }
               return spline_value(BSpline(degree, std::move(knots), controls.points, closed, controls.dimension));
             }});
  table.add({.name = "bezier",
             .signature = "bezier(controls)",
             .doc = "The Bezier curve of degree n - 1 over [0, 1] with the n control points [x, y] or [x, y, z].",
             .params = {{"controls"}},
             .run = [](const Arguments& args) -> Value {
               const curves::DigitizedCurve controls = points_arg(args, 0, "a list of points");
               return spline_value(BSpline::bezier(controls.points, controls.dimension));
             }});

  table.add({.name = "fit",
             .signature = "fit(c, controls=n, degree=3, closed=auto, method=\"sdm\", iterations=50, smoothing=0.1, start=s)",
             .doc = "A B-spline with `controls` control points fitted to curve c (its points) or a list of points, "
                    "without given parameters: foot points, a local quadratic model of each squared distance, "
                    "a linear solve, repeated (Wang, Pottmann & Liu 2006). method: \"sdm\" (curvature-based), "
                    "\"pdm\" (point distance) or \"tdm\" (tangent distance); a closed \"sdm\" fit switches to Newton's "
                    "model near the optimum (docs/splines.md). closed: true, false, or by default "
                    "the curve's own flag (a list is open). smoothing: the weight of the bending term in the "
                    "first step (halved each step). start: a spline to start from (default: an ellipse or a "
                    "chord along the data's main axis); controls then defaults to its count. fit_history() "
                    "gives the convergence figures.",
             .params = {{"c"},
                        {"controls", false},
                        {"degree", false},
                        {"closed", false},
                        {"method", false},
                        {"iterations", false},
                        {"smoothing", false},
                        {"start", false}},
             .run = [](const Arguments& args) -> Value {
               const curves::DigitizedCurve data = points_arg(args, 0, "a curve or a list of points");
               splines::FitOptions options;
               options.dimension = data.dimension;
               options.closed = data.closed;
               if (args.has(7)) {
                 options.start = spline_arg(args, 7).spline;
                 options.closed = options.start->closed();
               }
               if (args.has(1)) options.controls = static_cast<int>(args.integer(1, 1, 1'000'000));
               if (!args.has(1) && !args.has(7)) args.fail("give controls=n (the number of control points) or start=s");
               if (args.has(2)) options.degree = degree_arg(args, 2);
               if (args.has(3)) {
                 if (const std::string* mode = args.value(3).get<std::string>()) {
                   if (*mode != "auto") args.fail(3, "closed must be true, false or \"auto\"");
                 } else {
                   options.closed = args.boolean(3);
                 }
               }
               if (args.has(4)) options.method = splines::method_from_name(args.string(4));
               if (args.has(5)) options.iterations = static_cast<int>(args.integer(5, 0, 100'000));
               if (args.has(6)) options.smoothing = non_negative(args, 6, "smoothing");
               // Each step finds every data point's foot point on every span.
               args.charge(data.points.size() * static_cast<std::uint64_t>(options.iterations + 1));
               return fitted_value(splines::fit_curve(data.points, options));
             }});
  table.add({.name = "fit_history",
             .signature = "fit_history(s)",
             .doc = "The convergence of the fit (or degree reduction) that made spline s: one row "
                    "[objective, max, rms] per step, row 0 for the start curve. For fit, objective is the mean "
                    "squared distance of the data to the curve, max and rms the largest and root-mean-square "
                    "distance (exact foot points); for reduce_degree the same figures for the samples of each "
                    "curve against the other. len(fit_history(s)) - 1 is the number of steps taken. A closed fit of "
                    "many points (at least 4000 and 64 per control point) takes its first steps on a subset: "
                    "those rows describe the subset, the later ones all points.",
             .params = {{"s"}},
             .run = [](const Arguments& args) -> Value {
               const SplineValue& s = spline_arg(args, 0);
               if (s.history.empty()) args.fail(0, "this spline was not made by fit or reduce_degree");
               List rows;
               for (const splines::FitIteration& row : s.history)
                 rows.emplace_back(List{row.objective, row.max_distance, row.rms_distance});
               return rows;
             }});

  table.add({.name = "sample",
             .signature = "sample(s, n)",
             .doc = "A digitized curve of n points of spline s at uniform parameters (open: from its start to "
                    "its end; closed: once around, a closed curve), for linearize, revolve, points and fit.",
             .params = {{"s"}, {"n"}},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, 0).spline;
               const int n = static_cast<int>(args.integer(1, 1, 1'000'000));
               args.charge(static_cast<std::uint64_t>(n));
               curves::DigitizedCurve curve;
               curve.points = splines::sample(s, n);
               curve.dimension = s.dimension();
               curve.closed = s.closed();
               curve.name = "spline sample";
               return Value(std::shared_ptr<const Object>(std::make_shared<CurveValue>(std::move(curve))));
             }});
  table.add({.name = "reduce_degree",
             .signature = "reduce_degree(b, k, method=\"active\")",
             .doc = "Bezier curve b reduced to degree k < degree(b) with its end points kept. method \"active\": "
                    "the active-curve method (Pottmann, Leopoldseder & Hofer 2002, sec. 3.1), the curves come "
                    "close as point sets, and fit_history() gives the convergence; \"l2\": Eck's constrained "
                    "L2 reduction (the difference as functions of the parameter), for comparison.",
             .params = {{"b"}, {"k"}, {"method", false}},
             .run = [](const Arguments& args) -> Value {
               const BSpline& b = spline_arg(args, 0).spline;
               const int k = static_cast<int>(args.integer(1, 0, kMaxDegree));
               const std::string method = args.has(2) ? args.string(2) : "active";
               if (method == "l2") return spline_value(splines::reduce_degree_l2(b, k));
               if (method != "active") args.fail(2, "method must be \"active\" or \"l2\"");
               return fitted_value(splines::reduce_degree(b, k));
             }});
  table.add({.name = "distance",
             .signature = "distance(s, c)",
             .doc = "[max, rms]: the largest and the root-mean-square distance from the points of curve c (or a "
                    "list of points) to spline s, with exact foot points.",
             .params = {{"s"}, {"c"}},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, 0).spline;
               const curves::DigitizedCurve data = points_arg(args, 1, "a curve or a list of points");
               const splines::DistanceSummary d = splines::distance(s, data.points);
               return List{d.max, d.rms};
             }});
  table.add({.name = "control_points",
             .signature = "control_points(s)",
             .doc = "The control points of spline s: [x, y] each for a 2D spline, [x, y, z] for a 3D one "
                    "(a closed spline's are not repeated).",
             .params = {{"s"}},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, 0).spline;
               List out;
               for (const auto& p : s.controls()) out.push_back(point_value(p, s.dimension()));
               return out;
             }});
  table.add({.name = "knots",
             .signature = "knots(s)",
             .doc = "The knots of spline s: open, n + degree + 1 values; closed, the n + 1 break points of one "
                    "period (the form bspline(..., knots=) takes).",
             .params = {{"s"}},
             .run = [](const Arguments& args) -> Value {
               List out;
               for (double k : spline_arg(args, 0).spline.knots()) out.emplace_back(k);
               return out;
             }});
  table.add({.name = "degree",
             .signature = "degree(s)",
             .doc = "The degree of spline s.",
             .params = {{"s"}},
             .run = [](const Arguments& args) -> Value { return static_cast<double>(spline_arg(args, 0).spline.degree()); }});

  table.add({.name = "save_spline",
             .signature = "save_spline(s, \"file\")",
             .doc = "Writes spline s in the text form of docs/splines.md (degree, closed, dimension, knots, "
                    "controls; full precision). The file is replaced atomically; folders are created.",
             .params = {{"s"}, {"file"}},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, 0).spline;
               const std::filesystem::path path = args.file_path(1);
               if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
               write_file_atomically(path, splines::format_spline(s));
               return {};
             }});
  table.add({.name = "load_spline",
             .signature = "load_spline(\"file\")",
             .doc = "Reads a spline in the text form save_spline writes (hand-written files are fine: `#` comments, "
                    "knots may be left out for uniform ones). Errors name the file, line and column.",
             .params = {{"file"}},
             .run = [](const Arguments& args) -> Value { return spline_value(splines::load_spline(args.file_path(0))); }});

  table.add({.name = "offset",
             .signature = "offset(s, d, controls=auto, tol=1e-3)",
             .doc = "The offset of planar spline s at signed distance d (positive: to the right of the direction "
                    "of travel, outwards for a counter-clockwise closed curve), approximated by an active curve "
                    "(Pottmann, Leopoldseder & Hofer 2002, sec. 3.2). Where the offset crosses the medial axis "
                    "its swallowtail is trimmed and the result gets a sharp corner (a knot of multiplicity = "
                    "degree). controls: the control-point count, by default the fewest (up to 64) within tol of "
                    "the exact offset. An offset that would vanish or split into several loops is an error.",
             .params = {{"s"}, {"d"}, {"controls", false}, {"tol", false}},
             .run = [](const Arguments& args) -> Value {
               const BSpline& s = spline_arg(args, 0).spline;
               const double d = args.number(1);
               splines::OffsetOptions options;
               if (args.has(2)) options.controls = static_cast<int>(args.integer(2, 1, 10'000));
               if (args.has(3)) {
                 options.tolerance = non_negative(args, 3, "tol");
                 if (!(options.tolerance > 0)) args.fail(3, "argument 'tol' must be > 0");
               }
               splines::OffsetResult r = splines::offset_curve(s, d, options);
               return fitted_value({.curve = std::move(r.curve), .history = std::move(r.history),
                                    .iterations = int(r.history.size()) - 1, .converged = true});
             }});
}

}  // namespace sculpt::language
