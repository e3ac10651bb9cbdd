#pragma once
/// \file mesh_checks.hpp
/// GoogleTest checkers for polygon meshes, shared by the layers' tests (header-only).
/// They are written independently of lib/mesh (plain maps, long double sums) so they can
/// check it too. Each returns an AssertionResult that says what is wrong and where:
///   EXPECT_TRUE(sculpt::checks::EdgesManifoldAndOriented(mesh));
///   EXPECT_TRUE(sculpt::checks::VolumeNear(mesh, 1.0, 1e-12));

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::checks {

inline std::string describe(const PolygonMesh& m, int v) {
  std::ostringstream s;
  s.precision(17);
  s << "vertex " << v;
  if (v >= 0 && static_cast<size_t>(v) < m.vertices.size())
    s << " (" << m.vertices[v].x() << ", " << m.vertices[v].y() << ", " << m.vertices[v].z() << ")";
  return s.str();
}

/// Every face has >= 3 corners and valid indices.
inline ::testing::AssertionResult IndicesValid(const PolygonMesh& m) {
  for (size_t f = 0; f < m.faces.size(); ++f) {
    if (m.faces[f].size() < 3)
      return ::testing::AssertionFailure() << "face " << f << " has " << m.faces[f].size() << " corners";
    for (int v : m.faces[f])
      if (v < 0 || static_cast<size_t>(v) >= m.vertices.size())
        return ::testing::AssertionFailure() << "face " << f << " refers to vertex " << v << " of "
                                             << m.vertices.size();
  }
  return ::testing::AssertionSuccess();
}

/// Every undirected edge is used by exactly two faces, once in each direction
/// (closed, 2-manifold along edges, consistently oriented).
inline ::testing::AssertionResult EdgesManifoldAndOriented(const PolygonMesh& m) {
  if (auto r = IndicesValid(m); !r) return r;
  std::map<std::pair<int, int>, std::vector<int>> directed;  // (from, to) -> faces
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (size_t k = 0; k < m.faces[f].size(); ++k) {
      const int a = m.faces[f][k], b = m.faces[f][(k + 1) % m.faces[f].size()];
      if (a == b) return ::testing::AssertionFailure() << "face " << f << " repeats " << describe(m, a);
      directed[{a, b}].push_back(static_cast<int>(f));
    }
  for (const auto& [edge, faces] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    const size_t n_back = back == directed.end() ? 0 : back->second.size();
    if (faces.size() != 1 || n_back != 1)
      return ::testing::AssertionFailure()
             << "edge " << describe(m, edge.first) << " -> " << describe(m, edge.second) << " is used "
             << faces.size() << " time(s) this way (first by face " << faces[0] << ") and " << n_back
             << " time(s) the other way (expected 1 and 1)";
  }
  return ::testing::AssertionSuccess();
}

/// Every vertex has one fan: going around it from face to face across shared edges visits all of
/// its corners (no two sheets share a vertex). \pre EdgesManifoldAndOriented(m).
inline ::testing::AssertionResult VerticesManifold(const PolygonMesh& m) {
  if (auto r = EdgesManifoldAndOriented(m); !r) return r;
  // For each directed edge a -> b: the face using it and the position of a in that face.
  std::map<std::pair<int, int>, std::pair<int, int>> by_edge;
  std::vector<int> corners(m.vertices.size(), 0);
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (size_t k = 0; k < m.faces[f].size(); ++k) {
      const int a = m.faces[f][k], b = m.faces[f][(k + 1) % m.faces[f].size()];
      by_edge[{a, b}] = {static_cast<int>(f), static_cast<int>(k)};
      ++corners[static_cast<size_t>(a)];
    }
  std::vector<int> seen(m.vertices.size(), 0);
  std::vector<bool> started(m.vertices.size(), false);
  for (const auto& [edge, start] : by_edge) {
    const int v = edge.first;
    if (started[static_cast<size_t>(v)]) continue;
    started[static_cast<size_t>(v)] = true;
    // Walk the fan: from the corner at v in face f (outgoing edge v -> w), cross to the face
    // using w -> v, whose corner at v follows that edge.
    std::pair<int, int> at = start;
    do {
      ++seen[static_cast<size_t>(v)];
      const auto& face = m.faces[static_cast<size_t>(at.first)];
      const int w = face[(static_cast<size_t>(at.second) + 1) % face.size()];
      const auto& other = by_edge.at({w, v});
      const auto& of = m.faces[static_cast<size_t>(other.first)];
      at = {other.first, static_cast<int>((static_cast<size_t>(other.second) + 1) % of.size())};
    } while (at != start && seen[static_cast<size_t>(v)] <= corners[static_cast<size_t>(v)]);
    if (seen[static_cast<size_t>(v)] != corners[static_cast<size_t>(v)])
      return ::testing::AssertionFailure() << "vertex " << describe(m, v) << " has " << corners[static_cast<size_t>(v)]
                                           << " corners but its fan through face " << start.first << " has "
                                           << seen[static_cast<size_t>(v)] << " (two sheets share it)";
  }
  return ::testing::AssertionSuccess();
}

/// V - E + F, V = referenced vertices, E = distinct undirected edges.
inline int reference_euler_characteristic(const PolygonMesh& m) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (const auto& f : m.faces)
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      vertices.insert(a);
      edges.insert(std::minmax(a, b));
    }
  return static_cast<int>(vertices.size()) - static_cast<int>(edges.size()) + static_cast<int>(m.faces.size());
}

