// Motion design (Pottmann, Leopoldseder & Hofer 2002, sec. 5.3): rigidity along the whole motion,
// poses met exactly, less energy than interpolating the poses' matrices and projecting.
#include "splines/motion.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "base/errors.hpp"
#include "test_names.hpp"

namespace {

Eigen::Matrix3d turn(double degrees, const V& axis) {
  return Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()).toRotationMatrix();
}

std::vector<Pose> tumbling() {
  return {{turn(0, V::UnitZ()), V(0, 0, 0)},
          {turn(90, V(1, 1, 0)), V(2, 1, 0)},
          {turn(100, V(0, 1, 1)) * turn(90, V(1, 1, 0)), V(4, 0, 1)},
          {turn(120, V(1, 0, 0)) * turn(80, V(0, 1, 1)), V(5, -2, 1)},
          {turn(-90, V(0, 0, 1)), V(6, 0, 0)}};
}

/// max over `n` samples of |A^T A - I|_F computed from the affine map.
double rigidity_of(const Motion& m, int n) {
  const auto [a, b] = m.domain();
  double worst = 0.0;
  for (int k = 0; k <= n; ++k) {
    const Eigen::Matrix3d A = m.affine(a + (b - a) * k / n).leftCols<3>();
    worst = std::max(worst, (A.transpose() * A - Eigen::Matrix3d::Identity()).norm());
  }
  return worst;
}

/// integral |R''|_F^2 + |b''|^2 of the rigid motion by central differences and Simpson's rule.
double energy_of(const Motion& m) {
  const auto [a, b] = m.domain();
  const int n = 6000;
  const double h = 1e-4;
  double e = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double t = std::clamp(a + (b - a) * k / n, a + h, b - h);
    const Eigen::Matrix4d d = (m.rigid(t + h).matrix() - 2 * m.rigid(t).matrix() + m.rigid(t - h).matrix()) / (h * h);
    e += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * (d.topLeftCorner<3, 3>().squaredNorm() + 6 * d.topRightCorner<3, 1>().squaredNorm());
  }
  return e * (b - a) / n / 3.0;
}

}  // namespace

TEST(Motion, NearestRotationUndoesASymmetricStretch) {
  const Eigen::Matrix3d R = turn(70, V(1, 2, 3));
  Eigen::Matrix3d P;
  P << 1.3, 0.2, 0.1, 0.2, 0.9, -0.1, 0.1, -0.1, 1.1;  // symmetric positive definite
  EXPECT_LT((nearest_rotation(R * P) - R).norm(), 1e-12);
  EXPECT_LT((nearest_rotation(R) - R).norm(), 1e-14);
}

TEST(Motion, TumblingBodyIsRigidAndMeetsThePoses) {
  const std::vector<Pose> poses = tumbling();
  const MotionResult res = design_motion(poses);
  EXPECT_TRUE(res.converged);
  EXPECT_LE(rigidity_of(res.motion, 4000), 1e-4);
  EXPECT_LE(res.max_rigidity, 1e-4);
  EXPECT_GT(rigidity_of(res.start, 4000), 1e-2);  // the plain matrix spline is far from rigid
  for (std::size_t j = 0; j < poses.size(); ++j) {
    const double t = res.motion.times()[j];
    const Eigen::Matrix<double, 3, 4> m = res.motion.affine(t);
    EXPECT_LT((m.leftCols<3>() - poses[j].rotation).norm(), 1e-12) << j;
    EXPECT_LT((m.col(3) - poses[j].position).norm(), 1e-12) << j;
    EXPECT_LT((res.motion.rigid(t).linear() - poses[j].rotation).norm(), 1e-12) << j;
  }
  // Less energy than interpolating the poses' matrices and projecting pointwise.
  const double ours = energy_of(res.motion), projected = energy_of(res.start);
  EXPECT_LT(ours, projected);
  EXPECT_NEAR(rigid_energy(res.motion, std::sqrt(0.5), 6000), ours, 1e-3 * ours);  // 2 s^2 = 1
}

TEST(Motion, TurningAboutOneAxisStaysAboutIt) {
  std::vector<Pose> poses;
  for (int j = 0; j < 4; ++j) poses.push_back({turn(75.0 * j, V::UnitZ()), V(j, 0, 0)});
  const MotionResult res = design_motion(poses);
  EXPECT_LE(rigidity_of(res.motion, 2000), 1e-4);
  for (double t = 0; t <= 3.0; t += 0.01) {
    const Eigen::Matrix3d R = res.motion.rigid(t).linear();
    EXPECT_LT((R * V::UnitZ() - V::UnitZ()).norm(), 1e-9) << t;
    EXPECT_NEAR(res.motion.affine(t)(1, 3), 0.0, 1e-12);
  }
}

TEST(Motion, SamplingKeepsEveryVertexNearItsChord) {
  const MotionResult res = design_motion(tumbling());
  const std::vector<V> body{V(-1, -0.5, -0.3), V(1, -0.5, -0.3), V(1, 0.5, -0.3), V(-1, 0.5, -0.3),
                            V(-1, -0.5, 0.3), V(1, -0.5, 0.3), V(1, 0.5, 0.3), V(-1, 0.5, 0.3)};
  const double tol = 0.01;
  const std::vector<double> times = sample_motion(res.motion, body, {.tolerance = tol});
  ASSERT_GE(times.size(), 2u);
  EXPECT_DOUBLE_EQ(times.front(), 0.0);
  EXPECT_DOUBLE_EQ(times.back(), 4.0);
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const auto P0 = res.motion.rigid(times[i]), P1 = res.motion.rigid(times[i + 1]);
    for (int k = 1; k < 40; ++k) {
      const double s = k / 40.0;
      const auto Pt = res.motion.rigid(times[i] + (times[i + 1] - times[i]) * s);
      for (const V& v : body) worst = std::max(worst, (Pt * v - ((1 - s) * (P0 * v) + s * (P1 * v))).norm());
    }
  }
  EXPECT_LE(worst, tol);
  // A coarser tolerance needs fewer steps.
  EXPECT_LT(sample_motion(res.motion, body, {.tolerance = 0.1}).size(), times.size());
}

TEST(Motion, BadInputIsRefused) {
  EXPECT_THROW(design_motion({Pose{}}), InvalidInput);
  Pose skew;
  skew.rotation = Eigen::Matrix3d::Identity() * 1.1;
  EXPECT_THROW(design_motion({Pose{}, skew}), InvalidInput);
  Pose mirror;
  mirror.rotation = Eigen::Vector3d(1, 1, -1).asDiagonal();
  EXPECT_THROW(design_motion({Pose{}, mirror}), InvalidInput);
  EXPECT_THROW(design_motion({Pose{}, Pose{}}, {.times = {1.0, 0.5}}), InvalidInput);
  EXPECT_THROW(design_motion({Pose{}, Pose{}}, {.times = {1.0}}), InvalidInput);
  const MotionResult res = design_motion({Pose{}, Pose{turn(30, V::UnitX()), V(1, 0, 0)}});
  EXPECT_THROW(sample_motion(res.motion, {}), InvalidInput);
  EXPECT_THROW(sample_motion(res.motion, {V::Zero()}, {.tolerance = 0.0}), InvalidInput);
}
