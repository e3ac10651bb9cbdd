// Pictures by invariants (issue 17): areas and exact pixel bounds of known silhouettes, hidden
// solids, determinism, the PNG round trip, and the z-buffer's visible face against a brute-force
// ray cast over the faces and against the BSP tree's classification along the ray.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/sweep.hpp"
#include "bsp/transform.hpp"
#include "render/detail/scene.hpp"
#include "render/picture.hpp"
#include "render/png_image.hpp"
#include "support/scratch_path.hpp"

namespace sculpt::render {
namespace {

/// Pixels that are not the background colour (white), counted on the decoded PNG.
long covered(const Image& image) {
  long n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.pixel(x, y) != std::array<std::uint8_t, 3>{255, 255, 255}) ++n;
  return n;
}

Image through_png(const Image& image) { return decode_png(encode_png(image)); }

TEST(Picture, SphereSilhouetteCoversPiRSquared) {
  // r = 200 px: scale 200 px per unit on a unit sphere; every direction, a polyhedral sphere
  // inscribed in the unit sphere (its silhouette is within the disc and close to it).
  const Solid ball = sphere(1.0, {.segments = 96});
  const double disc = std::numbers::pi * 200 * 200;
  for (const char* view : {"front", "top", "iso", "left"}) {
    const Image image = through_png(render_solids({ball}, {.view = view_direction(view), .width = 480, .height = 480, .scale = 200}));
    const long n = covered(image);
    EXPECT_LT(std::abs(n - disc) / disc, 0.01) << view << ": " << n << " pixels, pi r^2 = " << disc;
    EXPECT_LE(n, disc + 2 * std::numbers::pi * 200 * 0.5) << view;  // inscribed, up to half a pixel of rim
  }
}

TEST(Picture, BoxAlongAnAxisIsARectangleWithExactPixelBounds) {
  // Corners chosen so that no pixel centre lies on an edge: pixel i is covered iff its centre
  // i + 0.5 lies inside the projected rectangle.
  const Solid b = box({-50.75, -30.25, -20.75}, {30.25, 10.75, 40.25});
  struct Case {
    const char* view;
    double x_lo, x_hi, y_lo, y_hi;  // screen rectangle (x right, y down) for center 0, scale 1, 200 x 200
  };
  const Case cases[] = {
      {"front", 100 - 50.75, 100 + 30.25, 100 - 40.25, 100 + 20.75},   // right = x, up = z
      {"back", 100 - 30.25, 100 + 50.75, 100 - 40.25, 100 + 20.75},    // right = -x
      {"right", 100 - 30.25, 100 + 10.75, 100 - 40.25, 100 + 20.75},   // right = y
      {"top", 100 - 50.75, 100 + 30.25, 100 - 10.75, 100 + 30.25},     // right = x, up = y
  };
  for (const Case& c : cases) {
    const Image image = through_png(render_solids({b}, {.view = view_direction(c.view), .width = 200, .height = 200, .scale = 1}));
    long wrong = 0;
    for (int y = 0; y < 200; ++y)
      for (int x = 0; x < 200; ++x) {
        const bool inside = x + 0.5 > c.x_lo && x + 0.5 < c.x_hi && y + 0.5 > c.y_lo && y + 0.5 < c.y_hi;
        const bool drawn = image.pixel(x, y) != std::array<std::uint8_t, 3>{255, 255, 255};
        if (inside != drawn) ++wrong;
      }
    EXPECT_EQ(wrong, 0) << c.view;
  }
}

TEST(Picture, NonConvexFacesAreDrawnWhole) {
  // A block with a groove carved by a ball along a bent path (the groove stays above the floor):
  // seen from the top it covers exactly its rectangle. Its top face around the groove is not
  // convex, and the rasterizer takes convex polygons, so such a face must be split first (before
  // it was, parts of the groove's faces were left out and the background showed through).
  const Solid block = box({-50.25, -30.25, -20}, {50.25, 30.25, 10});
  const std::vector<Eigen::Vector3d> path{{-40, -15, 10}, {0, 5, 10}, {40, -15, 10}};
  const Solid carved = carve(block, sphere(8, {.segments = 16}), path);
  const Image image = through_png(render_solids({carved}, {.view = view_direction("top"), .width = 200, .height = 200, .scale = 1}));
  long wrong = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      const double wx = x + 0.5 - 100, wy = 100 - (y + 0.5);  // top view: right = x, up = y
      const bool inside = std::abs(wx) < 50.25 && std::abs(wy) < 30.25;
      if ((image.pixel(x, y) != std::array<std::uint8_t, 3>{255, 255, 255}) != inside) ++wrong;
    }
  EXPECT_EQ(wrong, 0);
}

