#include "curves/appendix_b_curves.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <random>

#include "base/errors.hpp"

namespace sculpt::curves {
namespace {

using Vec = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

struct Info {
  AppendixBCurve which;
  const char* name;
  int paper_points;
  bool closed;
  int dimension;
};

constexpr Info kInfo[] = {
    {AppendixBCurve::Folium, "folium", 109, false, 2},  {AppendixBCurve::Cubic, "cubic", 408, false, 2},
    {AppendixBCurve::Rose, "rose", 400, true, 2},       {AppendixBCurve::Quartic, "quartic", 404, true, 3},
    {AppendixBCurve::Sextic, "sextic", 234, false, 3},  {AppendixBCurve::Helix, "helix", 400, false, 3},
};

const Info& info(AppendixBCurve which) {
  for (const Info& i : kInfo)
    if (i.which == which) return i;
  return kInfo[0];
}

// Point k of n: u in [0, 1] (open curves, both ends included) or [0, 1) (closed curves).
Vec sample(AppendixBCurve which, double u) {
  switch (which) {
    case AppendixBCurve::Folium: {  // loop of x^3 - 3xy + y^3 = 0: t = tan(theta), theta in [0, pi/2]
      const double theta = 0.5 * kPi * u;
      const double s = std::sin(theta), c = std::cos(theta);
      const double d = c * c * c + s * s * s;  // (3t/(1+t^3), 3t^2/(1+t^3)) times cos^3/cos^3
      return {3.0 * s * c * c / d, 3.0 * s * s * c / d, 0.0};
    }
    case AppendixBCurve::Cubic: {
      const double t = -1.0 + 2.0 * u;
      return {t, t * t * t, 0.0};
    }
    case AppendixBCurve::Rose: {  // (x^2 + y^2)^3 = 4 x^2 y^2  <=>  r = sin(2 theta)
      const double theta = 2.0 * kPi * u;
      const double r = std::sin(2.0 * theta);
      return {r * std::cos(theta), r * std::sin(theta), 0.0};
    }
    case AppendixBCurve::Quartic: {  // upper loop of 36x^2+81y^2+9z^2=324 and x^2+y^2=3.94
      const double phi = 2.0 * kPi * u;
      const double r2 = 3.94, r = std::sqrt(r2);
      const double x = r * std::cos(phi), y = r * std::sin(phi);
      const double z = std::sqrt(std::max(0.0, (324.0 - 36.0 * x * x - 81.0 * y * y) / 9.0));
      return {x, y, z};
    }
    case AppendixBCurve::Sextic: {  // y^2 = x^2 + x^3 (x = t^2 - 1, y = t x) on z = x^2 - x + 2
      const double t = -1.25 + 2.5 * u;
      const double x = t * t - 1.0, y = t * x;
      return {x, y, x * x - x + 2.0};
    }
    case AppendixBCurve::Helix: {
      const double t = 6.0 * kPi * u;
      return {std::cos(t), std::sin(t), t / (2.0 * kPi)};
    }
  }
  return Vec::Zero();
}

// Standard normal deviates from a fixed generator and Box-Muller, identical on every platform
// (std::normal_distribution is implementation-defined).
class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : engine_(seed) {}
  double operator()() {
    const double u1 = (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace

const std::vector<AppendixBCurve>& all_appendix_b_curves() {
  static const std::vector<AppendixBCurve> all{AppendixBCurve::Folium,  AppendixBCurve::Cubic,  AppendixBCurve::Rose,
                                          AppendixBCurve::Quartic, AppendixBCurve::Sextic, AppendixBCurve::Helix};
  return all;
}

std::string appendix_b_curve_name(AppendixBCurve which) { return info(which).name; }

std::optional<AppendixBCurve> appendix_b_curve_from_name(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const Info& i : kInfo)
    if (lower == i.name) return i.which;
  return std::nullopt;
}

int paper_point_count(AppendixBCurve which) { return info(which).paper_points; }

DigitizedCurve make_appendix_b_curve(AppendixBCurve which, const AppendixBCurveOptions& options) {
  const Info& about = info(which);
  const int n = options.points == 0 ? about.paper_points : options.points;
  const int minimum = about.closed ? 3 : 2;
  if (n < minimum)
    throw InvalidInput(std::string("test curve '") + about.name + "' needs at least " + std::to_string(minimum) +
                       " points, got " + std::to_string(n));
  if (!(options.noise >= 0.0) || !std::isfinite(options.noise))
    throw InvalidInput("test curve noise must be a finite value >= 0");
  DigitizedCurve curve;
  curve.name = about.name;
  curve.closed = about.closed;
  curve.dimension = about.dimension;
  curve.points.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double u = about.closed ? static_cast<double>(k) / n : static_cast<double>(k) / (n - 1);
    curve.points.push_back(sample(which, u));
  }
  if (options.noise > 0.0) {
    Gaussian gaussian(options.seed);
    for (Vec& p : curve.points)
      for (int c = 0; c < about.dimension; ++c) p[c] += options.noise * gaussian();
    curve.name += "-noisy";
  }
  return curve;
}

}  // namespace sculpt::curves
