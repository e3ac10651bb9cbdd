// Tests of the expression form (lib/implicit/expression.hpp): values and gradients against
// hand-derived formulas, interval bounds against sampled values, and the errors.
#include "implicit/expression.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace sculpt;
using namespace sculpt::implicit;
using Vec = Eigen::Vector3d;

namespace {

// f = x^2 y + sin(z) exp(x) - sqrt(x^2 + y^2 + 1) / (1 + z^2) + |y - 0.3| + min(x, z) max(y, z)
//     + cos(x y) + z^-2, with the shared term x^2 used twice.
Expression mixed_function() {
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  const Term x2 = b.pow(x, 2);
  Term f = b.mul(x2, y);
  f = b.add(f, b.mul(b.sin(z), b.exp(x)));
  const Term root = b.sqrt(b.add(b.add(x2, b.mul(y, y)), b.constant(1.0)));
  f = b.sub(f, b.div(root, b.add(b.constant(1.0), b.mul(z, z))));
  f = b.add(f, b.abs(b.sub(y, b.constant(0.3))));
  f = b.add(f, b.mul(b.min(x, z), b.max(y, z)));
  f = b.add(f, b.cos(b.mul(x, y)));
  f = b.add(f, b.pow(z, -2));
  return b.finish(f);
}

double mixed_value(const Vec& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  return x * x * y + std::sin(z) * std::exp(x) - std::sqrt(x * x + y * y + 1) / (1 + z * z) + std::abs(y - 0.3) +
         std::min(x, z) * std::max(y, z) + std::cos(x * y) + 1.0 / (z * z);
}

// The gradient of mixed_value, derived by hand.
Vec mixed_gradient(const Vec& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  const double r = std::sqrt(x * x + y * y + 1), q = 1 + z * z;
  Vec g(2 * x * y + std::sin(z) * std::exp(x) - x / (r * q) - y * std::sin(x * y),
        x * x - y / (r * q) + (y > 0.3 ? 1.0 : -1.0) - x * std::sin(x * y),
        std::cos(z) * std::exp(x) + r * 2 * z / (q * q) - 2.0 / (z * z * z));
  // min(x, z) max(y, z): the product rule with whichever operand each picks.
  const double mn = std::min(x, z), mx = std::max(y, z);
  const Vec dmin = x <= z ? Vec::UnitX() : Vec::UnitZ();
  const Vec dmax = y >= z ? Vec::UnitY() : Vec::UnitZ();
  return g + mn * dmax + mx * dmin;
}

}  // namespace

TEST(Expression, ValueAndGradientMatchHandDerivedFormulas) {
  const Expression e = mixed_function();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 200; ++k) {
    const Vec p(u(rng), u(rng), u(rng));
    if (std::abs(p.z()) < 0.2 || std::abs(p.y() - 0.3) < 1e-3) continue;  // 1/z^2 and |.| kink
    const double scale = std::max(1.0, std::abs(mixed_value(p)));
    EXPECT_NEAR(e.value(p), mixed_value(p), 1e-13 * scale);
    const ValueGradient vg = e.value_gradient(p);
    EXPECT_NEAR(vg.value, mixed_value(p), 1e-13 * scale);
    const Vec expected = mixed_gradient(p);
    EXPECT_LE((vg.gradient - expected).norm(), 1e-12 * std::max(1.0, expected.norm())) << "at " << p.transpose();
  }
}

TEST(Expression, GradientOfAPolynomialIsExact) {
  // The ellipsoid of Fig. 7: grad = (72x, 162y, 18z), exact in floating point for these points.
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  const Term f = b.sub(b.add(b.add(b.mul(b.constant(36), b.pow(x, 2)), b.mul(b.constant(81), b.pow(y, 2))),
                             b.mul(b.constant(9), b.pow(z, 2))),
                       b.constant(324));
  const Expression e = b.finish(f);
  const ValueGradient vg = e.value_gradient(Vec(1.5, -0.25, 2.0));
  EXPECT_EQ(vg.value, 36 * 2.25 + 81 * 0.0625 + 9 * 4.0 - 324);
  EXPECT_EQ(vg.gradient, Vec(108.0, -40.5, 36.0));
}

TEST(Expression, SharedTermsAreOneNodeAndUnusedNodesAreDropped) {
  ExpressionBuilder b;
  const Term x = b.x();
  const Term s = b.sin(x);
  (void)b.cos(b.y());  // not used by the root
  const Expression e = b.finish(b.mul(s, s));
  EXPECT_EQ(e.size(), 3u);  // x, sin(x), sin(x) * sin(x)
  EXPECT_EQ(e.str(), "(sin(x) * sin(x))");
  EXPECT_NEAR(e.value(Vec(0.5, 9, 9)), std::sin(0.5) * std::sin(0.5), 1e-16);
  EXPECT_EQ(b.x().index, x.index);  // one x node per builder
}

