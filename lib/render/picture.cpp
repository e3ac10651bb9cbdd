#include "render/picture.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"
#include "render/detail/edges.hpp"
#include "render/detail/rasterizer.hpp"
#include "render/detail/scene.hpp"
#include "render/detail/smooth_normals.hpp"
#include "splines/tessellate_surface.hpp"

namespace sculpt::render {
namespace {

using detail::DepthBuffer;
using detail::FaceInfo;
using detail::ScreenPolygon;

constexpr std::array<std::uint8_t, 3> kLine{40, 40, 48};

/// Newell's normal of a polygon (zero for a degenerate one).
Eigen::Vector3d newell_normal(const PolygonMesh& mesh, const std::vector<int>& face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Eigen::Vector3d& p = mesh.vertices[static_cast<std::size_t>(face[k])];
    const Eigen::Vector3d& q = mesh.vertices[static_cast<std::size_t>(face[(k + 1) % face.size()])];
    n += Eigen::Vector3d((p.y() - q.y()) * (p.z() + q.z()), (p.z() - q.z()) * (p.x() + q.x()),
                         (p.x() - q.x()) * (p.y() + q.y()));
  }
  return n;
}

void check_faces(const PolygonMesh& mesh) {
  for (const auto& face : mesh.faces)
    for (int v : face)
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
        throw InvalidInput("render: a face refers to vertex " + std::to_string(v) + " of " +
                           std::to_string(mesh.vertices.size()));
}

int line_width(const Camera& camera, const PictureOptions& options) {
  return options.line_width > 0 ? options.line_width
                                : std::max(1, static_cast<int>(std::lround(std::min(camera.width, camera.height) / 600.0)));
}

/// Crease lines shorter than this many pixels that touch no outline are specks (edges.hpp):
/// 2 % of the picture's smaller side, at least 6 (12 pixels in a 600-pixel picture).
int least_crease_pixels(const Camera& camera) {
  return std::max(6, static_cast<int>(std::lround(std::min(camera.width, camera.height) / 50.0)));
}

/// The options of the supersampled picture behind an antialiased one of `final`'s size: every
/// length in pixels times the factor (the framing scales with the size by itself).
PictureOptions supersampled(const PictureOptions& options, const Camera& final) {
  const int f = options.antialias;
  PictureOptions big = options;
  big.antialias = 1;
  big.width = options.width * f;
  big.height = options.height * f;
  big.scale = options.scale * f;
  big.line_width = line_width(final, options) * f;
  big.curve_width = (options.curve_width > 0 ? options.curve_width : 3 * line_width(final, options)) * f;
  return big;
}

/// Each factor x factor block of `big` averaged into one pixel.
Image downsampled(const Image& big, int factor) {
  Image image{.width = big.width / factor, .height = big.height / factor, .rgb = {}};
  image.rgb.resize(3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  const int n = factor * factor;
  for (int y = 0; y < image.height; ++y) {
    check_cancel();  // Ctrl-C (base/cancel.hpp), once a row
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int v = 0; v < factor; ++v)
          for (int u = 0; u < factor; ++u)
            sum += big.rgb[3 * (static_cast<std::size_t>(y * factor + v) * static_cast<std::size_t>(big.width) +
                                static_cast<std::size_t>(x * factor + u)) +
                           static_cast<std::size_t>(c)];
        image.rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                       static_cast<std::size_t>(x)) +
                  static_cast<std::size_t>(c)] = static_cast<std::uint8_t>((sum + n / 2) / n);
      }
  }
  return image;
}

void check_antialias(const PictureOptions& options) {
  if (options.antialias < 1 || options.antialias > 4)
    throw InvalidInput("render: antialias must be 1 to 4 samples per pixel side, got " +
                       std::to_string(options.antialias));
}

}  // namespace

