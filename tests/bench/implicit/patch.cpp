// Surface patches (Ihm & Naylor sec. 5.2): the sphere octant and Fig. 9's quartic patch at
// depths 0..5. Prints, per depth: vertices, triangles, curves traced, marching steps, the
// largest vertex residual |f|/|grad f| over the corners' box diagonal (target <= 1e-12), the
// largest distance of a triangle centroid from the surface, the shortest and longest edge,
// the area (sphere: its error against pi/2) and the time (median of runs).
//   implicit_patch [--figures DIR]   also writes DIR/fig9_patch_d3.off and DIR/fig9_patch_d3.svg
// See docs/implicit.md, "Surface patches (sec. 5.2)".
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "implicit/patch.hpp"
#include "implicit/patch_testing.hpp"
#include "mesh/mesh_io.hpp"

using namespace sculpt;
using namespace sculpt::implicit;
using Vec = Eigen::Vector3d;

namespace {

struct Case {
  std::string name;
  Expression f;
  std::array<Vec, 3> corners;
  bool sphere = false;
  curves::Method method = curves::Method::Optimal;
};

double median_ms(const Case& c, int depth, int runs, PatchResult& out) {
  std::vector<double> ms;
  for (int run = 0; run < runs; ++run) {
    const auto t0 = std::chrono::steady_clock::now();
    out = patch(c.f, {.corners = c.corners, .depth = depth, .method = c.method});
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

// An orthographic view with painter's order and Lambert shading; boundary edges drawn heavier.
void write_svg(const PatchResult& r, const std::string& path, const std::string& title) {
  const Vec eye = Vec(1.0, 0.75, 1.0).normalized();
  const Vec right = Vec::UnitY().cross(eye).normalized();
  const Vec up = eye.cross(right);
  const auto& V = r.mesh.vertices;
  auto screen = [&](const Vec& p) { return Eigen::Vector2d(p.dot(right), -p.dot(up)); };
  Eigen::AlignedBox2d box;
  for (const Vec& p : V) box.extend(screen(p));
  const double size = 480.0, margin = 20.0, s = size / box.sizes().maxCoeff();
  auto px = [&](const Vec& p) {
    const Eigen::Vector2d q = (screen(p) - box.min()) * s + Eigen::Vector2d::Constant(margin);
    return q;
  };
  std::vector<std::size_t> order(r.mesh.faces.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  auto depth = [&](std::size_t k) {
    const auto& f = r.mesh.faces[k];
    return (V[f[0]] + V[f[1]] + V[f[2]]).dot(eye);
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth(a) < depth(b); });
  std::ofstream out(path);
  const double width = box.sizes().x() * s + 2 * margin, height = box.sizes().y() * s + 2 * margin + 24;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height << "\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (const std::size_t k : order) {
    const auto& f = r.mesh.faces[k];
    const Vec n = (V[f[1]] - V[f[0]]).cross(V[f[2]] - V[f[0]]).normalized();
    const int shade = static_cast<int>(90 + 150 * std::abs(n.dot(Vec(0.3, 1.0, 0.6).normalized())));
    out << "<polygon points=\"";
    for (const int v : f) out << px(V[v]).x() << "," << px(V[v]).y() << " ";
    out << "\" fill=\"rgb(" << shade * 0.75 << "," << shade * 0.85 << "," << shade << ")\" stroke=\"black\" "
        << "stroke-width=\"0.6\" stroke-linejoin=\"round\"/>\n";
  }
  for (const auto& chain : r.boundary) {
    out << "<polyline fill=\"none\" stroke=\"rgb(180,30,30)\" stroke-width=\"2\" points=\"";
    for (const int v : chain) out << px(V[v]).x() << "," << px(V[v]).y() << " ";
    out << "\"/>\n";
  }
  out << "<text x=\"" << margin << "\" y=\"" << height - 8 << "\" font-family=\"sans-serif\" font-size=\"13\">" << title
      << "</text>\n</svg>\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string figures;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--figures") figures = argv[i + 1];
  std::vector<Case> cases;
  cases.push_back({"sphere-octant", testing::unit_sphere(), testing::sphere_octant_corners(), true});
  cases.push_back({"fig9-quartic", testing::fig9_quartic(), testing::fig9_octant_corners(), false});
  cases.push_back({"fig9 (ITER)", testing::fig9_quartic(), testing::fig9_octant_corners(), false, curves::Method::Iter});
  std::printf("| patch | d | vertices | triangles | curves | steps | resid/diag | centroid dist | edge min | edge max | "
              "area error | ms |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    Eigen::AlignedBox3d extent;
    for (const Vec& p : c.corners) extent.extend(p);
    const double diagonal = extent.diagonal().norm();
    for (int d = 0; d <= 5; ++d) {
      PatchResult r;
      const double ms = median_ms(c, d, d <= 3 ? 9 : 5, r);
      double residual = 0.0, centroid = 0.0, area = 0.0, lmin = 1e300, lmax = 0.0;
      for (const Vec& p : r.mesh.vertices) residual = std::max(residual, testing::normalized_residual(c.f, p));
      for (const auto& face : r.mesh.faces) {
        const Vec& a = r.mesh.vertices[face[0]];
        const Vec& b = r.mesh.vertices[face[1]];
        const Vec& e = r.mesh.vertices[face[2]];
        const Vec m = (a + b + e) / 3.0;
        centroid = std::max(centroid, c.sphere ? 1.0 - m.norm() : testing::distance_to_surface(c.f, m));
        area += 0.5 * (b - a).cross(e - a).norm();
        for (const double l : {(b - a).norm(), (e - b).norm(), (a - e).norm()}) {
          lmin = std::min(lmin, l);
          lmax = std::max(lmax, l);
        }
      }
      char area_text[32] = "-";
      if (c.sphere) std::snprintf(area_text, sizeof area_text, "%.2e", std::numbers::pi / 2 - area);
      std::printf("| %s | %d | %zu | %zu | %d | %ld | %.1e | %.2e | %.4f | %.4f | %s | %.2f |\n", c.name.c_str(), d,
                  r.mesh.vertices.size(), r.mesh.faces.size(), r.traced_curves, r.steps, residual / diagonal, centroid,
                  lmin, lmax, area_text, ms);
      if (!figures.empty() && !c.sphere && c.method == curves::Method::Optimal && d == 3) {
        write_mesh(r.mesh, figures + "/fig9_patch_d3.off");
        write_svg(r, figures + "/fig9_patch_d3.svg",
                  "Fig. 9 quartic, positive octant, d = 3: " + std::to_string(r.mesh.faces.size()) + " triangles");
      }
    }
  }
}
