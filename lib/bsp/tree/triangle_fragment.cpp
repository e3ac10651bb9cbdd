#include "bsp/tree/triangle_fragment.hpp"

#include <cstdlib>

#include "kernel/predicates.hpp"

namespace sculpt::bsp::detail {

using kernel::GridPoint;
using kernel::Plane;

kernel::ConvexPolygon triangle_polygon(kernel::PlaneTable& planes, std::int32_t support, const GridPoint* v) {
  const Plane s = planes[support];
  const std::int64_t n[3] = {std::abs(s.a), std::abs(s.b), std::abs(s.c)};
  const int k = n[0] >= n[1] && n[0] >= n[2] ? 0 : (n[1] >= n[2] ? 1 : 2);
  const GridPoint off{k == 0, k == 1, k == 2};
  std::int32_t edge[3];
  for (int i = 0; i < 3; ++i) {
    const GridPoint& a = v[i];
    const GridPoint& b = v[(i + 1) % 3];
    const GridPoint lifted{a.x + off.x, a.y + off.y, a.z + off.z};
    Plane e = kernel::plane_through(a, b, lifted);
    if (kernel::orient(v[(i + 2) % 3], e) == kernel::Sign::Positive) e = e.opposite();
    edge[i] = planes.add(e);
  }
  kernel::ConvexPolygon poly;
  poly.support = support;
  for (int i = 0; i < 3; ++i) {
    const std::int32_t prev = edge[(i + 2) % 3];
    poly.corners.push_back({edge[i], prev, edge[i], kernel::approximate_vertex(s, planes[prev], planes[edge[i]])});
  }
  return poly;
}

}  // namespace sculpt::bsp::detail