std::array<std::uint8_t, 3> solid_colour(std::size_t k) {
  static constexpr std::array<std::array<std::uint8_t, 3>, 8> kPalette = {{
      {86, 140, 205},   // blue
      {226, 135, 67},   // orange
      {96, 178, 106},   // green
      {200, 90, 90},    // red
      {150, 115, 200},  // violet
      {200, 180, 80},   // ochre
      {80, 180, 180},   // teal
      {170, 170, 170},  // grey
  }};
  return kPalette[k % kPalette.size()];
}

Camera picture_camera_for_points(const std::vector<Eigen::Vector3d>& points, const PictureOptions& options) {
  if (options.width < 1 || options.width > kMaxImageSide || options.height < 1 || options.height > kMaxImageSide)
    throw InvalidInput("render: the picture size must be 1 to " + std::to_string(kMaxImageSide) + " pixels per side");
  if (static_cast<long long>(options.width) * options.height > kMaxImagePixels)
    throw InvalidInput("render: the picture may have at most " + std::to_string(kMaxImagePixels) + " pixels");
  if (!std::isfinite(options.scale) || options.scale < 0 || options.scale > 1e6)
    throw InvalidInput("render: the scale must be 0 to 10^6 pixels per unit (0: frame the solids)");
  if (!options.center.allFinite()) throw InvalidInput("render: the centre must be finite");
  if (!std::isfinite(options.edge_angle)) throw InvalidInput("render: the edge angle must be finite");
  if (options.line_width < 0 || options.line_width > 64) throw InvalidInput("render: the line width must be 0 to 64");
  if (options.curve_width < 0 || options.curve_width > 64) throw InvalidInput("render: the curve width must be 0 to 64");
  Camera camera = orient_camera(options.view);
  camera.width = options.width;
  camera.height = options.height;
  if (options.scale > 0) {
    camera.scale = options.scale;
    camera.center = options.center;
  } else {
    frame_points(camera, points);
  }
  return camera;
}

Camera picture_camera(const std::vector<PolygonMesh>& meshes, const PictureOptions& options) {
  for (const PolygonMesh& mesh : meshes) check_faces(mesh);
  std::vector<Eigen::Vector3d> points;
  if (options.scale == 0)
    for (const PolygonMesh& mesh : meshes)
      for (const auto& face : mesh.faces)
        for (int v : face) points.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
  return picture_camera_for_points(points, options);
}

