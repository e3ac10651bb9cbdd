#include "bsp/tree/triangle_fragment.hpp"

#include <array>
#include <cstdlib>

#include "kernel/predicates.hpp"

namespace sculpt::bsp::detail {

using kernel::GridPoint;
using kernel::Plane;

namespace {

/// The edge planes of the triangle on `s`, oriented so that the triangle is on their negative side.
std::array<Plane, 3> edge_planes(const Plane& s, const GridPoint* v) {
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

/// The polygon on support `id` (plane `s`) bounded by `edge` (planes) with indices `ids`.
kernel::ConvexPolygon polygon(const Plane& s, std::int32_t id, const std::array<Plane, 3>& edge,
                              const std::array<std::int32_t, 3>& ids) {
  kernel::ConvexPolygon poly;
  poly.support = id;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t prev = (i + 2) % 3;
    poly.corners.push_back({ids[i], ids[prev], ids[i], kernel::approximate_vertex(s, edge[prev], edge[i])});
  }
  return poly;
}

}  // namespace

kernel::ConvexPolygon triangle_polygon(kernel::PlaneTable& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[support];
  const std::array<Plane, 3> edge = edge_planes(s, v);
  std::array<std::int32_t, 3> ids{};
  for (std::size_t i = 0; i < 3; ++i) ids[i] = planes.add(edge[i]);
  return polygon(s, support, edge, ids);
}

kernel::ConvexPolygon triangle_polygon(std::vector<Plane>& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[std::size_t(support)];
  const std::array<Plane, 3> edge = edge_planes(s, v);
  std::array<std::int32_t, 3> ids{};
  for (std::size_t i = 0; i < 3; ++i) {
    ids[i] = std::int32_t(planes.size());
    planes.push_back(edge[i]);
  }
  return polygon(s, support, edge, ids);
}

}  // namespace sculpt::bsp::detail
