// render of the goblet (Ihm & Naylor 1990, Figure 11; scripts/goblet.bsp's solid) at 1024 x 1024,
// the target of issue 17 (at most 100 ms), split into its stages: boundary extraction (to_mesh),
// the picture (z-buffer, lines, shading), PNG encoding, and the atomic file write. Figures are
// median thread CPU times over the runs (the machine is shared), with wall times and the load.
//   render_bench [models-dir] [runs] [out-dir]      (defaults: models, 15, out)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/set_operations.hpp"
#include "curves/digitized_curve.hpp"
#include "curves/profiles.hpp"
#include "render/picture.hpp"
#include "render/png_image.hpp"
#include "bsp/convex_path.hpp"
#include "revolution/revolve.hpp"
#include "bench/bench_timing.hpp"

using namespace sculpt;

namespace {

using bench::median_ms;
using bench::Timing;

std::vector<Eigen::Vector2d> load(const std::string& path) { return curves::planar_points(curves::load_curve(path).points); }

}  // namespace

int main(int argc, char** argv) {
  const std::string models = argc > 1 ? argv[1] : "models";
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 15;
  const std::string out = argc > 3 ? argv[3] : "out";
  double load_avg[3] = {0, 0, 0};

  const ConvexPath path = circular_path(32);
  Solid goblet;
  const Timing build = median_ms(runs, [&] {
    const Solid outer = revolution::revolve(load(models + "/goblet_profile_20.txt"), path);
    const Solid cavity = revolution::revolve(load(models + "/goblet_cavity_profile_12.txt"), path);
    const Solid ball = revolution::revolve(load(models + "/ball_profile_16.txt"), path);
    goblet = (outer - cavity) | ball;
  });
  PolygonMesh mesh;
  const Timing extract = median_ms(runs, [&] { mesh = to_mesh(goblet); });
  std::printf("goblet: %zu boundary faces, %zu vertices\n", mesh.faces.size(), mesh.vertices.size());

  std::printf("%-34s %10s %10s\n", "stage (1024 x 1024 unless said)", "cpu ms", "wall ms");
  std::printf("%-34s %10.2f %10.2f\n", "build the goblet (revolve, - , |)", build.cpu, build.wall);
  std::printf("%-34s %10.2f %10.2f\n", "to_mesh (boundary extraction)", extract.cpu, extract.wall);
  render::Image image;
  for (int side : {512, 1024, 2048}) {
    const render::PictureOptions options{.width = side, .height = side};
    const Timing picture = median_ms(runs, [&] { image = render::render_meshes({mesh}, options); });
    char label[64];
    std::snprintf(label, sizeof label, "picture %d x %d", side, side);
    std::printf("%-34s %10.2f %10.2f\n", label, picture.cpu, picture.wall);
  }
  const render::PictureOptions options{.width = 1024, .height = 1024};
  image = render::render_meshes({mesh}, options);
  std::string png;
  const Timing encode = median_ms(runs, [&] { png = render::encode_png(image); });
  std::printf("%-34s %10.2f %10.2f   (%zu bytes)\n", "encode_png", encode.cpu, encode.wall, png.size());
  const Timing encode_fast = median_ms(runs, [&] { png = render::encode_png(image, {.fast = true}); });
  std::printf("%-34s %10.2f %10.2f   (%zu bytes)\n", "encode_png fast (as :show)", encode_fast.cpu, encode_fast.wall,
              png.size());
  std::filesystem::create_directories(out);
  const Timing whole = median_ms(runs, [&] {
    // What render(goblet, "file.png", size=[1024, 1024]) does on a fresh solid value.
    render::write_png(render::render_meshes({to_mesh(goblet)}, options), out + "/goblet_1024.png");
  });
  const Timing write = median_ms(runs, [&] { render::write_png(image, out + "/goblet_1024.png"); });
  std::printf("%-34s %10.2f %10.2f\n", "write_png (encode, fsync, rename)", write.cpu, write.wall);
  std::printf("%-34s %10.2f %10.2f   target <= 100 ms: %s\n", "render(goblet) total", whole.cpu, whole.wall,
              whole.cpu <= 100 ? "met" : "MISSED");
  const Timing whole_fast = median_ms(runs, [&] {
    render::write_png(render::render_meshes({to_mesh(goblet)}, options), out + "/goblet_1024.png", {.fast = true});
  });
  std::printf("%-34s %10.2f %10.2f\n", "the same, fast PNG (as :show)", whole_fast.cpu, whole_fast.wall);
  std::printf("ratios: total / to_mesh %.2f, total / build %.2f\n", whole.cpu / extract.cpu, whole.cpu / build.cpu);

  // Issue 18: pictures with surfaces and curves (render_items), beside the goblet's picture.
  {
    const double x[3] = {-1, 0, 1}, sq[3] = {1, -1, 1};
    std::vector<Eigen::Vector3d> P;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) P.emplace_back(x[i], x[j], sq[i] + sq[j]);
    const splines::BSplineSurface bowl = splines::BSplineSurface::uniform({2, 2}, 3, 3, P);
    std::vector<Eigen::Vector3d> across, along;
    for (int k = 0; k <= 40; ++k) {
      const double t = -0.9 + 1.8 * k / 40;
      across.emplace_back(t, 0.3, t * t + 0.09);
      along.emplace_back(-0.2, t, 0.04 + t * t);
    }
    const splines::BSpline c1 = splines::BSpline::clamped(3, across), c2 = splines::BSpline::clamped(3, along);
    const Timing goblet_items = median_ms(runs, [&] { image = render::render_items({render::PictureMesh{.mesh = mesh}}, options); });
    const Timing goblet_meshes = median_ms(runs, [&] { image = render::render_meshes({mesh}, options); });
    const Timing surface = median_ms(runs, [&] { image = render::render_items({bowl}, options); });
    const Timing with_curves = median_ms(runs, [&] { image = render::render_items({bowl, c1, c2}, options); });
    std::printf("%-34s %10.2f %10.2f\n", "render_items goblet", goblet_items.cpu, goblet_items.wall);
    std::printf("%-34s %10.2f %10.2f\n", "render_meshes goblet (same run)", goblet_meshes.cpu, goblet_meshes.wall);
    std::printf("%-34s %10.2f %10.2f\n", "paraboloid patch (half a pixel)", surface.cpu, surface.wall);
    std::printf("%-34s %10.2f %10.2f\n", "the patch and two splines on it", with_curves.cpu, with_curves.wall);
    std::printf("ratios: items / meshes (goblet) %.2f, curves' share %.2f\n", goblet_items.cpu / goblet_meshes.cpu,
                (with_curves.cpu - surface.cpu) / with_curves.cpu);
  }
  if (getloadavg(load_avg, 3) == 3) std::printf("load average %.2f %.2f %.2f, %d runs\n", load_avg[0], load_avg[1], load_avg[2], runs);
  return 0;
}