TEST(Picture, HiddenSolidDoesNotAppear) {
  const Solid front = box({-2, -2, -2}, {2, 2, 2});
  const Solid behind = box({-1, 5, -1}, {1, 7, 1});  // behind the box seen from the front (-y)
  const PictureOptions options{.view = view_direction("front"), .width = 120, .height = 120, .scale = 20};
  const std::string alone = encode_png(render_solids({front}, options));
  EXPECT_EQ(encode_png(render_solids({front, behind}, options)), alone);
  // The control: seen from the back the small box is in front and shows.
  PictureOptions back = options;
  back.view = view_direction("back");
  EXPECT_NE(encode_png(render_solids({front, behind}, back)), encode_png(render_solids({front}, back)));
}

TEST(Picture, SameCallSameBytes) {
  const Solid s = cylinder(1.0, 2.0, {.segments = 40}) - sphere(0.9, {.segments = 40});
  const std::string a = encode_png(render_solids({s}));
  const std::string b = encode_png(render_solids({s}));
  EXPECT_EQ(a, b);
  // The fast encoding: other bytes, the same pixels, and also the same bytes every time.
  const std::string fast = encode_png(render_solids({s}), {.fast = true});
  EXPECT_EQ(fast, encode_png(render_solids({s}), {.fast = true}));
  EXPECT_EQ(decode_png(fast).rgb, decode_png(a).rgb);
  const auto dir = test::scratch_path("sculpt_render_test");
  std::filesystem::create_directories(dir);
  write_png(render_solids({s}), dir / "a.png");
  const Image back = read_png(dir / "a.png");
  EXPECT_EQ(back.rgb, render_solids({s}).rgb);
  EXPECT_EQ(back.width, 800);
  EXPECT_EQ(back.height, 600);
  std::filesystem::remove_all(dir);
}

TEST(Picture, DefaultFramesTheSolid) {
  // Framed with a 5 % margin: the drawn pixels touch neither border, and fill 90 % of the
  // limiting side to within a pixel.
  const Solid s = box({0, 0, 0}, {1, 2, 3});
  const Image image = render_solids({s});
  int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.pixel(x, y) != std::array<std::uint8_t, 3>{255, 255, 255})
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  ASSERT_GE(x1, 0);
  const double w = x1 - x0 + 1, h = y1 - y0 + 1;
  EXPECT_TRUE(std::abs(w - 0.9 * 800) <= 2 || std::abs(h - 0.9 * 600) <= 2) << w << " x " << h;
  EXPECT_NEAR((x0 + x1 + 1) / 2.0, 400, 1.5);
  EXPECT_NEAR((y0 + y1 + 1) / 2.0, 300, 1.5);
}

TEST(Picture, EmptySolidGivesBackground) {
  const Image image = render_solids({Solid()}, {.width = 10, .height = 8});
  EXPECT_EQ(covered(image), 0);
}

TEST(Picture, BadOptionsAreTypedErrors) {
  const Solid s = box({0, 0, 0}, {1, 1, 1});
  EXPECT_THROW(render_solids({s}, {.width = 0}), InvalidInput);
  EXPECT_THROW(render_solids({s}, {.height = kMaxImageSide + 1}), InvalidInput);
  EXPECT_THROW(render_solids({s}, {.width = kMaxImageSide, .height = kMaxImageSide}), InvalidInput);  // too many pixels
  EXPECT_THROW(render_solids({s}, {.view = {0, 0, 0}}), InvalidInput);
  EXPECT_THROW(render_solids({s}, {.scale = -1}), InvalidInput);
  EXPECT_THROW(render_solids({s}, {.scale = 1e7}), InvalidInput);
  // Far off screen, or much larger than the picture: drawn (or not) without trouble.
  EXPECT_EQ(covered(render_solids({s}, {.width = 20, .height = 20, .scale = 1e6, .center = {-500, 0, 0}})), 0);
  EXPECT_EQ(covered(render_solids({s}, {.width = 20, .height = 20, .scale = 1e6, .center = {0.5, 0.5, 0.5}})), 400);
  EXPECT_THROW(view_direction("sideways"), InvalidInput);
  PolygonMesh bad{.vertices = {{0, 0, 0}}, .faces = {{0, 1, 2}}};
  EXPECT_THROW(render_meshes({bad}), InvalidInput);
  EXPECT_THROW(decode_png("not a png"), IoError);
  EXPECT_THROW(write_png(render_solids({s}, {.width = 4, .height = 4}), "/nonexistent-dir/x.png"), IoError);
}

