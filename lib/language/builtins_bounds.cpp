// bounds(x): the axis-aligned bounding box of a value of any area that has points (solids, meshes,
// curves, linearizations, splines, surfaces, lists of points), from the library's own boxes.
#include <Eigen/Geometry>
#include <vector>

#include "bsp/boundary.hpp"
#include "curves/linearization.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"
#include "language/solid_values.hpp"
#include "language/spline_values.hpp"
#include "language/surface_values.hpp"
#include "mesh/mesh_measures.hpp"

namespace sculpt::language {
namespace {

Eigen::AlignedBox3d box_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  return box;
}

/// [[xmin, ymin(, zmin)], [xmax, ymax(, zmax)]]: 2D for plane curves and splines.
Value box_value(const Eigen::AlignedBox3d& box, int dimension) {
  List lo, hi;
  for (int k = 0; k < dimension; ++k) {
    lo.emplace_back(box.min()[k]);
    hi.emplace_back(box.max()[k]);
  }
  return List{Value(std::move(lo)), Value(std::move(hi))};
}

Value bounds(const Arguments& args) {
  const Value& x = args.value("x");
  if (const auto* s = x.object<SolidValue>()) {
    if (s->solid.is_empty()) args.fail("x", "the solid is empty: it has no bounding box");
    return box_value(bounding_box(s->solid), 3);
  }
  if (const auto* m = x.object<MeshValue>()) {
    if (m->mesh.faces.empty()) args.fail("x", "the mesh has no faces: it has no bounding box");
    return box_value(mesh_bounding_box(m->mesh), 3);
  }
  // A B-spline lies in the convex hull of its control points (a surface likewise).
  if (const auto* sv = x.object<SplineValue>()) return box_value(box_of(sv->spline.controls()), sv->spline.dimension());
  if (const auto* sf = x.object<SurfaceValue>()) return box_value(box_of(sf->surface.controls()), 3);
  if (const auto* la = x.object<LinearizationValue>())
    return box_value(box_of(curves::linearization_points(la->curve->curve, la->result)), la->curve->curve.dimension);
  curves::DigitizedCurve c;
  if (const auto* cv = x.object<CurveValue>()) {
    c = cv->curve;
  } else if (x.list()) {
    c = curve_from_points(args, "x");
  } else {
    args.fail_type("x", "a solid, a mesh, a curve, a linearization, a spline, a surface or a list of points");
  }
  if (c.points.empty()) args.fail("x", "no points: no bounding box");
  return box_value(box_of(c.points), c.dimension);
}

}  // namespace

void register_bounds(BuiltinTable& table) {
  table.add(
      {.name = "bounds",
       .doc = "The axis-aligned bounding box [[xmin, ymin, zmin], [xmax, ymax, zmax]] of x: a solid (its "
              "boundary vertices), a mesh, a curve, a linearization, a list of points, a spline or a "
              "surface (the box of the control points, which contains the curve or surface). Plane (2D) "
              "curves, splines and point lists give [[xmin, ymin], [xmax, ymax]]. The empty solid, a mesh "
              "without faces and an empty list are errors.",
       .params = {arg("x").any("a solid, a mesh, a curve, a linearization, a spline, a surface or a list of points")},
       .run = bounds});
}

}  // namespace sculpt::language
