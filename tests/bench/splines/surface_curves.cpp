// Issue 18's targets for curves on surfaces and motions (docs/motions.md, docs/benchmarks.md
// "Curves on surfaces and motions"): geodesics on the sphere and cylinder against great circles
// and helices, splines on the sphere against the radially projected natural spline, motions
// against interpolating the poses' matrices and projecting, and the bar sweep along a quarter turn
// against the quarter-disk volume. Every figure is measured here, by analytic references and
// dense sampling; times are thread CPU medians of 5 runs.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "bench/bench_timing.hpp"
#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/sweep.hpp"
#include "splines/motion.hpp"
#include "splines/surface_curves.hpp"

using namespace sculpt;
using namespace sculpt::splines;
using V = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

namespace {

double load_average() {
  double l = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &l) != 1) l = 0;
    std::fclose(f);
  }
  return l;
}

struct Speed {
  double spread;  // (max - min) / mean of |c'|
};

Speed speed_spread(const BSpline& c) {
  const auto [a, b] = c.domain();
  double lo = 1e300, hi = 0, sum = 0;
  const int n = 4000;
  for (int k = 0; k <= n; ++k) {
    const double s = c.derivatives(a + (b - a) * k / n, 1)[1].norm();
    lo = std::min(lo, s);
    hi = std::max(hi, s);
    sum += s;
  }
  return {(hi - lo) / (sum / (n + 1))};
}

double simpson_length(const BSpline& c) {
  const auto [a, b] = c.domain();
  const int n = 20000;
  double s = 0;
  for (int k = 0; k <= n; ++k) s += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * c.derivatives(a + (b - a) * k / n, 1)[1].norm();
  return s * (b - a) / n / 3;
}

template <class F>
double max_over(const BSpline& c, F f) {
  const auto [a, b] = c.domain();
  double worst = 0;
  for (int k = 0; k <= 8000; ++k) worst = std::max(worst, f(c.point(a + (b - a) * k / 8000.0)));
  return worst;
}

template <class F>
double bending_fd(double a, double b, F f) {
  const int n = 4000;
  const double h = 1e-4;
  double e = 0;
  for (int k = 0; k <= n; ++k) {
    const double t = std::clamp(a + (b - a) * k / n, a + h, b - h);
    e += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * ((f(t + h) - 2 * f(t) + f(t - h)) / (h * h)).squaredNorm();
  }
  return e * (b - a) / n / 3;
}

