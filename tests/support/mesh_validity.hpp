#pragma once
/// \file mesh_validity.hpp
/// gtest wrapper of lib/mesh's full validation (closed, manifold, oriented, planar simple faces,
/// no degenerate faces, no self-intersections; see docs/mesh_io.md) for other layers' tests:
///   EXPECT_TRUE(sculpt::checks::ValidSolidMesh(to_mesh(solid)));
/// Link sculpt_mesh. (mesh_checks.hpp is the independent, header-only counterpart.)

#include <gtest/gtest.h>

#include "mesh/mesh_validation.hpp"

namespace sculpt::checks {

inline ::testing::AssertionResult ValidSolidMesh(const PolygonMesh& mesh, ValidationOptions options = {}) {
  const ValidationReport report = check_closed_manifold(mesh, options);
  if (report.ok()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << report.summary(20);
}

}  // namespace sculpt::checks
