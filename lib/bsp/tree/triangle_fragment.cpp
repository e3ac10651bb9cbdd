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
  for (int i = 0; i < 3; ++i)  // the corners' approximations below rest on it
    SCULPT_ASSERT(s.eval(v[i]) == 0, "triangle_polygon: a corner is off the support plane");
  const std::int64_t n[3] = {std::abs(s.a), std::abs(s.b), std::abs(s.c)};
  const int k = n[0] >= n[1] && n[0] >= n[2] ? 0 : (n[1] >= n[2] ? 1 : 2);
  const GridPoint off{k == 0, k == 1, k == 2};
  std::array<Plane, 3> edge;
  for (int i = 0; i < 3; ++i) {
    const GridPoint& a = v[i];
    const GridPoint& b = v[(i + 1) % 3];
    const GridPoint lifted{a.x + off.x, a.y + off.y, a.z + off.z};
    Plane e = kernel::plane_through(a, b, lifted);
    if (kernel::orient(v[(i + 2) % 3], e) == kernel::Sign::Positive) e = e.opposite();
    edge[std::size_t(i)] = e;
  }
  return edge;
}

/// The polygon on support `id` bounded by the edge planes with indices `ids`. Corner i is
/// support ∩ edge[i-1] ∩ edge[i], which is v[i] exactly (the three planes contain it): its
/// approximation is the grid point itself, with no error (grid coordinates are exact doubles).
kernel::ConvexPolygon polygon(std::int32_t id, const GridPoint* v, const std::array<std::int32_t, 3>& ids) {
  kernel::ConvexPolygon poly;
  poly.support = id;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t prev = (i + 2) % 3;
    const kernel::ApproxPoint at{.x = double(v[i].x), .y = double(v[i].y), .z = double(v[i].z), .err = 0};
    poly.corners.push_back({ids[i], ids[prev], ids[i], at});
  }
  return poly;
}

}  // namespace

kernel::ConvexPolygon triangle_polygon(kernel::PlaneTable& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[support];
  const std::array<Plane, 3> edge = edge_planes(s, v);
  std::array<std::int32_t, 3> ids{};
  for (std::size_t i = 0; i < 3; ++i) ids[i] = planes.add(edge[i]);
  return polygon(support, v, ids);
}

kernel::ConvexPolygon triangle_polygon(std::vector<Plane>& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[std::size_t(support)];
  const std::array<Plane, 3> edge = edge_planes(s, v);
  std::array<std::int32_t, 3> ids{};
  for (std::size_t i = 0; i < 3; ++i) {
    ids[i] = std::int32_t(planes.size());
    planes.push_back(edge[i]);
  }
  return polygon(support, v, ids);
}

}  // namespace sculpt::bsp::detail