TEST(Picture, EdgesMarkSilhouettesAndCreasesOnly) {
  // A box seen from iso: three faces at 90 degrees, so lines along the silhouette and the three
  // inner edges; with edge_angle above 90 only the silhouette remains.
  const Solid b = box({-1, -1, -1}, {1, 1, 1});
  const PictureOptions options{.width = 200, .height = 200};
  const Image with = render_solids({b}, options);
  PictureOptions wide = options;
  wide.edge_angle = 120;
  const Image silhouette_only = render_solids({b}, wide);
  PictureOptions none = options;
  none.edges = false;
  const Image plain = render_solids({b}, none);
  auto dark = [](const Image& im) {
    long n = 0;
    for (std::size_t i = 0; i < im.rgb.size(); i += 3) n += im.rgb[i] == 40 && im.rgb[i + 1] == 40 && im.rgb[i + 2] == 48;
    return n;
  };
  EXPECT_EQ(dark(plain), 0);
  EXPECT_GT(dark(silhouette_only), 0);
  EXPECT_GT(dark(with), dark(silhouette_only));
  EXPECT_EQ(covered(with), covered(plain));  // lines never change what is covered
  PictureOptions thick = options;
  thick.line_width = 3;
  const Image thick_lines = render_solids({b}, thick);
  EXPECT_GT(dark(thick_lines), 2 * dark(with));
  EXPECT_EQ(covered(thick_lines), covered(plain));
}

/// Dark line pixels (the line colour) in the picture.
long line_pixels(const Image& im, int margin = 0) {
  long n = 0;
  for (int y = margin; y < im.height - margin; ++y)
    for (int x = margin; x < im.width - margin; ++x) n += im.pixel(x, y) == std::array<std::uint8_t, 3>{40, 40, 48};
  return n;
}

TEST(Picture, CoplanarPiecesMeetingAtTJunctionsDrawNoLine) {
  // The top of a carved block is made of many coplanar pieces whose corners do not match (a
  // corner of one lies on an edge of another). Here: a 2 x 2 square in two rows of two bricks,
  // the rows offset, so the pieces [0, 1.5] x [0, 1] and [0.5, 2] x [1, 2] are neighbours along
  // y = 1 without a common vertex. Seen from the top, only the outline may have lines.
  PolygonMesh top;
  auto quad = [&](double x0, double y0, double x1, double y1) {
    const int k = static_cast<int>(top.vertices.size());
    top.vertices.insert(top.vertices.end(), {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}});
    top.faces.push_back({k, k + 1, k + 2, k + 3});
  };
  quad(0, 0, 1.5, 1);
  quad(1.5, 0, 2, 1);
  quad(0, 1, 0.5, 2);
  quad(0.5, 1, 2, 2);
  const Image image = render_meshes({top}, {.view = {0, 0, 1}, .width = 200, .height = 200});
  EXPECT_GT(covered(image), 150 * 150);
  EXPECT_EQ(line_pixels(image, 20), 0) << "lines inside the square";
  EXPECT_GT(line_pixels(image), 0) << "the outline";
}

/// A flat square [-5, 5]^2 (normal +z) with a square pyramid of base half-width b and height b
/// standing in its middle: four trapezoids around the base and the pyramid's four faces, whose
/// creases with the flat part and each other are at 45 to 71 degrees.
PolygonMesh square_with_pyramid(double b) {
  PolygonMesh m;
  m.vertices = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0},  {-5, 5, 0}, {-b, -b, 0},
                {b, -b, 0},  {b, b, 0},  {-b, b, 0}, {0, 0, b}};
  m.faces = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 8}, {5, 6, 8}, {6, 7, 8}, {7, 4, 8}};
  return m;
}

TEST(Picture, CreasesShorterThanAFewPixelsAreSpecksAndLongerOnesStay) {
  // 20 pixels per unit: a pyramid 0.1 wide covers 2 pixels and its creases are a speck (a sliver
  // of a fine mesh looks like this); one 4 wide shows its creases. Seen from the top the square's
  // outline is the only other line.
  const PictureOptions options{.view = {0, 0, 1}, .width = 200, .height = 200, .scale = 20};
  EXPECT_EQ(line_pixels(render_meshes({square_with_pyramid(0.05)}, options), 10), 0);
  EXPECT_GT(line_pixels(render_meshes({square_with_pyramid(2)}, options), 10), 4 * 40);
}

