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

curves::DigitizedCurve curve_from_points(const Arguments& args, std::size_t i) {
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
             .signature = "curve(\"file\" or points, closed=false)",
             .doc = "A digitized curve: loaded from a file (one point per line, `x y` or `x y z`, "
                    "`#` comments; a relative path is relative to the script's folder), or made from "
                    "a list of [x, y] or [x, y, z] points (all of one kind). closed=true joins the "
                    "last point back to the first.",
             .params = {{"source"}, {"closed", false}},
             .run = [](const Arguments& args) {
               DigitizedCurve curve;
               if (args.value(0).get<std::string>()) {
                 curve = curves::load_curve(args.file_path(0));
               } else if (args.value(0).list()) {
                 curve = curve_from_points(args, 0);
               } else {
                 args.fail_type(0, "a file name or a list of points");
               }
               if (args.has(1)) curve.closed = args.boolean(1);
               return make_curve(std::move(curve));
             }});

  for (curves::AppendixBCurve which : curves::all_appendix_b_curves()) {
    const std::string name = curves::appendix_b_curve_name(which);
    table.add({.name = name,
               .signature = name + "(points=" + std::to_string(curves::paper_point_count(which)) +
                            ", noise=0, seed=1)",
               .doc = "The '" + name + "' test curve of Appendix B sampled at `points` points "
                      "(default: the paper's count), with optional seeded Gaussian noise.",
               .params = {{"points", false}, {"noise", false}, {"seed", false}},
               .run = [which](const Arguments& args) {
                 curves::AppendixBCurveOptions options;
                 if (args.has(0)) options.points = static_cast<int>(args.integer(0, 2, 10'000'000));
                 if (args.has(1)) options.noise = args.number(1);
                 if (args.has(2)) options.seed = static_cast<std::uint64_t>(args.integer(2, 0, 1LL << 53));
                 return make_curve(curves::make_appendix_b_curve(which, options));
               }});
  }

  table.add({.name = "linearize",
             .signature = "linearize(c, m, method=\"optimal\", alpha=0.5, tol=e)",
             .doc = "Piecewise linear approximation of curve c with exactly m segments (optimal, "
                    "i.e. least maximum error, by default), or with tol=e the fewest segments whose "
                    "error is at most e. method: \"optimal\", \"dynamic\", \"length\", \"image\", "
                    "\"init\", \"iter\", \"fast\", \"mincount\", \"center\", \"douglas_peucker\"; "
                    "alpha in [0, 1] weighs chord length against spherical image (init, iter).",
             .params = {{"c"}, {"m", false}, {"method", false}, {"alpha", false}, {"tol", false}},
             .run = [](const Arguments& args) -> Value {
               const auto& c = args.object<CurveValue>(0, "a curve");
               curves::LinearizeOptions options;
               if (args.has(1) == args.has(4)) args.fail("give either m (segments) or tol=, not both or neither");
               if (args.has(1)) options.segments = static_cast<int>(args.integer(1, 1, 1'000'000'000));
               if (args.has(4)) options.tolerance = args.number(4);
               if (args.has(2)) {
                 auto method = method_named(args.string(2));
                 if (!method) args.fail(2, "unknown method \"" + args.string(2) + "\"");
                 options.method = *method;
               }
               if (args.has(3)) options.alpha = args.number(3);
               auto value = std::make_shared<LinearizationValue>();
               value->curve = std::static_pointer_cast<const CurveValue>(
                   *args.value(0).get<std::shared_ptr<const Object>>());
               value->result = curves::linearize(c.curve, options);
               return Value(std::shared_ptr<const Object>(std::move(value)));
             }});

  table.add({.name = "error",
             .signature = "error(p)",
             .doc = "The maximum segment error of linearization p (L-infinity distance of the curve "
                    "points from their segments).",
             .params = {{"p"}},
             .run = [](const Arguments& args) -> Value {
               return args.object<LinearizationValue>(0, "a linearization").result.error;
             }});
  table.add({.name = "indices",
             .signature = "indices(p)",
             .doc = "The indices of the curve points where linearization p's segments start and end "
                    "(for a closed curve the last index, the point count, stands for point 0).",
             .params = {{"p"}},
             .run = [](const Arguments& args) -> Value {
               List out;
               for (int i : args.object<LinearizationValue>(0, "a linearization").result.indices) {
                 out.emplace_back(static_cast<double>(i));
               }
               return out;
             }});
  table.add({.name = "points",
             .signature = "points(x)",
             .doc = "The vertices of linearization x as a list of [x, y, z], or the points of curve x.",
             .params = {{"x"}},
             .run = [](const Arguments& args) -> Value {
               List out;
               if (const auto* c = args.value(0).object<CurveValue>()) {
                 for (const auto& p : c->curve.points) out.push_back(point_list(p));
                 return out;
               }
               const auto& la = args.object<LinearizationValue>(0, "a linearization or a curve");
               for (const auto& p : curves::linearization_points(la.curve->curve, la.result)) out.push_back(point_list(p));
               return out;
             }});
}

}  // namespace sculpt::language
