#pragma once
/// \file picture.hpp
/// Shaded pictures of solids: an orthographic view, each solid in its own colour, flat shading
/// per face, hidden surfaces removed per pixel, and dark lines where faces meet at an angle
/// above a threshold (feature edges) and along silhouettes and occlusion boundaries.
///
/// Hidden surfaces. Each pixel is sampled at its centre: the colour is that of the boundary
/// face nearest the viewer along the pixel's ray. The boundary faces of solids (bsp/boundary.hpp)
/// are convex polygons with disjoint interiors, so along a ray the faces it crosses are met at
/// distinct depths except where faces share an edge or a vertex (where either is right). A
/// z-buffer over the front-facing faces therefore finds, at every pixel centre, the same face a
/// ray cast through the solid's BSP tree finds (first boundary crossing from out to in); the
/// tests check this against the tree (classification of the ray's points) rather than assume it.
/// Coverage is watertight: an edge shared by two faces decides each pixel centre for exactly one
/// of them (the edge function is evaluated in one canonical orientation, ties by the top-left
/// rule), so there are no cracks nor double hits along shared edges.
///
/// Pictures of scenes (render_items): solids, open meshes and B-spline surfaces (shaded on both
/// sides), and curves drawn as lines a few pixels wide, depth-tested against the shaded items.

#include <array>
#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "bsp/solid.hpp"
#include "mesh/polygon_mesh.hpp"
#include "render/camera.hpp"
#include "splines/bspline.hpp"
#include "splines/bspline_surface.hpp"

namespace sculpt::render {

/// An RGB picture, 8 bits per channel, rows top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 * width * height bytes
  [[nodiscard]] std::array<std::uint8_t, 3> pixel(int x, int y) const {
    const std::size_t k = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
};

struct PictureOptions {
  Eigen::Vector3d view{1, -1, 1};  ///< from the scene towards the viewer (view_direction("iso"))
  int width = 800;
  int height = 600;
  /// Pixels per world unit; 0 frames the solids (margin 5 % of each side). With a scale given,
  /// `center` is the world point at the image centre.
  double scale = 0;
  Eigen::Vector3d center{0, 0, 0};
  double edge_angle = 30;          ///< degrees: faces meeting at a larger angle get a line
  bool edges = true;               ///< draw feature edges and silhouettes
  /// Line width in pixels (lines widen into the solids, never onto the background, so they do
  /// not change what is covered); 0: one pixel per 600 pixels of the smaller side, at least 1.
  int line_width = 0;
  std::array<std::uint8_t, 3> background{255, 255, 255};
  /// render_items: the chord error of surfaces' triangle meshes (world units); 0: half a pixel,
  /// 0.5 / scale, with the scale of the picture (framed from a coarse tessellation first).
  double surface_tolerance = 0;
  /// render_items: width of curves in pixels; 0: three times the line width.
  int curve_width = 0;
  /// Smooth shading: curved surfaces made of flat faces shade as curved (each pixel lit with a
  /// normal interpolated from the faces' corners, averaged over faces meeting at no more than
  /// edge_angle); creases above edge_angle stay sharp. Flat shading per face otherwise.
  bool smooth = false;
  /// Antialiasing: the picture is drawn at `antialias` times the size (every length in pixels
  /// scaled alike) and each antialias x antialias block averaged into one pixel. 1: one sample
  /// per pixel, at its centre (the exact pixel bounds the tests check); at most 4.
  int antialias = 1;
};

/// The colour of solid k (a fixed palette, repeating after 8): blue, orange, green, ...
std::array<std::uint8_t, 3> solid_colour(std::size_t k);

/// Largest image side accepted (pixels), and largest pixel count (a picture holds about 16 bytes
/// per pixel while it is made: 512 MiB at this bound).
inline constexpr int kMaxImageSide = 8192;
inline constexpr long long kMaxImagePixels = 1LL << 25;

/// The camera `options` describe for these meshes (framing them when scale is 0).
/// \throw InvalidInput for a bad view, size (1 to kMaxImageSide per side, at most kMaxImagePixels)
///        or scale.
Camera picture_camera(const std::vector<PolygonMesh>& meshes, const PictureOptions& options);
/// The same for points to frame (none: the picture's scale and centre must be given or are 1 and 0).
Camera picture_camera_for_points(const std::vector<Eigen::Vector3d>& points, const PictureOptions& options);

/// Picture of closed boundary meshes (faces convex, counter-clockwise from outside, as
/// to_mesh gives them), mesh k in solid_colour(k).
/// \throw InvalidInput as picture_camera, or for a face index out of range.
Image render_meshes(const std::vector<PolygonMesh>& meshes, const PictureOptions& options = {});

/// A mesh in a picture: closed and oriented (a solid's boundary: back faces culled), or two-sided
/// (an open surface: faces seen from behind are drawn, shaded with the normal turned to the viewer).
struct PictureMesh {
  PolygonMesh mesh;
  bool two_sided = false;
};

/// A polyline in a picture (2D data: z = 0).
struct PictureCurve {
  std::vector<Eigen::Vector3d> points;
  bool closed = false;
};

/// One item of a picture: a mesh, a B-spline surface (tessellated at
/// PictureOptions::surface_tolerance, two-sided), a B-spline curve (sampled so that segments are
/// about 2 pixels long) or a polyline.
using PictureItem = std::variant<PictureMesh, splines::BSplineSurface, splines::BSpline, PictureCurve>;

/// The colour of curve k: solid_colour(k) darkened to 60 %.
std::array<std::uint8_t, 3> curve_colour(std::size_t k);

/// Picture of items, item k in solid_colour(k) (curves in curve_colour(k)). Meshes and surfaces
/// are drawn as in render_meshes. A curve is drawn after them, `curve_width` pixels wide (pixel
/// centres within half the width of its projection), where it is not behind the shaded items:
/// a pixel of a curve point at depth d is drawn if nothing is drawn there or the depth there is at
/// most d + bias, the bias allowing for the curve lying on the surface (the surface's depth change
/// from the curve point to the pixel centre plus one pixel, with faces at most 88.9 degrees from
/// the viewer, plus the chord error and one pixel's length); of several curves at a pixel the
/// nearest wins.
/// \throw InvalidInput as picture_camera, for non-finite points, or a bad surface tolerance.
Image render_items(const std::vector<PictureItem>& items, const PictureOptions& options = {});

/// Picture of solids (their boundaries by to_mesh).
Image render_solids(const std::vector<Solid>& solids, const PictureOptions& options = {});

}  // namespace sculpt::render