TEST(Picture, AntialiasingAveragesSamplesAndKeepsTheCoveredArea) {
  // A 2 x 2 square seen from the top at 20.5 pixels per unit, its sides through pixel middles: with
  // one sample per pixel each pixel is the square's colour or white; with 4 x 4 samples the
  // pixels along the sides take colours between, and the covered area (the sum of each pixel's
  // share of the square's colour) stays 2 * 2 * 20.5^2 pixels within the sides' pixels.
  PolygonMesh square{.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, .faces = {{0, 1, 2, 3}}};
  PictureOptions options{
      .view = {0, 0, 1}, .width = 64, .height = 64, .scale = 20.5, .center = {1, 1, 0}, .edges = false};
  const Image sharp = render_meshes({square}, options);
  options.antialias = 4;
  const Image smooth = render_meshes({square}, options);
  ASSERT_EQ(smooth.width, 64);
  ASSERT_EQ(smooth.height, 64);
  const auto face = sharp.pixel(32, 32);
  ASSERT_NE(face[0], 255);
  auto share = [&](const Image& im) {
    double total = 0;
    int between = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const double s = (255.0 - im.pixel(x, y)[0]) / (255.0 - face[0]);
        total += s;
        between += s > 0.05 && s < 0.95;
      }
    return std::pair{total, between};
  };
  const auto [sharp_area, sharp_between] = share(sharp);
  const auto [smooth_area, smooth_between] = share(smooth);
  const double exact = 4 * 20.5 * 20.5;
  EXPECT_EQ(sharp_between, 0);
  EXPECT_GT(smooth_between, 4 * 38);  // the four sides
  EXPECT_NEAR(sharp_area, exact, 4 * 41);
  EXPECT_NEAR(smooth_area, exact, 0.1 * 4 * 41);  // within a tenth of the sides' pixels
  EXPECT_EQ(smooth.pixel(32, 32), face);          // inside, the face's own colour
  options.antialias = 5;
  EXPECT_THROW(render_meshes({square}, options), InvalidInput);
}

TEST(Picture, SmoothShadingFollowsTheTrueSphere) {
  // A 24-segment sphere seen along z at 100 pixels per unit, without lines. At each pixel well
  // inside the outline the true unit sphere's normal is (x, y, sqrt(1 - x^2 - y^2)); lit as the
  // pictures light (0.3 ambient + 0.7 diffuse, light (-0.25, 0.4, 1) normalized), it gives the
  // colour an ideal sphere would have. Smooth shading comes much closer to it than flat shading.
  const PolygonMesh ball = to_mesh(sphere(1.0, {.segments = 24}));
  PictureOptions options{.view = {0, 0, 1}, .width = 240, .height = 240, .scale = 100, .edges = false};
  const Image flat = render_meshes({ball}, options);
  options.smooth = true;
  const Image smooth = render_meshes({ball}, options);
  const Eigen::Vector3d light = Eigen::Vector3d(-0.25, 0.4, 1).normalized();
  const auto base = solid_colour(0);
  double flat_error = 0, smooth_error = 0;
  int n = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 240; ++x) {
      const double wx = (x + 0.5 - 120) / 100, wy = -(y + 0.5 - 120) / 100;
      if (wx * wx + wy * wy > 0.8) continue;
      const Eigen::Vector3d normal(wx, wy, std::sqrt(1 - wx * wx - wy * wy));
      const double ideal = base[2] * (0.3 + 0.7 * std::max(0.0, normal.dot(light)));
      flat_error += std::abs(flat.pixel(x, y)[2] - ideal);
      smooth_error += std::abs(smooth.pixel(x, y)[2] - ideal);
      ++n;
    }
  flat_error /= n;
  smooth_error /= n;
  EXPECT_LT(smooth_error, 0.4 * flat_error) << "flat " << flat_error << ", smooth " << smooth_error;
  EXPECT_LT(smooth_error, 2.0);
  // A box stays flat: its faces meet at 90 degrees, above the crease angle.
  const PolygonMesh cube = to_mesh(box({-1, -1, -1}, {1, 1, 1}));
  PictureOptions iso{.width = 120, .height = 120, .edges = false};
  const Image cube_flat = render_meshes({cube}, iso);
  iso.smooth = true;
  EXPECT_EQ(render_meshes({cube}, iso).rgb, cube_flat.rgb);
}

// ---- the z-buffer against independent references ----