namespace detail {
namespace {

/// True if the face's corners turn the same way at every corner on screen (a convex polygon).
bool convex_on_screen(const std::vector<Eigen::Vector3d>& screen, const std::vector<int>& face) {
  if (face.size() == 3) return true;
  int sign = 0;
  const std::size_t n = face.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d a = screen[static_cast<std::size_t>(face[k])].head<2>();
    const Eigen::Vector2d b = screen[static_cast<std::size_t>(face[(k + 1) % n])].head<2>();
    const Eigen::Vector2d c = screen[static_cast<std::size_t>(face[(k + 2) % n])].head<2>();
    const int s = orient2d(a, b, c);
    if (s == 0) continue;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

}  // namespace

Scene draw_scene(const std::vector<PolygonMesh>& meshes, const Camera& camera, const std::vector<bool>& two_sided,
                 const std::vector<int>& ids, double smooth_crease) {
  Scene scene{.buffer = DepthBuffer(camera.width, camera.height), .faces = {}};
  ScreenPolygon polygon;
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const PolygonMesh& mesh = meshes[m];
    std::vector<Eigen::Vector3d> screen(mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) screen[v] = camera.project(mesh.vertices[v]);
    const auto normals =
        smooth_crease >= 0 ? corner_normals(mesh, smooth_crease) : std::vector<std::vector<Eigen::Vector3d>>{};
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      poll.tick();
      const auto& face = mesh.faces[f];
      if (face.size() < 3) continue;
      const Eigen::Vector3d n = newell_normal(mesh, face);
      const double length = n.norm();
      if (!(length > 0)) continue;
      Eigen::Vector3d unit = n / length;
      // Back faces are never the nearest boundary of a closed solid; faces seen edge-on cover no
      // pixel centre's ray in their interior. A two-sided mesh's back face is drawn as the front
      // face of the other side (normal turned over, corners reversed).
      double nz = unit.dot(camera.toward);
      const bool flip = nz < 0 && m < two_sided.size() && two_sided[m];
      if (flip) {
        unit = -unit;
        nz = -nz;
      }
      if (!(nz > 1e-12)) continue;
      // Depth plane on screen: a world point p = center + right (x - w/2) / s - up (y - h/2) / s
      // + toward t lies on the face's plane n . (p - p0) = 0.
      const Eigen::Vector3d& p0 = mesh.vertices[static_cast<std::size_t>(face[0])];
      const double nr = unit.dot(camera.right), nu = unit.dot(camera.up);
      polygon.dx = -nr / (camera.scale * nz);
      polygon.dy = nu / (camera.scale * nz);
      polygon.d0 = unit.dot(p0 - camera.center) / nz - polygon.dx * 0.5 * camera.width - polygon.dy * 0.5 * camera.height;
      polygon.id = static_cast<int>(scene.faces.size());
      scene.faces.push_back({.solid = m < ids.size() ? ids[m] : static_cast<int>(m),
                             .face = static_cast<int>(f),
                             .normal = unit,
                             .dx = polygon.dx,
                             .dy = polygon.dy,
                             .d0 = polygon.d0});
      if (!normals.empty()) {
        FaceInfo& info = scene.faces.back();
        for (std::size_t k = 0; k < face.size(); ++k) {
          info.corners.emplace_back(screen[static_cast<std::size_t>(face[k])].head<2>());
          info.corner_normals.push_back(flip ? -normals[f][k] : normals[f][k]);
        }
      }
      // The rasterizer takes convex polygons; a boundary face of a set operation's result is often
      // not convex (a face around a groove): it is drawn as the triangles of its exact ear
      // clipping, all with the face's id, which share their edges watertightly.
      if (convex_on_screen(screen, face)) {
        polygon.corners.clear();
        for (int v : face) polygon.corners.emplace_back(screen[static_cast<std::size_t>(v)].head<2>());
        if (flip) std::reverse(polygon.corners.begin(), polygon.corners.end());
        rasterize(scene.buffer, polygon);
      } else {
        for (const IndexTriangle& t : triangulate_polygon(mesh.vertices, face)) {
          polygon.corners.clear();
          for (int v : t) polygon.corners.emplace_back(screen[static_cast<std::size_t>(v)].head<2>());
          if (flip) std::reverse(polygon.corners.begin(), polygon.corners.end());
          rasterize(scene.buffer, polygon);
        }
      }
    }
  }
  return scene;
}

}  // namespace detail