/// Connected components of faces (through shared vertex indices).
inline int reference_component_count(const PolygonMesh& m) {
  std::vector<int> parent(m.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& f : m.faces)
    for (int v : f) parent[find(v)] = find(f[0]);
  std::set<int> roots;
  for (const auto& f : m.faces) roots.insert(find(f[0]));
  return static_cast<int>(roots.size());
}

inline ::testing::AssertionResult EulerCharacteristicIs(const PolygonMesh& m, int expected) {
  if (auto r = IndicesValid(m); !r) return r;
  const int chi = reference_euler_characteristic(m);
  if (chi != expected)
    return ::testing::AssertionFailure() << "Euler characteristic " << chi << ", expected " << expected;
  return ::testing::AssertionSuccess();
}

/// Closed orientable surface with `components` components of total genus `genus`:
/// chi = 2 * components - 2 * genus. Checks edges first.
inline ::testing::AssertionResult GenusIs(const PolygonMesh& m, int genus, int components = 1) {
  if (auto r = EdgesManifoldAndOriented(m); !r) return r;
  const int c = reference_component_count(m);
  if (c != components)
    return ::testing::AssertionFailure() << c << " components, expected " << components;
  const int chi = reference_euler_characteristic(m);
  if (chi != 2 * components - 2 * genus)
    return ::testing::AssertionFailure() << "Euler characteristic " << chi << " means genus "
                                         << (2 * c - chi) / 2.0 << ", expected " << genus;
  return ::testing::AssertionSuccess();
}

/// No two vertices have exactly the same coordinates.
inline ::testing::AssertionResult NoDuplicateVertices(const PolygonMesh& m) {
  std::map<std::tuple<double, double, double>, int> seen;
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    const auto key = std::make_tuple(m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z());
    const auto [it, inserted] = seen.emplace(key, static_cast<int>(v));
    if (!inserted)
      return ::testing::AssertionFailure() << describe(m, static_cast<int>(v)) << " duplicates vertex "
                                           << it->second;
  }
  return ::testing::AssertionSuccess();
}

/// Area of a polygon face: half the norm of its Newell normal (long double).
inline long double reference_face_area(const PolygonMesh& m, const std::vector<int>& f) {
  long double n[3] = {0, 0, 0};
  for (size_t k = 0; k < f.size(); ++k) {
    const auto& a = m.vertices[f[k]];
    const auto& b = m.vertices[f[(k + 1) % f.size()]];
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      n[i] += (static_cast<long double>(a[j]) - b[j]) * (static_cast<long double>(a[l]) + b[l]);
    }
  }
  return 0.5L * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/// No face repeats a vertex index, and every face's area exceeds `min_area`.
inline ::testing::AssertionResult NoDegenerateFaces(const PolygonMesh& m, double min_area = 0) {
  if (auto r = IndicesValid(m); !r) return r;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    std::set<int> corners(m.faces[f].begin(), m.faces[f].end());
    if (corners.size() != m.faces[f].size())
      return ::testing::AssertionFailure() << "face " << f << " repeats a vertex";
    const long double area = reference_face_area(m, m.faces[f]);
    if (!(area > min_area))
      return ::testing::AssertionFailure() << "face " << f << " has area " << static_cast<double>(area)
                                           << " <= " << min_area << ", first corner "
                                           << describe(m, m.faces[f][0]);
  }
  return ::testing::AssertionSuccess();
}

/// Signed volume by the divergence theorem (fan of each face from the origin, long double).
inline long double reference_signed_volume(const PolygonMesh& m) {
  long double sum = 0;
  for (const auto& f : m.faces)
    for (size_t k = 1; k + 1 < f.size(); ++k) {
      const auto &a = m.vertices[f[0]], &b = m.vertices[f[k]], &c = m.vertices[f[k + 1]];
      const long double ax = a.x(), ay = a.y(), az = a.z();
      const long double bx = b.x(), by = b.y(), bz = b.z();
      const long double cx = c.x(), cy = c.y(), cz = c.z();
      sum += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
    }
  return sum / 6;
}

/// |volume - expected| <= rel_tol * max(|expected|, 1e-300) (relative tolerance, stated by the caller).
inline ::testing::AssertionResult VolumeNear(const PolygonMesh& m, double expected, double rel_tol) {
  if (auto r = IndicesValid(m); !r) return r;
  const double v = static_cast<double>(reference_signed_volume(m));
  const double err = std::abs(v - expected);
  if (!(err <= rel_tol * std::max(std::abs(expected), 1e-300)))
    return ::testing::AssertionFailure() << std::setprecision(17) << "volume " << v << ", expected "
                                         << expected << " (relative error " << err / std::abs(expected)
                                         << " > " << rel_tol << ")";
  return ::testing::AssertionSuccess();
}

}  // namespace sculpt::checks