TEST(Expression, IntervalBoundsContainSampledValues) {
  const Expression e = mixed_function();
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  // Even and odd powers, a quotient, trigonometry over wide ranges.
  const Expression poly = b.finish(b.add(b.sub(b.pow(b.sub(x, y), 4), b.pow(z, 3)),
                                         b.div(b.sin(b.mul(b.constant(7), x)), b.add(b.pow(y, 2), b.constant(0.5)))));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0), w(0.0, 2.5);
  for (int k = 0; k < 300; ++k) {
    Box box;
    box.lo = Vec(u(rng), u(rng), u(rng));
    box.hi = box.lo + Vec(w(rng), w(rng), w(rng));
    for (const Expression* ex : {&e, &poly}) {
      const IntervalBounds bounds = ex->bounds(box);
      for (int s = 0; s < 50; ++s) {
        std::uniform_real_distribution<double> ux(box.lo.x(), box.hi.x()), uy(box.lo.y(), box.hi.y()),
            uz(box.lo.z(), box.hi.z());
        const Vec p(ux(rng), uy(rng), uz(rng));
        double v = 0.0;
        try {
          v = ex->value(p);
        } catch (const NonFiniteValue&) {
          continue;  // z = 0 in 1/z^2
        }
        EXPECT_TRUE(bounds.range.contains(v)) << ex->str() << " = " << v << " not in [" << bounds.range.lo << ", "
                                              << bounds.range.hi << "]";
      }
    }
  }
}

TEST(Expression, EvenPowerOfAnIntervalAroundZeroStartsAtZero) {
  ExpressionBuilder b;
  const Expression e = b.finish(b.pow(b.x(), 2));
  const IntervalBounds r = e.bounds({.lo = Vec(-1, 0, 0), .hi = Vec(2, 0, 0)});
  EXPECT_EQ(r.range.lo, 0.0);  // x * x would give [-2, 4]
  EXPECT_GE(r.range.hi, 4.0);
  EXPECT_LE(r.range.hi, 4.0 + 1e-14);
  ExpressionBuilder c;
  const Expression cube = c.finish(c.pow(c.x(), 3));
  const IntervalBounds rc = cube.bounds({.lo = Vec(-1, 0, 0), .hi = Vec(2, 0, 0)});
  EXPECT_LE(rc.range.lo, -1.0);
  EXPECT_GE(rc.range.lo, -1.0 - 1e-14);
}

TEST(Expression, BoundsAreRoundedOutward) {
  // 0.1 + 0.2 is not 0.3 in floating point; the bounds must enclose the exact sum.
  ExpressionBuilder b;
  const Expression e = b.finish(b.add(b.x(), b.constant(0.2)));
  const IntervalBounds r = e.bounds({.lo = Vec(0.1, 0, 0), .hi = Vec(0.1, 0, 0)});
  EXPECT_LT(r.range.lo, 0.1 + 0.2);
  EXPECT_GT(r.range.hi, 0.1 + 0.2);
}

TEST(Expression, DivisionByAnIntervalContainingZeroIsTheWholeLine) {
  ExpressionBuilder b;
  const Expression e = b.finish(b.div(b.constant(1.0), b.x()));
  const IntervalBounds r = e.bounds({.lo = Vec(-1, 0, 0), .hi = Vec(1, 0, 0)});
  EXPECT_EQ(r.range.lo, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.range.hi, std::numeric_limits<double>::infinity());
  const IntervalBounds s = e.bounds({.lo = Vec(0.5, 0, 0), .hi = Vec(2, 0, 0)});
  EXPECT_LE(s.range.lo, 0.5);
  EXPECT_GE(s.range.hi, 2.0);
  EXPECT_LT(s.range.hi, 2.0 + 1e-14);
}

TEST(Expression, SqrtOfANegativeRangeSetsTheDomainFlag) {
  ExpressionBuilder b;
  const Expression e = b.finish(b.sqrt(b.x()));
  EXPECT_FALSE(e.bounds({.lo = Vec(0, 0, 0), .hi = Vec(4, 0, 0)}).domain_error);
  const IntervalBounds r = e.bounds({.lo = Vec(-1, 0, 0), .hi = Vec(4, 0, 0)});
  EXPECT_TRUE(r.domain_error);
  EXPECT_EQ(r.range.lo, 0.0);
  EXPECT_GE(r.range.hi, 2.0);
}

TEST(Expression, NonFiniteValuesAreReportedWithThePoint) {
  ExpressionBuilder b;
  const Expression inverse = b.finish(b.div(b.constant(1.0), b.x()));
  try {
    (void)inverse.value(Vec(0, 1, 2));
    FAIL() << "1/0 must be reported";
  } catch (const NonFiniteValue& e) {
    EXPECT_EQ(e.point(), Vec(0, 1, 2));
  }
  ExpressionBuilder c;
  const Expression root = c.finish(c.sqrt(c.x()));
  EXPECT_THROW((void)root.value(Vec(-1, 0, 0)), NonFiniteValue);
  EXPECT_NO_THROW((void)root.value(Vec(0, 0, 0)));
  EXPECT_THROW((void)root.value_gradient(Vec(0, 0, 0)), NonFiniteValue);  // d sqrt(x) / dx at 0
  ExpressionBuilder d;
  const Expression big = d.finish(d.exp(d.x()));
  EXPECT_THROW((void)big.value(Vec(1000, 0, 0)), NonFiniteValue);
}

TEST(Expression, BadBuilderInputIsRejected) {
  ExpressionBuilder b;
  EXPECT_THROW((void)b.finish(Term{0}), InvalidInput);  // empty builder
  EXPECT_THROW((void)b.constant(std::nan("")), InvalidInput);
  EXPECT_THROW((void)b.sin(Term{5}), InvalidInput);
  const Term x = b.x();
  EXPECT_THROW((void)b.add(x, Term{-1}), InvalidInput);
  const Expression e = b.finish(x);
  EXPECT_THROW((void)e.bounds({.lo = Vec(1, 0, 0), .hi = Vec(0, 0, 0)}), InvalidInput);
}
