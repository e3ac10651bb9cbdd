#include "bsp/rings/ring_boundary.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "bsp/primitives.hpp"

namespace sculpt {
namespace {

using kernel::ApproxPoint;
using kernel::Int128;
using kernel::Plane;

bool same_bits(const ApproxPoint& a, const ApproxPoint& b) {
  return std::bit_cast<std::uint64_t>(a.x) == std::bit_cast<std::uint64_t>(b.x) &&
         std::bit_cast<std::uint64_t>(a.y) == std::bit_cast<std::uint64_t>(b.y) &&
         std::bit_cast<std::uint64_t>(a.z) == std::bit_cast<std::uint64_t>(b.z) &&
         std::bit_cast<std::uint64_t>(a.err) == std::bit_cast<std::uint64_t>(b.err);
}

// The batch (two corners per vector operation, coordinates before error bounds) must give
// kernel::approximate_vertex's bits for every triple: random planes of every size (small integer
// normals, 53-bit normals, offsets to 80 bits, zero components), nearly dependent triples (the
// kernel's exact rounding), dependent ones (err = -1), and odd counts (the scalar tail).
TEST(RingBoundary, BatchApproximationsHaveTheKernelsBits) {
  std::mt19937_64 rng(7);
  kernel::PlaneTable planes;
  auto coefficient = [&](int bits) {
    const std::int64_t m = bits >= 63 ? INT64_MAX : (std::int64_t(1) << bits);
    const std::int64_t v = std::int64_t(rng() % std::uint64_t(m)) * (rng() % 2 ? 1 : -1);
    return rng() % 7 == 0 ? std::int64_t(0) : v;  // zero components (signed zeros in products)
  };
  for (int i = 0; i < 400; ++i) {
    const int nb = 1 + int(rng() % 52), db = 1 + int(rng() % 78);
    std::int64_t a = coefficient(nb), b = coefficient(nb), c = coefficient(nb);
    if (a == 0 && b == 0 && c == 0) c = 1;
    const Int128 d = Int128(coefficient(db > 62 ? 62 : db)) << (db > 62 ? db - 62 : 0);
    planes.add(Plane(a, b, c, d));
  }
  // Nearly dependent: (A, 1, 0), (A + 1, 1, 0), (0, 0, 1) have determinant -1 at 51-bit normals.
  const std::int64_t big = std::int64_t(1) << 51;
  const std::int32_t n0 = planes.add(Plane(big, 1, 0, 5)), n1 = planes.add(Plane(big + 1, 1, 0, -7)),
                     n2 = planes.add(Plane(0, 0, 1, 3));
  const std::int32_t d0 = planes.add(Plane(1, 2, 3, 0)), d1 = planes.add(Plane(2, 4, 6, 1));  // parallel
  std::vector<bsp::detail::VertexPlanes> triples;
  const auto count = std::uint64_t(planes.size());
  for (int i = 0; i < 20001; ++i) {  // odd: the last one is computed alone
    triples.push_back({std::int32_t(rng() % count), std::int32_t(rng() % count), std::int32_t(rng() % count)});
    if (i % 97 == 0) triples.push_back({n0, n1, n2});
    if (i % 89 == 0) triples.push_back({n2, n0, n1});
    if (i % 83 == 0) triples.push_back({d0, d1, n2});
  }
  const std::vector<ApproxPoint> batch = bsp::detail::approximate_vertices(planes, triples);
  ASSERT_EQ(batch.size(), triples.size());
  int nearly = 0, dependent = 0;
  for (std::size_t i = 0; i < triples.size(); ++i) {
    const bsp::detail::VertexPlanes t = triples[i];
    const ApproxPoint expected = kernel::approximate_vertex(planes[t.p], planes[t.q], planes[t.r]);
    ASSERT_TRUE(same_bits(batch[i], expected)) << i << ": " << batch[i].x << " " << expected.x;
    nearly += t.p == n0 || t.p == n2;
    dependent += expected.err < 0;
  }
  EXPECT_GT(nearly, 200);
  EXPECT_GT(dependent, 200);
  EXPECT_TRUE(bsp::detail::approximate_vertices(planes, {}).empty());
}

// Every corner a ring primitive carries is the vertex support ∩ p ∩ q with edge q, approximated
// with approximate_vertex's bits; labels follow the cycle (each corner's q is the next one's p).
TEST(RingBoundary, CarriedCornersAreTheKernelsApproximations) {
  std::vector<Solid> solids;
  for (int n : {3, 4, 5, 7, 10, 16, 31, 32, 64}) {
    solids.push_back(sphere(1.0, {.segments = n}));
    solids.push_back(sphere(0.013, {.segments = n}));
    solids.push_back(cylinder(2.5, 0.75, {.segments = n, .center = true}));
    solids.push_back(cone(1.0, 2.0, {.segments = n}));
    solids.push_back(cone(1.0, 2.0, {.segments = n, .top_radius = 0.4}));
  }
  std::size_t corners = 0;
  for (std::size_t s = 0; s < solids.size(); ++s) {
    const Solid& solid = solids[s];
    ASSERT_TRUE(solid.has_boundary()) << s;
    for (const FragmentRef f : solid.boundary()) {
      const auto& c = f.polygon.corners;
      ASSERT_GE(c.size(), 3u);
      for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_EQ(c[i].edge, c[i].q);
        EXPECT_EQ(c[i].q, c[(i + 1) % c.size()].p);
        // As a corner keeps it: the kernel's approximation, its error bound a float rounded up.
        const ApproxPoint expected =
            kernel::Corner(0, 0, 0,
                           kernel::approximate_vertex(solid.planes()[f.polygon.support], solid.planes()[c[i].p],
                                                      solid.planes()[c[i].q]))
                .at();
        ASSERT_TRUE(same_bits(c[i].at(), expected)) << s << " corner " << i;
        ++corners;
      }
    }
  }
  EXPECT_GT(corners, 10000u);
}

}  // namespace
}  // namespace sculpt
