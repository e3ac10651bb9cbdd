// Pictures of scenes with surfaces and curves (issue 18), by invariants: a curve on the far side
// of a sphere is hidden and the same curve mirrored to the near side is drawn (pixel colours at
// projected points), a B-spline surface's outline against its analytic outline, open surfaces
// drawn from both sides, each curve in its own colour, the same call giving the same bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "render/camera.hpp"
#include "render/picture.hpp"
#include "render/png_image.hpp"

namespace sculpt::render {
namespace {

using V = Eigen::Vector3d;
using Rgb = std::array<std::uint8_t, 3>;

// z = x^2 + y^2 over [-1, 1]^2 as a biquadratic Bezier patch (x = 2u - 1, y = 2v - 1; x^2 has
// Bernstein coefficients 1, -1, 1), as in tests/splines/surface_shapes.hpp.
splines::BSplineSurface paraboloid() {
  const double x[3] = {-1, 0, 1}, sq[3] = {1, -1, 1};
  std::vector<V> P;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P.emplace_back(x[i], x[j], sq[i] + sq[j]);
  return splines::BSplineSurface::uniform({2, 2}, 3, 3, P);
}

/// The circle of radius 0.6 around the y axis at y = side * 0.8: on the unit sphere; both sides
/// project to the same circle seen along y.
PictureCurve latitude(double side, int n = 200) {
  PictureCurve c{.points = {}, .closed = true};
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    c.points.emplace_back(0.6 * std::cos(t), side * 0.8, 0.6 * std::sin(t));
  }
  return c;
}

/// The camera render_items uses for these options (scale and centre given).
Camera camera_of(const PictureOptions& o) { return picture_camera_for_points({}, o); }

/// Pixels of `image` in `colour`.
long count_colour(const Image& image, const Rgb& colour) {
  long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.pixel(x, y) == colour;
  return n;
}

TEST(ItemsPicture, CurveOnTheFarSideOfASphereIsHiddenOnTheNearSideDrawn) {
  const PolygonMesh ball = to_mesh(sphere(1.0, {.segments = 64}));
  const PictureOptions options{.view = view_direction("front"), .width = 200, .height = 200, .scale = 80};
  const Camera camera = camera_of(options);
  const Image near = render_items({PictureMesh{.mesh = ball}, latitude(-1)}, options);
  const Image far = render_items({PictureMesh{.mesh = ball}, latitude(+1)}, options);
  const Image alone = render_items({PictureMesh{.mesh = ball}}, options);
  const Rgb curve = curve_colour(1);
  int checked = 0;
  for (const V& p : latitude(-1, 40).points) {
    const V s = camera.project(p);
    const int x = static_cast<int>(std::floor(s.x())), y = static_cast<int>(std::floor(s.y()));
    EXPECT_EQ(near.pixel(x, y), curve) << x << ", " << y;
    EXPECT_NE(far.pixel(x, y), curve) << x << ", " << y;
    ++checked;
  }
  EXPECT_EQ(checked, 40);
  // Hidden entirely: the far curve leaves the sphere's picture as it is; the near one is a ring
  // about 3 pixels wide and 2 pi 0.6 * 80 = 302 pixels long.
  EXPECT_EQ(far.rgb, alone.rgb);
  const long ring = count_colour(near, curve);
  EXPECT_GT(ring, 3 * 302 * 0.8);
  EXPECT_LT(ring, 3 * 302 * 1.25);
}

TEST(ItemsPicture, CurveBehindAnOpenSurfaceIsHiddenInFrontDrawn) {
  // The paraboloid seen from the top: a curve 0.1 above it is drawn, one 0.1 below is hidden;
  // from the bottom (the surface seen from behind: two-sided) the other way round. The curves
  // are apart on screen (y = 0.3 and -0.3), so neither hides the other.
  const PictureOptions options{.view = view_direction("top"), .width = 240, .height = 240, .scale = 100,
                               .center = {0, 0, 1}};
  const Camera camera = camera_of(options);
  PictureCurve above, below;
  for (int k = 0; k <= 50; ++k) {
    const double x = -0.8 + 1.6 * k / 50, y = 0.3;
    above.points.emplace_back(x, y, x * x + y * y + 0.1);
    below.points.emplace_back(x, -y, x * x + y * y - 0.1);
  }
  const Image picture = render_items({paraboloid(), above, below}, options);
  EXPECT_GT(count_colour(picture, curve_colour(1)), 0);
  EXPECT_EQ(count_colour(picture, curve_colour(2)), 0);
  for (const V& p : above.points) {
    const V s = camera.project(p);
    EXPECT_EQ(picture.pixel(static_cast<int>(s.x()), static_cast<int>(s.y())), curve_colour(1));
  }
  PictureOptions under = options;
  under.view = view_direction("bottom");
  const Image from_below = render_items({paraboloid(), above, below}, under);
  EXPECT_EQ(count_colour(from_below, curve_colour(1)), 0);
  EXPECT_GT(count_colour(from_below, curve_colour(2)), 0);
  // The surface alone, from below, covers the square too (drawn from behind).
  const Image underside = render_items({paraboloid()}, under);
  EXPECT_NEAR(static_cast<double>(240 * 240 - count_colour(underside, {255, 255, 255})), 200.0 * 200.0, 4 * 200.0);
}

TEST(ItemsPicture, SurfaceOutlineMatchesTheAnalyticOutline) {
  // Seen from the front (along +y), z = x^2 + y^2 over [-1, 1]^2 covers x^2 <= z <= x^2 + 1 for
  // |x| <= 1, every column without gaps from the lower to the upper outline.
  const double scale = 100;
  const PictureOptions options{.view = view_direction("front"), .width = 240, .height = 260, .scale = scale,
                               .center = {0, 0, 1}, .edges = false};
  const Camera camera = camera_of(options);
  ASSERT_NEAR(camera.right.x(), 1, 1e-15);
  const Image image = render_items({paraboloid()}, options);
  const Rgb background{255, 255, 255};
  int columns = 0;
  for (int x = 0; x < image.width; ++x) {
    const double wx = (x + 0.5 - 0.5 * image.width) / scale;
    if (std::abs(wx) > 0.98) continue;
    int top = -1, bottom = -1;
    for (int y = 0; y < image.height; ++y)
      if (image.pixel(x, y) != background) {
        if (top < 0) top = y;
        bottom = y;
      }
    ASSERT_GE(top, 0) << x;
    for (int y = top; y <= bottom; ++y) ASSERT_NE(image.pixel(x, y), background) << "gap at " << x << ", " << y;
    const double z_top = wx * wx + 1, z_bottom = wx * wx;
    const double y_top = 0.5 * image.height - scale * (z_top - 1), y_bottom = 0.5 * image.height - scale * (z_bottom - 1);
    EXPECT_NEAR(top, y_top, 2.0) << x;
    EXPECT_NEAR(bottom + 1, y_bottom, 2.0) << x;
    ++columns;
  }
  EXPECT_GT(columns, 190);
  // From the top the outline is the square [-1, 1]^2: 200 x 200 pixels, to a pixel along each side.
  const Image top = render_items({paraboloid()}, {.view = view_direction("top"), .width = 240, .height = 240,
                                                  .scale = scale, .center = {0, 0, 1}});
  const long covered = 240 * 240 - count_colour(top, background);
  EXPECT_NEAR(static_cast<double>(covered), 200.0 * 200.0, 4 * 200.0);
}

TEST(ItemsPicture, EachCurveInItsOwnColourAndTheSameCallGivesTheSameBytes) {
  splines::BSpline arc = splines::BSpline::clamped(3, {{-1, 0, 0}, {-0.3, 0, 1}, {0.3, 0, 1}, {1, 0, 0}});
  PictureCurve line{.points = {{-1, 0, -0.5}, {1, 0, -0.5}}};
  const std::vector<PictureItem> items = {arc, line, paraboloid()};
  const PictureOptions options{.view = view_direction("front"), .width = 160, .height = 120};
  const Image a = render_items(items, options);
  const Image b = render_items(items, options);
  EXPECT_EQ(encode_png(a), encode_png(b));
  EXPECT_GT(count_colour(a, curve_colour(0)), 100);
  EXPECT_GT(count_colour(a, curve_colour(1)), 100);
  EXPECT_NE(curve_colour(0), curve_colour(1));
  // Framing takes the curves in: the arc's top and the line's ends are inside the picture.
  EXPECT_EQ(render_items({arc}, options).width, 160);
}

TEST(ItemsPicture, BadInputIsAnError) {
  EXPECT_THROW(render_items({PictureCurve{.points = {{0, 0, NAN}}}}), InvalidInput);
  EXPECT_THROW(render_items({paraboloid()}, {.surface_tolerance = -1}), InvalidInput);
  EXPECT_THROW(render_items({paraboloid()}, {.curve_width = 100}), InvalidInput);
  PolygonMesh bad;
  bad.vertices = {{0, 0, 0}};
  bad.faces = {{0, 1, 2}};
  EXPECT_THROW(render_items({PictureMesh{.mesh = bad}}), InvalidInput);
  // Nothing to draw: an empty picture, no error.
  EXPECT_EQ(render_items({}, {.width = 10, .height = 10}).rgb.size(), 300u);
}

}  // namespace
}  // namespace sculpt::render
