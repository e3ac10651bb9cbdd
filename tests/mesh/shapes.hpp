#pragma once
// Hand-built test meshes with known measures (faces counter-clockwise from outside).
#include <cmath>
#include <numbers>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::test_shapes {

/// Axis-aligned box [lo, hi], 8 vertices, 6 quads.
inline PolygonMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  PolygonMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return m;
}

inline PolygonMesh unit_cube() { return box({0, 0, 0}, {1, 1, 1}); }

/// Corner tetrahedron (0,0,0), e_x, e_y, e_z: volume 1/6, area 3/2 + sqrt(3)/2.
inline PolygonMesh tetrahedron() {
  PolygonMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

/// |x| + |y| + |z| <= 1: volume 4/3, area 4 sqrt(3).
inline PolygonMesh octahedron() {
  PolygonMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int sx : {0, 1})
    for (int sy : {2, 3})
      for (int sz : {4, 5}) {
        // Orientation flips with each negative axis.
        const int neg = (sx == 1) + (sy == 3) + (sz == 5);
        if (neg % 2 == 0) m.faces.push_back({sx, sy, sz});
        else m.faces.push_back({sx, sz, sy});
      }
  return m;
}

/// Torus with n x m quads (major radius R, minor radius r): genus 1.
inline PolygonMesh torus(int n, int m, double R = 2, double r = 0.5) {
  PolygonMesh t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / m;
      t.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                              r * std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) t.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return t;
}

/// UV sphere: `segments` around the equator, segments / 2 bands, poles as triangle fans.
inline PolygonMesh uv_sphere(int segments, double radius = 1) {
  PolygonMesh s;
  const int rings = segments / 2;
  s.vertices.emplace_back(0, 0, -radius);
  for (int i = 1; i < rings; ++i) {
    const double phi = std::numbers::pi * i / rings - std::numbers::pi / 2;
    for (int j = 0; j < segments; ++j) {
      const double th = 2 * std::numbers::pi * j / segments;
      s.vertices.emplace_back(radius * std::cos(phi) * std::cos(th), radius * std::cos(phi) * std::sin(th),
                              radius * std::sin(phi));
    }
  }
  s.vertices.emplace_back(0, 0, radius);
  const int top = static_cast<int>(s.vertices.size()) - 1;
  auto id = [&](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) s.faces.push_back({0, id(1, j + 1), id(1, j)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) s.faces.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)});
  for (int j = 0; j < segments; ++j) s.faces.push_back({top, id(rings - 1, j), id(rings - 1, j + 1)});
  return s;
}

/// Two meshes side by side as one (indices of `b` shifted).
inline PolygonMesh merged(PolygonMesh a, const PolygonMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) {
    for (int& v : f) v += offset;
    a.faces.push_back(f);
  }
  return a;
}

}  // namespace sculpt::test_shapes
