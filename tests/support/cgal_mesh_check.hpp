#pragma once
/// \file cgal_mesh_check.hpp
/// An independent judge of exported meshes (issue 14, "Clean output"): CGAL's polygon mesh
/// processing (Debian's libcgal-dev, a test dependency only) decides whether a mesh is usable by
/// other tools as it is. Only cgal_mesh_check.cpp includes CGAL (slow to compile); callers see
/// plain data. Coordinates are taken as given (doubles, or floats widened): round them to the
/// file format's numbers first to judge what a file holds.
///   EXPECT_TRUE(sculpt::checks::CleanForOtherTools(mesh.vertices, mesh.faces));

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace sculpt::checks {

/// What CGAL says about a polygon mesh given as vertices and faces (counter-clockwise from outside).
struct CgalMeshReport {
  bool polygon_mesh = false;  ///< every edge used at most once per direction, faces simple (CGAL's soup test)
  bool closed = false;        ///< no border edge
  bool outward = false;       ///< closed and oriented outward (CGAL's is_outward_oriented)
  std::size_t duplicate_points = 0;  ///< vertices whose coordinates equal an earlier vertex's
  std::size_t degenerate_faces = 0;  ///< faces of zero area: all corners collinear (exact predicate)
  std::size_t self_intersections = 0;  ///< pairs of triangles that intersect other than along shared
                                       ///< edges or vertices (after CGAL triangulates the faces)
  double volume = 0;          ///< enclosed volume (CGAL, double arithmetic)
  std::string problem;        ///< first problem found, in words; empty if clean

  [[nodiscard]] bool clean() const { return problem.empty(); }
};

/// Runs the checks above (exact predicates, inexact constructions: CGAL's Epick kernel).
CgalMeshReport cgal_check(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::vector<int>>& faces);

/// gtest form: success if CGAL finds the mesh clean, else the first problem.
inline ::testing::AssertionResult CleanForOtherTools(const std::vector<Eigen::Vector3d>& vertices,
                                                     const std::vector<std::vector<int>>& faces) {
  const CgalMeshReport r = cgal_check(vertices, faces);
  if (r.clean()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "CGAL: " << r.problem;
}

}  // namespace sculpt::checks
