#include "bsp/tree/triangle_fragment.hpp"

#include <array>
#include <cstdlib>

#include "base/assert.hpp"
#include "kernel/predicates.hpp"

namespace sculpt::bsp::detail {

using kernel::GridPoint;
using kernel::Plane;

namespace {

/// The edge planes of the triangle on `s`, oriented so that the triangle is on their negative side.
std::array<Plane, 3> edge_planes(const Plane& s, const GridPoint* v) {
  for (int i = 0; i < 3; ++i)  // the corners' approximations rest on it
    SCULPT_ASSERT(s.eval(v[i]) == 0, "triangle_polygon: a corner is off the support plane");
  return {transverse_edge_plane(s, v, 0), transverse_edge_plane(s, v, 1), transverse_edge_plane(s, v, 2)};
}

}  // namespace

Plane transverse_edge_plane(const Plane& s, const GridPoint* v, int i) {
  const std::int64_t n[3] = {std::abs(s.a), std::abs(s.b), std::abs(s.c)};
  const int k = n[0] >= n[1] && n[0] >= n[2] ? 0 : (n[1] >= n[2] ? 1 : 2);
  const GridPoint& a = v[i];
  const GridPoint& b = v[(i + 1) % 3];
  const GridPoint lifted{a.x + (k == 0), a.y + (k == 1), a.z + (k == 2)};
  const Plane e = kernel::plane_through(a, b, lifted);
  return kernel::orient(v[(i + 2) % 3], e) == kernel::Sign::Positive ? e.opposite() : e;
}

/// Corner i is support ∩ edges[i-1] ∩ edges[i], which is v[i] exactly (the three planes contain
/// it): its approximation is the grid point itself, with no error (grid coordinates are exact doubles).
kernel::ConvexPolygon triangle_polygon(std::int32_t support, const GridPoint* v,
                                       const std::array<std::int32_t, 3>& edges) {
  kernel::ConvexPolygon poly;
  poly.support = support;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t prev = (i + 2) % 3;
    const kernel::ApproxPoint at{.x = double(v[i].x), .y = double(v[i].y), .z = double(v[i].z), .err = 0};
    poly.corners.push_back({edges[i], edges[prev], edges[i], at});
  }
  return poly;
}

kernel::ConvexPolygon triangle_polygon(kernel::PlaneTable& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[support];
  const std::array<Plane, 3> edge = edge_planes(s, v);
  std::array<std::int32_t, 3> ids{};
  for (std::size_t i = 0; i < 3; ++i) ids[i] = planes.add(edge[i]);
  return triangle_polygon(support, v, ids);
}

kernel::ConvexPolygon triangle_polygon(std::vector<Plane>& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[std::size_t(support)];
  const std::array<Plane, 3> edge = edge_planes(s, v);
  std::array<std::int32_t, 3> ids{};
  for (std::size_t i = 0; i < 3; ++i) {
    ids[i] = std::int32_t(planes.size());
    planes.push_back(edge[i]);
  }
  return triangle_polygon(support, v, ids);
}

}  // namespace sculpt::bsp::detail