V on_sphere(double r, double theta, double phi) {
  return r * V(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

Eigen::Matrix3d turn(double degrees, const V& axis) {
  return Eigen::AngleAxisd(degrees * kPi / 180, axis.normalized()).toRotationMatrix();
}

double rigid_energy_fd(const Motion& m) {
  const auto [a, b] = m.domain();
  const int n = 6000;
  const double h = 1e-4;
  double e = 0;
  for (int k = 0; k <= n; ++k) {
    const double t = std::clamp(a + (b - a) * k / n, a + h, b - h);
    const Eigen::Matrix4d d = (m.rigid(t + h).matrix() - 2 * m.rigid(t).matrix() + m.rigid(t - h).matrix()) / (h * h);
    e += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * d.topLeftCorner<3, 3>().squaredNorm();
  }
  return e * (b - a) / n / 3;
}

double max_rigidity_dense(const Motion& m) {
  const auto [a, b] = m.domain();
  double worst = 0;
  for (int k = 0; k <= 20000; ++k) {
    const Eigen::Matrix3d A = m.affine(a + (b - a) * k / 20000.0).leftCols<3>();
    worst = std::max(worst, (A.transpose() * A - Eigen::Matrix3d::Identity()).norm());
  }
  return worst;
}

}  // namespace

int main() {
  std::printf("load average at start: %.1f\n\n", load_average());

  std::printf("## Geodesics (64 segments)\n\n| surface | case | exact length | relative length error | max distance | speed spread | steps | CPU ms |\n|---|---|---|---|---|---|---|---|\n");
  {
    const double r = 2.0;
    const Surface s = sphere_surface(V::Zero(), r);
    for (double angle : {0.5, 1.5, 2.6, 3.0}) {
      const V p = on_sphere(r, 0.7, 0.2);
      const V axis = p.cross(V(0.2, 1.0, -0.4)).normalized();
      const V q = Eigen::AngleAxisd(angle, axis) * p;
      GeodesicResult g = geodesic(s, p, q);
      const bench::Timing t = bench::median_ms(5, [&] { g = geodesic(s, p, q); });
      const double exact = r * angle;
      std::printf("| sphere r = 2 | arc %.1f rad | %.6f | %.2e | %.2e | %.2e | %d | %.2f |\n", angle, exact,
                  std::abs(simpson_length(g.curve) - exact) / exact,
                  max_over(g.curve, [&](const V& x) { return std::abs(x.norm() - r); }), speed_spread(g.curve).spread,
                  g.iterations, t.cpu);
    }
    const double rc = 0.8;
    const Surface c = cylinder_surface(V::Zero(), V::UnitZ(), rc);
    for (auto [phi, h] : {std::pair{2.5, 1.7}, std::pair{1.0, 4.0}, std::pair{3.0, 0.2}}) {
      const V p(rc, 0, 0), q(rc * std::cos(phi), rc * std::sin(phi), h);
      GeodesicResult g = geodesic(c, p, q);
      const bench::Timing t = bench::median_ms(5, [&] { g = geodesic(c, p, q); });
      const double exact = std::hypot(rc * phi, h);
      std::printf("| cylinder r = 0.8 | helix %.1f rad, rise %.1f | %.6f | %.2e | %.2e | %.2e | %d | %.2f |\n", phi, h, exact,
                  std::abs(simpson_length(g.curve) - exact) / exact,
                  max_over(g.curve, [&](const V& x) { return std::abs(x.head<2>().norm() - rc); }),
                  speed_spread(g.curve).spread, g.iterations, t.cpu);
    }
  }
  std::printf("\nSegments (sphere r = 2, arc 2.6 rad): polygon and spline length errors\n\n| segments | polygon rel. error | spline rel. error | max distance |\n|---|---|---|---|\n");
  {
    const double r = 2.0, angle = 2.6;
    const Surface s = sphere_surface(V::Zero(), r);
    const V p = on_sphere(r, 0.7, 0.2);
    const V q = Eigen::AngleAxisd(angle, p.cross(V(0.2, 1.0, -0.4)).normalized()) * p;
    for (int n : {8, 16, 32, 64, 128}) {
      const GeodesicResult g = geodesic(s, p, q, {.segments = n});
      std::printf("| %d | %.2e | %.2e | %.2e |\n", n, std::abs(g.polygon_length - r * angle) / (r * angle),
                  std::abs(simpson_length(g.curve) - r * angle) / (r * angle),
                  max_over(g.curve, [&](const V& x) { return std::abs(x.norm() - r); }));
    }
  }

  std::printf("\n## Splines on the sphere r = 1.3\n\n| points | splits | through points | max distance | bending ours | bending projected natural | ratio | CPU ms |\n|---|---|---|---|---|---|---|---|\n");
  {
    const double r = 1.3;
    const Surface s = sphere_surface(V::Zero(), r);
    const std::vector<std::vector<V>> sets{
        {on_sphere(r, 0.5, 0.0), on_sphere(r, 1.1, 0.6), on_sphere(r, 1.4, 1.5), on_sphere(r, 0.9, 2.3), on_sphere(r, 1.6, 3.1)},
        {on_sphere(r, 0.3, 0.0), on_sphere(r, 1.5, 0.3), on_sphere(r, 2.6, 1.0), on_sphere(r, 1.5, 2.0), on_sphere(r, 0.4, 3.0),
         on_sphere(r, 1.2, 4.2)}};
    for (const auto& pts : sets)
      for (int splits : {3, 0}) {
        SurfaceSplineOptions o;
        if (splits == 0) o.distance = 1e-4; else o.splits = splits;
        SurfaceSplineResult res = surface_spline(s, pts, o);
        const bench::Timing t = bench::median_ms(5, [&] { res = surface_spline(s, pts, o); });
        double through = 0;
        for (std::size_t j = 0; j < pts.size(); ++j) through = std::max(through, (res.curve.point(res.parameters[j]) - pts[j]).norm());
        const auto [a, b] = res.curve.domain();
        const double ours = bending_fd(a, b, [&](double x) { return res.curve.point(x); });
        const double proj = bending_fd(a, b, [&](double x) -> V { return r * res.start.point(x).normalized(); });
        std::printf("| %zu | %d%s | %.1e | %.2e | %.4f | %.4f | %.3f | %.1f |\n", pts.size(), res.splits,
                    splits == 0 ? " (tol 1e-4)" : "", through,
                    max_over(res.curve, [&](const V& x) { return std::abs(x.norm() - r); }), ours, proj, ours / proj, t.cpu);
      }
  }

  std::printf("\n## Motions\n\n| poses | splits | max A^T A - I (20001 samples) | pose error | energy ours | energy projected | ratio | CPU ms |\n|---|---|---|---|---|---|---|---|\n");
  {
    const std::vector<std::vector<Pose>> cases{
        {{turn(0, V::UnitZ()), V(0, 0, 0)}, {turn(75, V::UnitZ()), V(1, 0, 0)}, {turn(150, V::UnitZ()), V(2, 0, 0)}, {turn(225, V::UnitZ()), V(3, 0, 0)}},
        {{turn(0, V::UnitZ()), V(0, 0, 0)},
         {turn(90, V(1, 1, 0)), V(2, 1, 0)},
         {turn(100, V(0, 1, 1)) * turn(90, V(1, 1, 0)), V(4, 0, 1)},
         {turn(120, V(1, 0, 0)) * turn(80, V(0, 1, 1)), V(5, -2, 1)},
         {turn(-90, V(0, 0, 1)), V(6, 0, 0)}}};
    const char* names[] = {"4, one axis, 75 deg steps", "5, tumbling"};
    for (std::size_t c = 0; c < cases.size(); ++c) {
      MotionResult res = design_motion(cases[c]);
      const bench::Timing t = bench::median_ms(5, [&] { res = design_motion(cases[c]); });
      double pose_error = 0;
      for (std::size_t j = 0; j < cases[c].size(); ++j) {
        const Eigen::Isometry3d P = res.motion.rigid(res.motion.times()[j]);
        pose_error = std::max({pose_error, (P.linear() - cases[c][j].rotation).norm(), (P.translation() - cases[c][j].position).norm()});
      }
      const double ours = rigid_energy_fd(res.motion), proj = rigid_energy_fd(res.start);
      std::printf("| %s | %d | %.2e | %.1e | %.3f | %.3f | %.3f | %.0f |\n", names[c], res.splits, max_rigidity_dense(res.motion),
                  pose_error, ours, proj, ours / proj, t.cpu);
    }
  }

  std::printf("\n## Sweep of a bar [0, 4] x [-0.5, 0.5]^2 turning 90 deg about z (quarter disk + two strips of width 0.5 inside its radius)\n\n| tol | poses | volume | exact | rel. error | CPU ms |\n|---|---|---|---|---|---|\n");
  {
    const double L = 4, w = 0.5, R = std::hypot(L, w);
    const Solid bar = box({0, -w, -w}, {L, w, w});
    const MotionResult res = design_motion({{turn(0, V::UnitZ()), V::Zero()}, {turn(45, V::UnitZ()), V::Zero()}, {turn(90, V::UnitZ()), V::Zero()}});
    const std::vector<V> body = to_mesh(bar).vertices;
    const double strip = 0.5 * (w * L + R * R * std::asin(w / R));  // integral_0^w sqrt(R^2 - y^2) dy
    const double exact = 2 * w * (kPi * R * R / 4 + 2 * strip);
    for (double tol : {0.2, 0.05, 0.02}) {
      std::vector<Eigen::Isometry3d> poses;
      for (double t : sample_motion(res.motion, body, {.tolerance = tol})) poses.push_back(res.motion.rigid(t));
      double vol = 0;
      const bench::Timing t = bench::median_ms(3, [&] { vol = volume(sweep(bar, poses)); });
      std::printf("| %.2f | %zu | %.4f | %.4f | %.2e | %.0f |\n", tol, poses.size(), vol, exact, (vol - exact) / exact, t.cpu);
    }
  }
  std::printf("\nload average at end: %.1f\n", load_average());
}