/// The nearest face hit by the ray through pixel (x, y)'s centre, by brute force over the
/// mesh's faces (point in polygon on the face's plane: faces are simple polygons, not always
/// convex, as where coplanar fragments around a hole join); -1 if none. Also returns its depth.
std::pair<int, double> brute_force_hit(const PolygonMesh& mesh, const Camera& camera, int x, int y) {
  const Eigen::Vector3d origin = camera.center + camera.right * ((x + 0.5 - 0.5 * camera.width) / camera.scale) -
                                 camera.up * ((y + 0.5 - 0.5 * camera.height) / camera.scale);
  const Eigen::Vector3d dir = camera.toward;  // depth t: point origin + t * toward
  int best = -1;
  double best_t = -INFINITY;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < face.size(); ++k)
      n += mesh.vertices[face[k]].cross(mesh.vertices[face[(k + 1) % face.size()]]);
    if (n.dot(dir) <= 1e-12 * n.norm()) continue;
    const double t = n.dot(mesh.vertices[face[0]] - origin) / n.dot(dir);
    const Eigen::Vector3d p = origin + t * dir;
    // Crossing number in the projection along the normal's largest coordinate.
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    bool inside = false;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const Eigen::Vector3d& a = mesh.vertices[face[k]];
      const Eigen::Vector3d& b = mesh.vertices[face[(k + 1) % face.size()]];
      if ((a[j] > p[j]) != (b[j] > p[j]) && p[i] < a[i] + (p[j] - a[j]) / (b[j] - a[j]) * (b[i] - a[i]))
        inside = !inside;
    }
    if (inside && t > best_t) best = static_cast<int>(f), best_t = t;
  }
  return {best, best_t};
}

TEST(Picture, VisibleFaceMatchesRayCastAndTree) {
  // A cup with a ball in it: concave, with faces hiding others. Pixels next to a different face
  // (where the centre may be within rounding of an edge) are skipped for the face identity.
  const Solid cup = (cylinder(1.0, 1.5, {.segments = 24}) - translate(cylinder(0.8, 1.5, {.segments = 24}), {0, 0, 0.2})) |
                    translate(sphere(0.5, {.segments = 16}), {0.2, 0.1, 0.9});
  const PolygonMesh mesh = to_mesh(cup);
  for (const char* view : {"iso", "top", "front"}) {
    const Camera camera = picture_camera({mesh}, {.view = view_direction(view), .width = 160, .height = 120});
    const detail::Scene scene = detail::draw_scene({mesh}, camera);
    const auto& buffer = scene.buffer;
    int compared = 0, tree_checked = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const std::size_t i = buffer.index(x, y);
        bool interior = true;
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < camera.width && v < camera.height && buffer.face[buffer.index(u, v)] != buffer.face[i])
            interior = false;
        }
        const auto [hit, t] = brute_force_hit(mesh, camera, x, y);
        const int drawn = buffer.face[i] < 0 ? -1 : scene.faces[static_cast<std::size_t>(buffer.face[i])].face;
        if (interior) {
          ++compared;
          ASSERT_EQ(drawn, hit) << view << " pixel " << x << ", " << y;
        } else {
          // Near an edge: both agree on whether something is hit at (nearly) this depth.
          if (hit >= 0 && drawn >= 0) {
            EXPECT_NEAR(buffer.depth[i], t, 1e-6) << view << " pixel " << x << ", " << y;
          }
        }
        // The tree: just in front of the visible surface is outside the solid, just behind is
        // inside (Ihm & Naylor sec. 6's point classification, exact predicates; 1e-3 is ~30 grid steps,
        // faces within 78 degrees of facing the viewer).
        if (interior && drawn >= 0 && (x + y) % 5 == 0 &&
            scene.faces[static_cast<std::size_t>(buffer.face[i])].normal.dot(camera.toward) > 0.2) {
          const Eigen::Vector3d origin = camera.center +
                                         camera.right * ((x + 0.5 - 0.5 * camera.width) / camera.scale) -
                                         camera.up * ((y + 0.5 - 0.5 * camera.height) / camera.scale);
          const Eigen::Vector3d p = origin + buffer.depth[i] * camera.toward;
          EXPECT_EQ(classify(cup, p + 1e-3 * camera.toward).location, Location::Outside) << view << " " << x << "," << y;
          EXPECT_EQ(classify(cup, p - 1e-3 * camera.toward).location, Location::Inside) << view << " " << x << "," << y;
          ++tree_checked;
        }
      }
    EXPECT_GT(compared, 2000) << view;
    EXPECT_GT(tree_checked, 100) << view;
  }
}

}  // namespace
}  // namespace sculpt::render
