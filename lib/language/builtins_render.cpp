// Built-ins of the render area: pictures of solids (PNG) and SVG plots of curves, linearizations
// and splines (lib/render; docs/pictures.md).
#include <cctype>
#include <cmath>
#include <filesystem>

#include "base/errors.hpp"
#include "language/builtins.hpp"
#include "language/curve_values.hpp"
#include "language/motion_values.hpp"
#include "language/picture_items.hpp"
#include "language/solid_values.hpp"
#include "language/spline_values.hpp"
#include "language/surface_values.hpp"
#include "mesh/mesh_io.hpp"
#include "render/camera.hpp"
#include "render/picture.hpp"
#include "render/plot.hpp"
#include "render/png_image.hpp"

namespace sculpt::language {
namespace {

/// The view argument: a name ("iso", "front", ...) or a direction [x, y, z].
Eigen::Vector3d view_arg(const Arguments& args, std::string_view i) {
  if (const std::string* name = args.value(i).get<std::string>()) {
    try {
      return render::view_direction(*name);
    } catch (const InvalidInput& e) {
      args.fail(i, e.what());
    }
  }
  const std::vector<double> v = args.vector(i, 3);
  const Eigen::Vector3d d(v[0], v[1], v[2]);
  if (!d.allFinite() || d.norm() == 0) args.fail(i, "the view direction must be a nonzero finite vector");
  return d;
}

}  // namespace

bool is_point_list(const List* list) {
  return list && !list->empty() && (*list)[0].list() && !(*list)[0].list()->empty() && (*list)[0].list()->front().get<double>();
}

std::variant<render::PictureItem, std::string> picture_item(const Value& v) {
  if (const auto* s = v.object<SolidValue>()) return render::PictureMesh{.mesh = s->boundary(), .two_sided = false};
  if (const auto* m = v.object<MeshValue>()) return render::PictureMesh{.mesh = m->mesh, .two_sided = true};
  if (const auto* b = v.object<SurfaceValue>()) return b->surface;
  if (const auto* s = v.object<SplineValue>()) return s->spline;
  if (const auto* m = v.object<MotionValue>()) return m->result.motion.path();
  if (const auto* c = v.object<CurveValue>()) return render::PictureCurve{.points = c->curve.points, .closed = c->curve.closed};
  if (const auto* l = v.object<LinearizationValue>())
    return render::PictureCurve{.points = curves::linearization_points(l->curve->curve, l->result), .closed = false};
  if (const List* points = v.list(); is_point_list(points)) {
    render::PictureCurve polyline;
    for (std::size_t p = 0; p < points->size(); ++p) {
      const List* xyz = (*points)[p].list();
      const std::size_t n = xyz ? xyz->size() : 0;
      bool ok = n == 2 || n == 3;
      for (std::size_t a = 0; ok && a < n; ++a) ok = (*xyz)[a].get<double>() && std::isfinite(*(*xyz)[a].get<double>());
      if (!ok) return "point " + std::to_string(p + 1) + " must be [x, y] or [x, y, z]";
      polyline.points.emplace_back(*(*xyz)[0].get<double>(), *(*xyz)[1].get<double>(),
                                   n == 3 ? *(*xyz)[2].get<double>() : 0.0);
    }
    return polyline;
  }
  if (const auto* c = v.object<ConstraintSurfaceValue>())
    return "cannot draw " + c->description +
           " (only B-spline surfaces are tessellated; draw the solid, e.g. sphere(r) translated, or a surface_mesh)";
  return "must be a solid, mesh, surface, spline, curve, linearization, motion or list of points, not " + type_name(v);
}

std::variant<std::vector<render::PictureItem>, std::string> picture_items(const Value& x, const std::string& name) {
  std::vector<render::PictureItem> items;
  const List* list = x.list();
  if (list && !is_point_list(list)) {
    if (list->empty()) return std::string("the list is empty");
    for (std::size_t k = 0; k < list->size(); ++k) {
      auto item = picture_item((*list)[k]);
      if (const std::string* error = std::get_if<std::string>(&item)) return "item " + std::to_string(k) + " " + *error;
      items.push_back(std::move(std::get<render::PictureItem>(item)));
    }
    return items;
  }
  auto item = picture_item(x);
  if (const std::string* error = std::get_if<std::string>(&item)) return name + " " + *error;
  items.push_back(std::move(std::get<render::PictureItem>(item)));
  return items;
}

namespace {

/// A list of [x, y] or [x, y, z] points as a polyline (2D unless a point has z); fails at
/// argument i with `what`.
curves::DigitizedCurve polyline_of(const Arguments& args, std::string_view i, const List& points,
                                   const std::string& what) {
  auto item = picture_item(Value(points));
  if (const std::string* error = std::get_if<std::string>(&item)) args.fail(i, what + *error);
  curves::DigitizedCurve polyline;
  polyline.points = std::get<render::PictureCurve>(std::get<render::PictureItem>(item)).points;
  polyline.dimension = 2;
  for (const Value& p : points)
    if (p.list() && p.list()->size() == 3) polyline.dimension = 3;
  return polyline;
}

/// The file of argument i, which must end in `extension` (".png": the picture is PNG whatever the
/// name says, so render(b, "x.jpg") would write PNG data into a .jpg), with its folders created.
std::filesystem::path output_path(const Arguments& args, std::string_view i, const std::string& extension,
                                  const char* format) {
  const std::filesystem::path path = args.file_path(i);
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != extension)
    args.fail(i, std::string("the picture is ") + format + ": the file name must end in " + extension + ", not '" +
                     path.extension().string() + "'");
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  return path;
}

/// The view parameter of render and plot.
Param view_param() { return arg("view").any("a view name or a direction [x, y, z]").optional("\"iso\""); }

}  // namespace

