// Built-ins of the motions area: surfaces for curves on them, geodesics, splines on surfaces, and
// rigid-body motions through poses (Pottmann, Leopoldseder & Hofer 2002, sec. 5; lib/splines/
// surface_curves.hpp, motion.hpp). sweep, carve and add take a motion (builtins_solids.cpp).
// See docs/motions.md.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "implicit/expression.hpp"
#include "language/builtins.hpp"
#include "language/implicit_compiler.hpp"
#include "language/motion_values.hpp"
#include "language/spline_values.hpp"
#include "language/surface_values.hpp"
#include "splines/motion.hpp"
#include "splines/surface_curves.hpp"

namespace sculpt::language {
namespace {

using V = Eigen::Vector3d;

Value constraint_surface_value(splines::Surface s, std::string description) {
  return Value(std::shared_ptr<const Object>(std::make_shared<ConstraintSurfaceValue>(std::move(s), std::move(description))));
}

/// The implicit surface f = 0 of a script function, compiled once (value and exact gradient).
splines::Surface implicit_from_function(const Arguments& args, std::string_view i, double scale) {
  const auto* f = args.value(i).get<std::shared_ptr<const UserFunction>>();
  if (!f) args.fail_type(i, "a surface (sphere_surface, ..., a B-spline surface) or a function fn f(x, y, z)");
  ImplicitCompileOptions options;
  options.global = [&args](const std::string& name) { return args.global(name); };
  std::shared_ptr<const implicit::Expression> e;
  try {
    e = std::make_shared<const implicit::Expression>(compile_implicit(**f, options));
  } catch (ScriptError& err) {
    err.add_note({args.call(), "in compiling '" + (*f)->name + "' for this call"});
    throw;
  }
  return splines::implicit_surface([e](const V& p) { return e->value(p); },
                                   [e](const V& p) -> V { return e->value_gradient(p).gradient; },
                                   {.scale = scale});
}

/// Argument i as a surface: a surface value, or a function whose zero set is the surface.
splines::Surface constraint_surface_arg(const Arguments& args, std::string_view i, double scale) {
  if (const auto* s = args.value(i).object<ConstraintSurfaceValue>()) return s->surface;
  if (const auto* b = args.value(i).object<SurfaceValue>()) return splines::bspline_surface_constraint(b->surface);
  return implicit_from_function(args, i, scale);
}

std::vector<V> motion_points_arg(const Arguments& args, std::string_view i) {
  std::vector<V> points;
  const List& l = args.list(i);
  for (std::size_t k = 0; k < l.size(); ++k) {
    const List* xyz = l[k].list();
    bool ok = xyz && xyz->size() == 3;
    for (std::size_t a = 0; ok && a < 3; ++a) ok = (*xyz)[a].get<double>() && std::isfinite(*(*xyz)[a].get<double>());
    if (!ok) args.fail(i, "point " + std::to_string(k + 1) + " must be [x, y, z]");
    points.emplace_back(*(*xyz)[0].get<double>(), *(*xyz)[1].get<double>(), *(*xyz)[2].get<double>());
  }
  return points;
}

/// A list of n finite numbers, or nullopt.
std::optional<std::vector<double>> finite_numbers(const Value& v, std::size_t n) {
  const List* l = v.list();
  if (!l || l->size() != n) return std::nullopt;
  std::vector<double> out;
  for (const Value& x : *l) {
    const double* d = x.get<double>();
    if (!d || !std::isfinite(*d)) return std::nullopt;
    out.push_back(*d);
  }
  return out;
}

/// Pose k of argument i: [position, rotation] with rotation [ax, ay, az, degrees] (axis and angle,
/// right-handed, as rotate) or a 3 x 3 matrix [[r00, r01, r02], [r10, ...], [r20, ...]].
splines::Pose pose_at(const Arguments& args, std::string_view i, const Value& item, std::size_t k) {
  const std::string what = "pose " + std::to_string(k + 1);
  const List* pair = item.list();
  if (!pair || pair->size() != 2) args.fail(i, what + " must be [position, rotation]");
  const auto position = finite_numbers((*pair)[0], 3);
  if (!position) args.fail(i, what + ": the position must be [x, y, z]");
  splines::Pose pose;
  pose.position = V((*position)[0], (*position)[1], (*position)[2]);
  if (const auto axis_angle = finite_numbers((*pair)[1], 4)) {
    const V axis((*axis_angle)[0], (*axis_angle)[1], (*axis_angle)[2]);
    if (axis.norm() == 0.0) args.fail(i, what + ": the rotation axis must not be zero");
    pose.rotation = Eigen::AngleAxisd((*axis_angle)[3] * M_PI / 180.0, axis.normalized()).toRotationMatrix();
    return pose;
  }
  const List* rows = (*pair)[1].list();
  if (!rows || rows->size() != 3) args.fail(i, what + ": the rotation must be [ax, ay, az, degrees] or a 3 x 3 matrix");
  for (int r = 0; r < 3; ++r) {
    const auto row = finite_numbers((*rows)[static_cast<std::size_t>(r)], 3);
    if (!row) args.fail(i, what + ": the rotation must be [ax, ay, az, degrees] or a 3 x 3 matrix");
    for (int c = 0; c < 3; ++c) pose.rotation(r, c) = (*row)[static_cast<std::size_t>(c)];
  }
  return pose;
}

const MotionValue& motion_arg(const Arguments& args, std::string_view i) { return args.object<MotionValue>(i); }

}  // namespace

std::string MotionValue::repr() const {
  const auto [t0, t1] = result.motion.domain();
  char rigid[32];
  std::snprintf(rigid, sizeof rigid, "%.2g", result.max_rigidity);
  return "<motion: " + std::to_string(result.motion.times().size()) + " poses, time [" + format_number(t0) + ", " +
         format_number(t1) + "], " + std::to_string(result.splits) + " splits, rigid to " + rigid + ">";
}

std::vector<Eigen::Isometry3d> motion_poses(const MotionValue& motion, const Solid& tool, double tolerance) {
  const std::vector<V> body = to_mesh(tool).vertices;
  if (body.empty()) throw InvalidInput("the tool is empty");
  Eigen::AlignedBox3d box;
  for (const V& v : body) box.extend(v);
  if (!(tolerance > 0.0)) tolerance = 0.01 * box.diagonal().norm();
  if (!(tolerance > 0.0)) tolerance = 1e-3;
  const std::vector<double> times = splines::sample_motion(motion.result.motion, body, {.tolerance = tolerance});
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(times.size());
  for (double t : times) poses.push_back(motion.result.motion.rigid(t));
  return poses;
}

void register_motions(BuiltinTable& table) {
  table.add({.name = "sphere_surface",
             .doc = "The sphere as a surface for geodesic and surface_spline.",
             .params = {arg("center").vector(3), arg("r").positive()},
             .run = [](const Arguments& args) -> Value {
               const V c = args.point("center");
               const double r = args.number("r");
               return constraint_surface_value(splines::sphere_surface(c, r),
                                               "sphere centre " + format_point(c) + ", radius " + format_number(r));
             }});
  table.add(
      {.name = "cylinder_surface",
       .doc = "The infinite circular cylinder of radius r around the line through `point` along `axis`, as a surface.",
       .params = {arg("point").vector(3), arg("axis").vector(3), arg("r").positive()},
       .run = [](const Arguments& args) -> Value {
         const V p = args.point("point"), a = args.point("axis");
         if (a.norm() == 0.0) args.fail("axis", "the axis must not be zero");
         const double r = args.number("r");
         return constraint_surface_value(
             splines::cylinder_surface(p, a, r),
             "cylinder through " + format_point(p) + " along " + format_point(a) + ", radius " + format_number(r));
       }});
  table.add({.name = "torus_surface",
             .doc = "The torus around `axis` through `center`: centre circle of radius R, tube of radius r (0 < r < "
                    "R), as a surface.",
             .params = {arg("center").vector(3), arg("axis").vector(3), arg("R").positive(), arg("r").positive()},
             .run = [](const Arguments& args) -> Value {
               const V c = args.point("center"), a = args.point("axis");
               if (a.norm() == 0.0) args.fail("axis", "the axis must not be zero");
               const double R = args.number("R"), r = args.number("r");
               if (!(r < R)) args.fail("r", "the tube radius r must be below R");
               return constraint_surface_value(splines::torus_surface(c, a, R, r),
                                               "torus centre " + format_point(c) + ", axis " + format_point(a) +
                                                   ", radii " + format_number(R) + ", " + format_number(r));
             }});
  table.add({.name = "geodesic",
             .doc = "A shortest path on `surface` (a surface value, or a function f whose zero set f = 0 is the "
                    "surface) from p to q (moved to their foot points): the discrete energy of a polygon of "
                    "`segments` edges minimized with its vertices on the surface, from the straight segment "
                    "(sec. 5.1); returned as the constant-speed cubic spline through the vertices (domain [0, 1]).",
             .params = {arg("surface").any("a surface or a function"), arg("p").vector(3), arg("q").vector(3),
                        arg("segments").integer(2, 100000).defaults(double(splines::GeodesicOptions{}.segments))},
             .run = [](const Arguments& args) -> Value {
               const V p = args.point("p"), q = args.point("q");
               const splines::Surface s = constraint_surface_arg(args, "surface", std::max(1.0, (p - q).norm()));
               splines::GeodesicOptions options;
               options.segments = static_cast<int>(args.integer("segments"));
               args.charge(static_cast<std::uint64_t>(options.segments));
               return spline_value(splines::geodesic(s, p, q, options).curve);
             }});
  table.add({.name = "surface_spline",
             .doc = "A cubic spline through `points` (moved to their foot points on `surface`) that stays close to "
                    "the surface and bends least (sec. 5.2, Fig. 14): the natural spline through them, each span "
                    "split into `splits` segments, moved as an active curve with the points kept exactly; splits "
                    "grow until the curve is within tol of the surface (or 24). Parameter: chord length.",
             .params = {arg("surface").any("a surface or a function"), arg("points").list(),
                        arg("splits")
                            .integer(1, splines::SurfaceSplineOptions{}.max_splits)
                            .defaults(double(splines::SurfaceSplineOptions{}.splits)),
                        arg("tol").positive().defaults(1e-4)},
             .run = [](const Arguments& args) -> Value {
               const std::vector<V> points = motion_points_arg(args, "points");
               double size = 0.0;
               for (std::size_t k = 1; k < points.size(); ++k) size = std::max(size, (points[k] - points[0]).norm());
               const splines::Surface s = constraint_surface_arg(args, "surface", std::max(1.0, size));
               splines::SurfaceSplineOptions options;
               options.splits = static_cast<int>(args.integer("splits"));
               options.distance = args.number("tol");
               args.charge(points.size() * static_cast<std::uint64_t>(options.splits));
               return spline_value(splines::surface_spline(s, points, options).curve);
             }});
  table.add({.name = "motion",
             .doc = "A smooth rigid-body motion through `poses`, each [position, rotation] with rotation "
                    "[ax, ay, az, degrees] (axis and angle) or a 3 x 3 matrix, at `times` (sec. 5.3): a cubic "
                    "curve of affine maps through the poses, pulled onto the rigid motions by minimizing its "
                    "bending with the poses kept exactly; splits grow until |A^T A - I| <= 5e-5. sweep, carve "
                    "and add take it as the path; motion_path gives the origin's path, pose the map at a time.",
             .params = {arg("poses").list(), arg("times").list().optional("[0, 1, ...]")},
             .run = [](const Arguments& args) -> Value {
               const List& l = args.list("poses");
               if (l.size() < 2) args.fail("poses", "give at least two poses");
               std::vector<splines::Pose> poses;
               for (std::size_t k = 0; k < l.size(); ++k) poses.push_back(pose_at(args, "poses", l[k], k));
               splines::MotionOptions options;
               if (args.has("times")) {
                 const auto t = finite_numbers(args.value("times"), l.size());
                 if (!t) args.fail("times", "times must be a list of one number per pose");
                 options.times = *t;
               }
               args.charge(poses.size() * 100);
               return Value(std::shared_ptr<const Object>(
                   std::make_shared<MotionValue>(splines::design_motion(poses, options))));
             }});
  table.add(
      {.name = "motion_path",
       .doc = "The path of the moving body's origin under motion m, as a spline (for plot).",
       .params = {arg("m").of<MotionValue>("a motion")},
       .run = [](const Arguments& args) -> Value { return spline_value(motion_arg(args, "m").result.motion.path()); }});
  table.add({.name = "pose",
             .doc = "The rigid map of motion m at time t (clamped to the motion's time span) as 3 rows [r0, r1, r2, "
                    "tx] (for transform).",
             .params = {arg("m").of<MotionValue>("a motion"), arg("t").finite_number()},
             .run = [](const Arguments& args) -> Value {
               const double t = args.number("t");
               const Eigen::Isometry3d p = motion_arg(args, "m").result.motion.rigid(t);
               List rows;
               for (int r = 0; r < 3; ++r)
                 rows.push_back(List{p.linear()(r, 0), p.linear()(r, 1), p.linear()(r, 2), p.translation()(r)});
               return rows;
             }});
}

}  // namespace sculpt::language
