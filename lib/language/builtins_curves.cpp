// Built-ins of the curves area: digitized curves (files and the Appendix-B test curves) and
// their piecewise linear approximation (Ihm & Naylor 1990, sections 2-4; lib/curves).
#include <algorithm>
#include <cctype>
#include <cmath>

#include "curves/digitized_curve.hpp"
#include "curves/linearize.hpp"
#include "curves/appendix_b_curves.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"

namespace sculpt::language {
namespace {

using curves::DigitizedCurve;

Value make_curve(DigitizedCurve curve) {
  return Value(std::shared_ptr<const Object>(std::make_shared<CurveValue>(std::move(curve))));
}

Value point_list(const Eigen::Vector3d& p) { return List{p.x(), p.y(), p.z()}; }

/// "douglas_peucker" and "Douglas-Peucker" both name the method "douglas-peucker".
std::optional<curves::Method> method_named(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return curves::method_from_name(name);
}

}  // namespace

curves::DigitizedCurve curve_from_points(const Arguments& args, std::string_view i) {
  DigitizedCurve curve;
  curve.name = "list";
  const List& items = args.list(i);
  curve.dimension = items.empty() ? 3 : 0;
  for (const Value& item : items) {
    const List* xyz = item.list();
    const std::size_t k = xyz ? xyz->size() : 0;
    bool numbers = k == 2 || k == 3;
    for (std::size_t a = 0; numbers && a < k; ++a) {
      const double* x = (*xyz)[a].get<double>();
      numbers = x && std::isfinite(*x);
    }
    if (!numbers) args.fail(i, "point " + std::to_string(curve.points.size() + 1) +
                                   " must be [x, y] or [x, y, z] with finite numbers");
    if (curve.dimension != 0 && curve.dimension != int(k))
      args.fail(i, "point " + std::to_string(curve.points.size() + 1) + " has " + std::to_string(k) +
                       " coordinates, the first had " + std::to_string(curve.dimension) +
                       " (all points must be 2D or all 3D)");
    curve.dimension = int(k);
    curve.points.emplace_back(*(*xyz)[0].get<double>(), *(*xyz)[1].get<double>(), k == 3 ? *(*xyz)[2].get<double>() : 0.0);
  }
  args.charge(curve.points.size());
  return curve;
}

PlanePolygon plane_polygon_arg(const Arguments& args, std::string_view name, const std::string& what,
                               const std::string& not_plane) {
  curves::DigitizedCurve c;
  if (const auto* cv = args.value(name).object<CurveValue>())
    c = cv->curve;
  else if (args.value(name).list())
    c = curve_from_points(args, name);
  else
    args.fail_type(name, what);
  PlanePolygon polygon{.points = {}, .z = c.points.empty() ? 0.0 : c.points.front().z(), .dimension = c.dimension};
  for (const Eigen::Vector3d& p : c.points) {
    if (p.z() != polygon.z) args.fail(name, not_plane);
    polygon.points.emplace_back(p.x(), p.y());
  }
  return polygon;
}

std::string CurveValue::repr() const {
  return "<curve " + (curve.name.empty() ? std::string() : curve.name + ": ") +
         std::to_string(curve.points.size()) + " points, " + std::to_string(curve.dimension) + "D" +
         (curve.closed ? ", closed" : "") + ">";
}

std::string LinearizationValue::repr() const {
  return "<linearization: " + std::to_string(result.segments()) + " segments, error " +
         format_number(result.error) + ">";
}

void register_curves(BuiltinTable& table) {
  table.add({.name = "curve",
             .doc = "A digitized curve: loaded from a file (one point per line, `x y` or `x y z`, "
                    "`#` comments; a relative path is relative to the script's folder), or made from "
                    "a list of [x, y] or [x, y, z] points (all of one kind). closed=true joins the "
                    "last point back to the first.",
             .params = {arg("source").any("a file name or a list of points").shown_as("\"file\" or points"),
                        arg("closed").boolean().defaults(false)},
             .run = [](const Arguments& args) {
               DigitizedCurve curve;
               if (args.value("source").get<std::string>()) {
                 curve = curves::load_curve(args.input_path("source"));
               } else if (args.value("source").list()) {
                 curve = curve_from_points(args, "source");
               } else {
                 args.fail_type("source", "a file name or a list of points");
               }
               if (args.has("closed")) curve.closed = args.boolean("closed");
               return make_curve(std::move(curve));
             }});

  for (curves::AppendixBCurve which : curves::all_appendix_b_curves()) {
    const std::string name = curves::appendix_b_curve_name(which);
    table.add({.name = name,
               .doc = "The '" + name +
                      "' test curve of Appendix B sampled at `points` points "
                      "(default: the paper's count), with optional seeded Gaussian noise.",
               .params = {arg("points").integer(2, 10'000'000).defaults(double(curves::paper_point_count(which))),
                          arg("noise").number().defaults(curves::AppendixBCurveOptions{}.noise),
                          arg("seed").integer(0, 0x1p53).defaults(double(curves::AppendixBCurveOptions{}.seed))},
               .run = [which](const Arguments& args) {
                 curves::AppendixBCurveOptions options;
                 options.points = static_cast<int>(args.integer("points"));
                 options.noise = args.number("noise");
                 options.seed = static_cast<std::uint64_t>(args.integer("seed"));
                 return make_curve(curves::make_appendix_b_curve(which, options));
               }});
  }

  table.add({.name = "linearize",
             .doc = "Piecewise linear approximation of curve c with exactly m segments (optimal, "
                    "i.e. least maximum error, by default), or with tol=e the fewest segments whose "
                    "error is at most e. method: \"optimal\", \"dynamic\", \"length\", \"image\", "
                    "\"init\", \"iter\", \"fast\", \"mincount\", \"center\", \"douglas_peucker\"; "
                    "alpha in [0, 1] weighs chord length against spherical image (init, iter).",
             .params = {arg("c").of<CurveValue>("a curve"), arg("m").integer(1, 1'000'000'000).optional(),
                        arg("method").string().optional("\"optimal\""),
                        arg("alpha").between(0, 1).defaults(curves::LinearizeOptions{}.alpha),
                        arg("tol").number().optional("e")},
             .run = [](const Arguments& args) -> Value {
               const auto& c = args.object<CurveValue>("c");
               curves::LinearizeOptions options;
               if (args.has("m") == args.has("tol")) args.fail("give either m (segments) or tol=, not both or neither");
               if (args.has("m")) options.segments = static_cast<int>(args.integer("m"));
               if (args.has("tol")) options.tolerance = args.number("tol");
               if (args.has("method")) {
                 auto method = method_named(args.string("method"));
                 if (!method) args.fail("method", "unknown method \"" + args.string("method") + "\"");
                 options.method = *method;
               }
               options.alpha = args.number("alpha");
               auto value = std::make_shared<LinearizationValue>();
               value->curve =
                   std::static_pointer_cast<const CurveValue>(*args.value("c").get<std::shared_ptr<const Object>>());
               value->result = curves::linearize(c.curve, options);
               return Value(std::shared_ptr<const Object>(std::move(value)));
             }});

  table.add({.name = "error",
             .doc = "The maximum segment error of linearization p (L-infinity distance of the curve "
                    "points from their segments).",
             .params = {arg("p").of<LinearizationValue>("a linearization")},
             .run = [](const Arguments& args) -> Value { return args.object<LinearizationValue>("p").result.error; }});
  table.add({.name = "indices",
             .doc = "The indices of the curve points where linearization p's segments start and end "
                    "(for a closed curve the last index, the point count, stands for point 0).",
             .params = {arg("p").of<LinearizationValue>("a linearization")},
             .run = [](const Arguments& args) -> Value {
               List out;
               for (int i : args.object<LinearizationValue>("p").result.indices) {
                 out.emplace_back(static_cast<double>(i));
               }
               return out;
             }});
  table.add({.name = "points",
             .doc = "The vertices of linearization x as a list of [x, y, z], or the points of curve x.",
             .params = {arg("x").any("a linearization or a curve")},
             .run = [](const Arguments& args) -> Value {
               List out;
               if (const auto* c = args.value("x").object<CurveValue>()) {
                 for (const auto& p : c->curve.points) out.push_back(point_list(p));
                 return out;
               }
               const auto& la = args.object<LinearizationValue>("x");
               for (const auto& p : curves::linearization_points(la.curve->curve, la.result))
                 out.push_back(point_list(p));
               return out;
             }});
}

}  // namespace sculpt::language