namespace {

/// `base` lit by `light` on a surface of unit normal n: 0.3 ambient plus 0.7 diffuse.
std::array<std::uint8_t, 3> lit(const std::array<std::uint8_t, 3>& base, const Eigen::Vector3d& n,
                                const Eigen::Vector3d& light) {
  const double intensity = 0.3 + 0.7 * std::max(0.0, n.dot(light));
  std::array<std::uint8_t, 3> out{};
  for (std::size_t c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(std::lround(base[c] * intensity));
  return out;
}

/// The shaded picture of a drawn scene: flat shading per face in its solid's colour (or smooth,
/// per pixel, where the faces carry corner normals), lines.
Image shade(const detail::Scene& scene, const Camera& camera, const PictureOptions& options) {
  const DepthBuffer& buffer = scene.buffer;
  const std::vector<FaceInfo>& faces = scene.faces;

  // Flat shading: a light a little above and left of the viewer, plus ambient light (the three
  // visible sides of a box seen from "iso" get about 0.87, 0.68 and 0.45 of the full colour).
  const Eigen::Vector3d light = (camera.toward + 0.4 * camera.up - 0.25 * camera.right).normalized();
  std::vector<std::array<std::uint8_t, 3>> shade(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    shade[f] = lit(solid_colour(static_cast<std::size_t>(faces[f].solid)), faces[f].normal, light);
  std::vector<bool> lines;
  if (options.edges)
    lines = detail::edge_pixels(buffer, faces, std::cos(options.edge_angle * std::numbers::pi / 180), 1 / camera.scale,
                                least_crease_pixels(camera));
  const int width = line_width(camera, options);
  if (!lines.empty() && width > 1) lines = detail::widen_lines(buffer, lines, width);

  Image image{.width = camera.width, .height = camera.height, .rgb = {}};
  image.rgb.resize(3 * buffer.face.size());
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp): tens of millions of pixels when antialiased
  for (std::size_t i = 0; i < buffer.face.size(); ++i) {
    poll.tick();
    const int f = buffer.face[i];
    std::array<std::uint8_t, 3> colour = f < 0                          ? options.background
                                         : (!lines.empty() && lines[i]) ? kLine
                                                                        : shade[static_cast<std::size_t>(f)];
    if (f >= 0 && (lines.empty() || !lines[i]) && !faces[static_cast<std::size_t>(f)].corner_normals.empty()) {
      // Smooth shading: lit with the normal interpolated at the pixel's centre.
      const FaceInfo& info = faces[static_cast<std::size_t>(f)];
      const Eigen::Vector2d centre(static_cast<double>(i % static_cast<std::size_t>(buffer.width)) + 0.5,
                                   static_cast<double>(i / static_cast<std::size_t>(buffer.width)) + 0.5);
      const Eigen::Vector3d n = detail::interpolated_normal(info.corners, info.corner_normals, centre);
      colour = lit(solid_colour(static_cast<std::size_t>(info.solid)), n, light);
    }
    std::copy(colour.begin(), colour.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(3 * i));
  }
  return image;
}

}  // namespace

Image render_meshes(const std::vector<PolygonMesh>& meshes, const PictureOptions& options) {
  check_antialias(options);
  const Camera camera = picture_camera(meshes, options);
  if (options.antialias > 1)
    return downsampled(render_meshes(meshes, supersampled(options, camera)), options.antialias);
  return shade(detail::draw_scene(meshes, camera, {}, {}, options.smooth ? options.edge_angle : -1), camera, options);
}

namespace {

using V = Eigen::Vector3d;

/// Points of a B-spline curve: per knot span, `per_span(coarse length of the span)` segments.
template <class PerSpan>
std::vector<V> sample_spline(const splines::BSpline& spline, PerSpan per_span) {
  const std::vector<double> breaks = spline.breaks();
  std::vector<V> points;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double a = breaks[k], b = breaks[k + 1];
    double length = 0;
    V previous = spline.point(a);
    for (int i = 1; i <= 8; ++i) {
      const V p = spline.point(a + (b - a) * i / 8);
      length += (p - previous).norm();
      previous = p;
    }
    const int n = per_span(length);
    if (k == 0) points.push_back(spline.point(a));
    for (int i = 1; i <= n; ++i) points.push_back(spline.point(i == n ? b : a + (b - a) * i / n));
  }
  return points;
}

void check_points(const std::vector<V>& points) {
  for (const V& p : points)
    if (!p.allFinite()) throw InvalidInput("render: a curve point is not finite");
}

/// Clips the screen segment a + t (b - a), t in [t0, t1], to the box [lo, hi]^2 (Liang-Barsky);
/// false if nothing is left.
bool clip(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
          double& t0, double& t1) {
  t0 = 0, t1 = 1;
  for (int axis = 0; axis < 2; ++axis) {
    const double d = b[axis] - a[axis];
    if (d == 0) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) return false;
      continue;
    }
    double u = (lo[axis] - a[axis]) / d, v = (hi[axis] - a[axis]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u);
    t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

/// The curves' own buffer: the nearest curve point drawn at each pixel.
struct CurveBuffer {
  std::vector<double> depth;
  std::vector<int> item;
};

/// Draws polyline `points` (world) as item `id` into `curves`, `radius` pixels around its
/// projection, where it is not hidden by the scene (the bias of render_items).
void draw_curve(const detail::Scene& scene, const Camera& camera, const std::vector<V>& points, bool closed, int id,
                double radius, double chord_error, CurveBuffer& curves) {
  const DepthBuffer& buffer = scene.buffer;
  // Depth change per pixel of each face (faces within 88.9 degrees of facing the viewer).
  std::vector<double> slope(scene.faces.size());
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    const V& n = scene.faces[f].normal;
    slope[f] = std::hypot(n.dot(camera.right), n.dot(camera.up)) / (std::max(0.02, n.dot(camera.toward)) * camera.scale);
  }
  const double constant = chord_error + 1 / camera.scale;
  auto stamp = [&](const V& s) {
    const int x0 = std::max(0, static_cast<int>(std::floor(s.x() - radius - 0.5)));
    const int x1 = std::min(buffer.width - 1, static_cast<int>(std::ceil(s.x() + radius - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(s.y() - radius - 0.5)));
    const int y1 = std::min(buffer.height - 1, static_cast<int>(std::ceil(s.y() + radius - 0.5)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double dx = x + 0.5 - s.x(), dy = y + 0.5 - s.y();
        const double distance = std::sqrt(dx * dx + dy * dy);
        if (distance > radius) continue;
        const std::size_t i = buffer.index(x, y);
        const int f = buffer.face[i];
        if (f >= 0 && buffer.depth[i] > s.z() + (distance + 1) * slope[static_cast<std::size_t>(f)] + constant) continue;
        if (s.z() > curves.depth[i]) {
          curves.depth[i] = s.z();
          curves.item[i] = id;
        }
      }
  };
  std::vector<V> screen;
  screen.reserve(points.size() + 1);
  for (const V& p : points) screen.push_back(camera.project(p));
  if (closed && points.size() > 2) screen.push_back(screen.front());
  const Eigen::Vector2d lo(-radius - 1, -radius - 1), hi(buffer.width + radius + 1, buffer.height + radius + 1);
  if (screen.size() == 1) {
    if (screen[0].x() >= lo.x() && screen[0].x() <= hi.x() && screen[0].y() >= lo.y() && screen[0].y() <= hi.y()) stamp(screen[0]);
    return;
  }
  for (std::size_t k = 0; k + 1 < screen.size(); ++k) {
    const V& a = screen[k];
    const V& b = screen[k + 1];
    double t0 = 0, t1 = 1;
    if (!clip(a.head<2>(), b.head<2>(), lo, hi, t0, t1)) continue;
    // Samples a quarter pixel apart along the visible part.
    const double length = (b.head<2>() - a.head<2>()).norm() * (t1 - t0);
    const int n = std::max(1, static_cast<int>(std::ceil(length / 0.25)));
    for (int i = 0; i <= n; ++i) stamp(a + (t0 + (t1 - t0) * i / n) * (b - a));
  }
}

}  // namespace

std::array<std::uint8_t, 3> curve_colour(std::size_t k) {
  auto c = solid_colour(k);
  for (auto& x : c) x = static_cast<std::uint8_t>(std::lround(0.6 * x));
  return c;
}

Image render_items(const std::vector<PictureItem>& items, const PictureOptions& options) {
  if (!std::isfinite(options.surface_tolerance) || options.surface_tolerance < 0)
    throw InvalidInput("render: the surface tolerance must be a finite number >= 0 (0: half a pixel)");
  // Framing: meshes' vertices, surfaces tessellated coarsely (1 % of their control points' box),
  // curves sampled 8 times per span.
  std::vector<V> frame;
  for (const PictureItem& item : items) {
    if (const auto* m = std::get_if<PictureMesh>(&item)) {
      check_faces(m->mesh);
      for (const auto& face : m->mesh.faces)
        for (int v : face) frame.push_back(m->mesh.vertices[static_cast<std::size_t>(v)]);
    } else if (const auto* s = std::get_if<splines::BSplineSurface>(&item)) {
      Eigen::AlignedBox3d box;
      for (const V& c : s->controls()) box.extend(c);
      const double diagonal = box.diagonal().norm();
      const auto coarse = splines::tessellate(*s, {.tolerance = diagonal > 0 ? 0.01 * diagonal : 1.0, .max_cells = 64});
      frame.insert(frame.end(), coarse.points.begin(), coarse.points.end());
    } else if (const auto* b = std::get_if<splines::BSpline>(&item)) {
      const auto points = sample_spline(*b, [](double) { return 8; });
      frame.insert(frame.end(), points.begin(), points.end());
    } else {
      const auto& c = std::get<PictureCurve>(item);
      check_points(c.points);
      frame.insert(frame.end(), c.points.begin(), c.points.end());
    }
  }
  const Camera camera = picture_camera_for_points(frame, options);
  check_antialias(options);
  if (options.antialias > 1) return downsampled(render_items(items, supersampled(options, camera)), options.antialias);
  const double tolerance = options.surface_tolerance > 0 ? options.surface_tolerance : 0.5 / camera.scale;

  std::vector<PolygonMesh> meshes;
  std::vector<bool> two_sided;
  std::vector<int> ids;
  double chord_error = 0;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (const auto* m = std::get_if<PictureMesh>(&items[k])) {
      meshes.push_back(m->mesh);
      two_sided.push_back(m->two_sided);
      ids.push_back(static_cast<int>(k));
    } else if (const auto* s = std::get_if<splines::BSplineSurface>(&items[k])) {
      const auto t = splines::tessellate(*s, {.tolerance = tolerance});
      chord_error = std::max(chord_error, t.error_bound);
      PolygonMesh mesh;
      mesh.vertices = t.points;
      for (const auto& tri : t.triangles) mesh.faces.push_back({tri[0], tri[1], tri[2]});
      meshes.push_back(std::move(mesh));
      two_sided.push_back(true);
      ids.push_back(static_cast<int>(k));
    }
  }
  const detail::Scene scene =
      detail::draw_scene(meshes, camera, two_sided, ids, options.smooth ? options.edge_angle : -1);
  Image image = shade(scene, camera, options);

