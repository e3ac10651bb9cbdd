#include "render/picture.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"
#include "render/detail/edges.hpp"
#include "render/detail/rasterizer.hpp"
#include "render/detail/scene.hpp"

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

Camera picture_camera(const std::vector<PolygonMesh>& meshes, const PictureOptions& options) {
  if (options.width < 1 || options.width > kMaxImageSide || options.height < 1 || options.height > kMaxImageSide)
    throw InvalidInput("render: the picture size must be 1 to " + std::to_string(kMaxImageSide) + " pixels per side");
  if (static_cast<long long>(options.width) * options.height > kMaxImagePixels)
    throw InvalidInput("render: the picture may have at most " + std::to_string(kMaxImagePixels) + " pixels");
  if (!std::isfinite(options.scale) || options.scale < 0 || options.scale > 1e6)
    throw InvalidInput("render: the scale must be 0 to 10^6 pixels per unit (0: frame the solids)");
  if (!options.center.allFinite()) throw InvalidInput("render: the centre must be finite");
  if (!std::isfinite(options.edge_angle)) throw InvalidInput("render: the edge angle must be finite");
  if (options.line_width < 0 || options.line_width > 64) throw InvalidInput("render: the line width must be 0 to 64");
  for (const PolygonMesh& mesh : meshes) check_faces(mesh);
  Camera camera = orient_camera(options.view);
  camera.width = options.width;
  camera.height = options.height;
  if (options.scale > 0) {
    camera.scale = options.scale;
    camera.center = options.center;
  } else {
    std::vector<Eigen::Vector3d> points;
    for (const PolygonMesh& mesh : meshes)
      for (const auto& face : mesh.faces)
        for (int v : face) points.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
    frame_points(camera, points);
  }
  return camera;
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

Scene draw_scene(const std::vector<PolygonMesh>& meshes, const Camera& camera) {
  Scene scene{.buffer = DepthBuffer(camera.width, camera.height), .faces = {}};
  ScreenPolygon polygon;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const PolygonMesh& mesh = meshes[m];
    std::vector<Eigen::Vector3d> screen(mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) screen[v] = camera.project(mesh.vertices[v]);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& face = mesh.faces[f];
      if (face.size() < 3) continue;
      const Eigen::Vector3d n = newell_normal(mesh, face);
      const double length = n.norm();
      if (!(length > 0)) continue;
      const Eigen::Vector3d unit = n / length;
      // Back faces are never the nearest boundary of a closed solid; faces seen edge-on cover no
      // pixel centre's ray in their interior.
      const double nz = unit.dot(camera.toward);
      if (!(nz > 1e-12)) continue;
      // Depth plane on screen: a world point p = center + right (x - w/2) / s - up (y - h/2) / s
      // + toward t lies on the face's plane n . (p - p0) = 0.
      const Eigen::Vector3d& p0 = mesh.vertices[static_cast<std::size_t>(face[0])];
      const double nr = unit.dot(camera.right), nu = unit.dot(camera.up);
      polygon.dx = -nr / (camera.scale * nz);
      polygon.dy = nu / (camera.scale * nz);
      polygon.d0 = unit.dot(p0 - camera.center) / nz - polygon.dx * 0.5 * camera.width - polygon.dy * 0.5 * camera.height;
      polygon.id = static_cast<int>(scene.faces.size());
      FaceInfo info{.solid = static_cast<int>(m), .face = static_cast<int>(f), .normal = unit, .vertices = face};
      std::sort(info.vertices.begin(), info.vertices.end());
      scene.faces.push_back(std::move(info));
      // The rasterizer takes convex polygons; a boundary face of a set operation's result is often
      // not convex (a face around a groove): it is drawn as the triangles of its exact ear
      // clipping, all with the face's id, which share their edges watertightly.
      if (convex_on_screen(screen, face)) {
        polygon.corners.clear();
        for (int v : face) polygon.corners.emplace_back(screen[static_cast<std::size_t>(v)].head<2>());
        rasterize(scene.buffer, polygon);
      } else {
        for (const IndexTriangle& t : triangulate_polygon(mesh.vertices, face)) {
          polygon.corners.clear();
          for (int v : t) polygon.corners.emplace_back(screen[static_cast<std::size_t>(v)].head<2>());
          rasterize(scene.buffer, polygon);
        }
      }
    }
  }
  return scene;
}

}  // namespace detail

Image render_meshes(const std::vector<PolygonMesh>& meshes, const PictureOptions& options) {
  const Camera camera = picture_camera(meshes, options);
  const detail::Scene scene = detail::draw_scene(meshes, camera);
  const DepthBuffer& buffer = scene.buffer;
  const std::vector<FaceInfo>& faces = scene.faces;

  // Flat shading: a light a little above and left of the viewer, plus ambient light (the three
  // visible sides of a box seen from "iso" get about 0.87, 0.68 and 0.45 of the full colour).
  const Eigen::Vector3d light = (camera.toward + 0.4 * camera.up - 0.25 * camera.right).normalized();
  std::vector<std::array<std::uint8_t, 3>> shade(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const double intensity = 0.3 + 0.7 * std::max(0.0, faces[f].normal.dot(light));
    const auto base = solid_colour(static_cast<std::size_t>(faces[f].solid));
    for (int c = 0; c < 3; ++c)
      shade[f][static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround(base[static_cast<std::size_t>(c)] * intensity));
  }
  std::vector<bool> lines;
  if (options.edges)
    lines = detail::edge_pixels(buffer, faces, std::cos(options.edge_angle * std::numbers::pi / 180));
  const int width = options.line_width > 0
                        ? options.line_width
                        : std::max(1, static_cast<int>(std::lround(std::min(camera.width, camera.height) / 600.0)));
  if (!lines.empty() && width > 1) lines = detail::widen_lines(buffer, lines, width);

  Image image{.width = camera.width, .height = camera.height, .rgb = {}};
  image.rgb.resize(3 * buffer.face.size());
  for (std::size_t i = 0; i < buffer.face.size(); ++i) {
    const int f = buffer.face[i];
    const auto& colour = f < 0 ? options.background : (!lines.empty() && lines[i]) ? kLine : shade[static_cast<std::size_t>(f)];
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
