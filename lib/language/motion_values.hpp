#pragma once
/// \file motion_values.hpp
/// Script values of the motions area (builtins_motions.cpp): a surface for curves on surfaces
/// (type "surface") and a designed rigid-body motion (type "motion"), which sweep, carve and add
/// accept in place of a path (builtins_solids.cpp).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "bsp/solid.hpp"
#include "language/value.hpp"
#include "splines/motion.hpp"
#include "splines/surface_curves.hpp"

namespace sculpt::language {

struct ConstraintSurfaceValue final : Object {
  ConstraintSurfaceValue(splines::Surface s, std::string d) : surface(std::move(s)), description(std::move(d)) {}
  splines::Surface surface;
  std::string description;  ///< "sphere centre (0, 0, 0), radius 1"
  [[nodiscard]] std::string type_name() const override { return "surface"; }
  [[nodiscard]] std::string repr() const override { return "<surface: " + description + ">"; }
};

struct MotionValue final : Object {
  explicit MotionValue(splines::MotionResult r) : result(std::move(r)) {}
  splines::MotionResult result;
  [[nodiscard]] std::string type_name() const override { return "motion"; }
  /// "<motion: 4 poses, time [0, 3], 6 splits, rigid to 2.1e-05>"
  [[nodiscard]] std::string repr() const override;
};

/// The poses at which `tool` (in body coordinates: its origin follows the motion) is placed to
/// sweep it along the motion within `tolerance` (splines::sample_motion); `tolerance` <= 0 takes
/// 1 % of the tool's bounding box diagonal. \throw InvalidInput for an empty tool.
std::vector<Eigen::Isometry3d> motion_poses(const MotionValue& motion, const Solid& tool, double tolerance);

}  // namespace sculpt::language
