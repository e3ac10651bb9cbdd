// Built-ins of the revolution area: convex paths, solids of revolution as nearly balanced BSP
// trees, and the profile models of Figure 5 (Ihm & Naylor 1990, sec. 6; lib/revolution/revolve.hpp,
// lib/curves/profiles.hpp). See docs/revolution.md.
#include <cmath>
#include <string>

#include "revolution/revolve.hpp"
#include "curves/linearization.hpp"
#include "curves/profiles.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"
#include "language/solid_values.hpp"

namespace sculpt::language {
namespace {

/// A convex path of revolution (type "path").
struct PathValue final : Object {
  explicit PathValue(ConvexPath p) : path(std::move(p)) {}
  ConvexPath path;
  [[nodiscard]] std::string type_name() const override { return "path"; }
  [[nodiscard]] std::string repr() const override {
    return "<path: convex polygon of " + std::to_string(path.edges()) + " edges>";
  }
};

Value path_value(ConvexPath p) { return Value(std::shared_ptr<const Object>(std::make_shared<PathValue>(std::move(p)))); }

/// A path's edge count parameter.
Param edges_param(std::string name) { return arg(std::move(name)).integer(3, 100000); }
int edge_count(const Arguments& args, std::string_view i) { return static_cast<int>(args.integer(i, 3, 100000)); }

/// A list of [x, y] (or [x, y, z], z ignored) pairs.
std::vector<Eigen::Vector2d> point_pairs(const Arguments& args, std::string_view i, const char* what) {
  std::vector<Eigen::Vector2d> out;
  for (const Value& item : args.list(i)) {
    const List* xy = item.list();
    if (!xy || xy->size() < 2 || xy->size() > 3 || !(*xy)[0].get<double>() || !(*xy)[1].get<double>())
      args.fail(i, std::string(what) + " must be a list of [x, y] number pairs");
    out.emplace_back(*(*xy)[0].get<double>(), *(*xy)[1].get<double>());
  }
  return out;
}

/// The profile polyline of a curve (its points), a linearization (its vertices) or a list of [r, z].
/// `closed` is set for a closed curve.
std::vector<Eigen::Vector2d> profile_arg(const Arguments& args, std::string_view i, bool& closed) {
  if (const auto* c = args.value(i).object<CurveValue>()) {
    closed = closed || c->curve.closed;
    return curves::planar_points(c->curve.points);
  }
  if (const auto* la = args.value(i).object<LinearizationValue>())
    return curves::planar_points(curves::linearization_points(la->curve->curve, la->result));
  if (args.value(i).list()) return point_pairs(args, i, "a profile");
  args.fail_type(i, "a curve, a linearization or a list of [r, z] points");
}

}  // namespace

void register_revolution(BuiltinTable& table) {
  table.add({.name = "circle",
             .signature = "circle(n) or circle(r, n)",
             .doc = "Path of revolution: the regular n-gon inscribed in the circle of radius r "
                    "(default 1) around the z axis, its first vertex on +x.",
             .params = {arg("a").number(), arg("b").number().optional()},
             .run = [](const Arguments& args) {
               if (!args.has("b")) return path_value(circular_path(edge_count(args, "a")));
               return path_value(circular_path(edge_count(args, "b"), args.number("a")));
             }});
  table.add({.name = "ellipse",
             .doc = "Path of revolution: the n-gon inscribed in the ellipse with semi-axes a (x) and "
                    "b (y), vertex k at (a cos 2 pi k/n, b sin 2 pi k/n).",
             .params = {arg("a").positive(), arg("b").positive(), edges_param("n")},
             .run = [](const Arguments& args) {
               return path_value(ellipse_path(args.number("a"), args.number("b"), edge_count(args, "n")));
             }});
  table.add({.name = "convex_path",
             .doc = "Path of revolution through the given [x, y] vertices, which must form a strictly "
                    "convex polygon (checked exactly; clockwise order is reversed).",
             .params = {arg("vertices").list()},
             .run = [](const Arguments& args) {
               return path_value(polygon_path(point_pairs(args, "vertices", "the vertices")));
             }});
  table.add(
      {.name = "revolve",
       .doc = "Solid of revolution: the profile (a curve, a linearization, or a list of [r, z] "
              "with r >= 0) revolved along the convex path; profile point (r, z) and path vertex "
              "(u, v) give (r u, r v, z). An open profile must be monotone in z; flat caps close it "
              "where it does not end on the axis. A closed profile (closed=true, a closed curve, or "
              "a list whose last point repeats its first) is a simple polygon: the region it "
              "encloses is revolved (holes, overhangs, a hollow wall; a profile away from the axis "
              "needs a path around the axis). angle: degrees, 0 < angle <= 360, from +x "
              "counter-clockwise about z (OpenSCAD's rotate_extrude). The BSP tree is section 6's: "
              "balanced horizontal planes, then per slab a nearly balanced tree of the path (face "
              "planes only below face_only_below edges); a closed profile unites its z-monotone "
              "pieces, each such a tree.",
       .params =
           {arg("profile").any("a curve, a linearization or a list of [r, z] points"),
            arg("path").of<PathValue>("a path (circle, ellipse, convex_path)"),
            arg("face_only_below").integer(2, 1000000).defaults(double(revolution::RevolveOptions{}.face_only_below)),
            arg("closed").boolean().defaults(revolution::RevolveOptions{}.closed),
            [] {
              Param angle = arg("angle").between(0, 360).defaults(revolution::RevolveOptions{}.angle);
              angle.low_open = true;
              return angle;
            }()},
       .run = [](const Arguments& args) {
         bool closed = args.boolean("closed");
         const auto profile = profile_arg(args, "profile", closed);
         const auto& path = args.object<PathValue>("path").path;
         revolution::RevolveOptions options{.grid = args.grid(), .closed = closed, .angle = args.number("angle")};
         options.face_only_below = static_cast<int>(args.integer("face_only_below"));
         // About 1.4 nodes per profile segment and path edge (docs/revolution.md).
         args.charge(static_cast<std::uint64_t>(profile.size()) * static_cast<std::uint64_t>(path.edges()));
         return solid_value(revolution::revolve(profile, path, options));
       }});
  table.add({.name = "profile",
             .doc = "A profile model of Figure 5 as a 2D curve (x = r, y = z), sampled at `points` points "
                    "(default: the paper's 237 for the goblet, 169 for the human; 120 cavity, 101 ball) "
                    "equally spaced in arc length, disturbed by seeded uniform noise of amplitude `noise` "
                    "(z stays monotone). name: \"goblet\", \"cavity\" (the goblet's bowl), \"human\", "
                    "\"ball\" (radius 1.5 about z = 6.8). Our designs: Piegl's 1987 data is not available.",
             .params = {arg("name").string(), arg("points").integer(2, 1'000'000).optional("n"),
                        arg("noise").number().defaults(curves::SampleOptions{}.noise),
                        arg("seed").integer(0, 0x1p53).defaults(double(curves::SampleOptions{}.seed))},
             .run = [](const Arguments& args) -> Value {
               const std::string& name = args.string("name");
               curves::ProfileDesign design;
               curves::SampleOptions options;
               if (name == "goblet") {
                 design = curves::goblet_profile();
                 options.points = 237;
               } else if (name == "cavity") {
                 design = curves::goblet_cavity_profile();
                 options.points = 120;
               } else if (name == "human") {
                 design = curves::human_profile();
                 options.points = 169;
               } else if (name == "ball") {
                 design = curves::ball_profile(1.5, 6.8);
                 options.points = 101;
               } else {
                 args.fail("name", "unknown profile \"" + name + "\" (goblet, cavity, human, ball)");
               }
               if (args.has("points")) options.points = static_cast<int>(args.integer("points"));
               args.charge(static_cast<std::uint64_t>(options.points));
               options.noise = args.number("noise");
               options.seed = static_cast<std::uint64_t>(args.integer("seed"));
               return Value(std::shared_ptr<const Object>(
                   std::make_shared<CurveValue>(curves::sample_profile(design, options))));
             }});
}

}  // namespace sculpt::language