  const int width = options.curve_width > 0 ? options.curve_width : 3 * line_width(camera, options);
  const double radius = 0.5 * width;
  CurveBuffer curves{.depth = std::vector<double>(scene.buffer.depth.size(), -std::numeric_limits<double>::infinity()),
                     .item = std::vector<int>(scene.buffer.depth.size(), -1)};
  bool any = false;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (const auto* b = std::get_if<splines::BSpline>(&items[k])) {
      // Segments about 2 pixels long (at most 4096 per span).
      const auto points = sample_spline(*b, [&](double length) {
        return static_cast<int>(std::clamp(std::ceil(0.5 * length * camera.scale), 4.0, 4096.0));
      });
      draw_curve(scene, camera, points, b->closed(), static_cast<int>(k), radius, chord_error, curves);
      any = true;
    } else if (const auto* c = std::get_if<PictureCurve>(&items[k])) {
      draw_curve(scene, camera, c->points, c->closed, static_cast<int>(k), radius, chord_error, curves);
      any = true;
    }
  }
  if (any)
    for (std::size_t i = 0; i < curves.item.size(); ++i)
      if (curves.item[i] >= 0) {
        const auto colour = curve_colour(static_cast<std::size_t>(curves.item[i]));
        std::copy(colour.begin(), colour.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(3 * i));
      }
  return image;
}

Image render_solids(const std::vector<Solid>& solids, const PictureOptions& options) {
  std::vector<PolygonMesh> meshes;
  meshes.reserve(solids.size());
  for (const Solid& s : solids) meshes.push_back(to_mesh(s));
  return render_meshes(meshes, options);
}

}  // namespace sculpt::render