void register_render(BuiltinTable& table) {
  const render::PictureOptions picture;  // the defaults
  table.add(
      {.name = "render",
       .doc = "Writes a shaded picture (PNG) of x, or of a list of items each in its own colour, seen "
              "orthographically from direction `view` (a name: iso, front, back, left, right, top, bottom; "
              "or a vector pointing towards the viewer). Items: solids; surfaces and meshes (shaded on both "
              "sides; a surface is tessellated to chord error `tol`, 0: half a pixel); curves, splines "
              "(geodesics, splines on surfaces), linearizations, motions (the origin's path) and lists of "
              "points, drawn as lines `width` pixels wide (0: 3 per 600 pixels) where not hidden behind "
              "the shaded items. Hidden surfaces are removed per pixel; lines mark silhouettes and faces "
              "meeting at more than `edge_angle` degrees. `scale` in pixels per unit with `center` at the "
              "image centre; 0 frames the items. `antialias`: samples per pixel side (1: one at the pixel's "
              "centre). smooth=true shades curved surfaces as curved (normals interpolated across faces "
              "meeting at no more than edge_angle). The file is replaced atomically; folders are created.",
       .params = {arg("x").any("an item to draw or a list of them"), arg("file").string().shown_as("\"file.png\""),
                  view_param(), arg("size").vector(2).defaults(List{double(picture.width), double(picture.height)}),
                  arg("scale").between(0, 1e6).defaults(picture.scale),
                  arg("center").vector(3).defaults(List{picture.center.x(), picture.center.y(), picture.center.z()}),
                  arg("edge_angle").between(0, 180).defaults(picture.edge_angle),
                  arg("edges").boolean().defaults(picture.edges),
                  arg("tol").at_least(0).defaults(picture.surface_tolerance),
                  arg("width").integer(0, 64).defaults(double(picture.curve_width)),
                  arg("antialias").integer(1, 4).defaults(double(kPictureAntialias)),
                  arg("smooth").boolean().defaults(picture.smooth)},
       .run = [](const Arguments& args) -> Value {
         (void)output_path(args, "file", ".png", "PNG");  // a wrong name is refused before the work
         auto drawn = picture_items(args.value("x"), "x");
         if (const std::string* error = std::get_if<std::string>(&drawn)) args.fail("x", *error);
         const std::vector<render::PictureItem>& items = std::get<std::vector<render::PictureItem>>(drawn);
         render::PictureOptions options;
         if (args.has("view")) options.view = view_arg(args, "view");
         if (args.has("size")) {
           const std::vector<double> size = args.vector("size");
           for (double s : size)
             if (!(s >= 1 && s <= render::kMaxImageSide) || s != std::floor(s))
               args.fail("size", "size must be [width, height], whole numbers from 1 to " +
                                     std::to_string(render::kMaxImageSide));
           options.width = static_cast<int>(size[0]);
           options.height = static_cast<int>(size[1]);
           if (static_cast<long long>(options.width) * options.height > render::kMaxImagePixels)
             args.fail("size", "size: at most " + std::to_string(render::kMaxImagePixels) + " pixels");
         }
         options.scale = args.number("scale");
         const std::vector<double> c = args.vector("center");
         options.center = Eigen::Vector3d(c[0], c[1], c[2]);
         options.edge_angle = args.number("edge_angle");
         options.edges = args.boolean("edges");
         options.surface_tolerance = args.number("tol");
         options.curve_width = static_cast<int>(args.integer("width"));
         options.antialias = static_cast<int>(args.integer("antialias"));
         options.smooth = args.boolean("smooth");
         args.charge(static_cast<std::uint64_t>(options.width) * static_cast<std::uint64_t>(options.height) / 1024);
         const render::Image image = render::render_items(items, options);
         render::write_png(image, output_path(args, "file", ".png", "PNG"));
         return {};
       }});
  table.add(
      {.name = "plot",
       .doc = "Writes an SVG figure of xs: a curve, linearization, spline, motion or list of points, or a "
              "list of them, each in its own colour: a curve as its points, a linearization as its polygon "
              "with the break points marked (and its curve's points), a spline (a geodesic, a spline on a "
              "surface) as the curve with its dashed control polygon, a motion as its origin's path, a list "
              "of points as a polyline. 2D data is drawn in its plane; when any "
              "item is 3D (or `view` is given) everything is projected along `view` (as in render). "
              "`size`: the figure's side. The file is replaced atomically; folders are created.",
       .params = {arg("xs").any("an item to plot or a list of them"), arg("file").string().shown_as("\"file.svg\""),
                  view_param(), arg("size").between(50, 10000).defaults(480.0), arg("title").string().defaults("")},
       .run = [](const Arguments& args) -> Value {
         // A single item, or a list of items (a list of points alone is one item).
         std::vector<const Value*> items;
         const List* list = args.value("xs").list();
         if (list && !is_point_list(list)) {
           for (const Value& v : *list) items.push_back(&v);
           if (items.empty()) args.fail("xs", "plot: the list is empty");
         } else {
           items.push_back(&args.value("xs"));
         }
         render::PlotPanel panel;
         panel.title = args.string("title");
         bool three_d = false;
         for (std::size_t k = 0; k < items.size(); ++k) {
           const Value& v = *items[k];
           const std::string color = render::plot_color(k);
           const std::string what = items.size() > 1 ? "item " + std::to_string(k) + " " : "";
           if (const auto* c = v.object<CurveValue>()) {
             panel.layers.push_back(render::curve_layer(c->curve, color));
             three_d |= c->curve.dimension == 3;
           } else if (const auto* l = v.object<LinearizationValue>()) {
             panel.layers.push_back(render::curve_layer(l->curve->curve, "#9a9a9a"));
             for (auto& layer : render::linearization_layers(l->curve->curve, l->result, color))
               panel.layers.push_back(std::move(layer));
             three_d |= l->curve->curve.dimension == 3;
           } else if (const auto* s = v.object<SplineValue>()) {
             for (auto& layer : render::spline_layers(s->spline, color)) panel.layers.push_back(std::move(layer));
             three_d |= s->spline.dimension() == 3;
           } else if (const auto* m = v.object<MotionValue>()) {
             for (auto& layer : render::spline_layers(m->result.motion.path(), color))
               panel.layers.push_back(std::move(layer));
             three_d = true;
           } else if (const List* points = v.list()) {
             const curves::DigitizedCurve polyline = polyline_of(args, "xs", *points, what);
             three_d |= polyline.dimension == 3;
             panel.layers.push_back({.lines = {polyline.points}, .color = color, .width = 1.5});
           } else {
             args.fail("xs",
                       what + "must be a curve, linearization, spline, motion or list of points, not " + type_name(v));
           }
         }
         render::PlotOptions options;
         if (three_d || args.has("view")) {
           options.projection = render::Projection::View;
           if (args.has("view")) options.view = view_arg(args, "view");
         }
         options.size = args.number("size");
         write_file_atomically(output_path(args, "file", ".svg", "SVG"), render::svg_panels({panel}, options));
         return {};
       }});
}

}  // namespace sculpt::language
