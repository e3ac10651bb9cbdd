// default_grid_hash: one hash of the bits of every mesh vertex, face list, volume, node count and
// leaf-cell volume of 40 seeded constructions with general rotations, from_mesh rebuilds and
// scalings, and a revolved profile, all at the default grid. Built on two commits, equal hashes
// mean the default grid gives the same results bit for bit (docs/benchmarks.md, "World range").
// Uses only API that predates kernel::Grid, so it builds on older commits too.
#include <cstdio>
#include <random>
#include <cstring>
#include <cstdint>
#include "bsp/boundary.hpp"
#include "bsp/cells.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "revolution/revolve.hpp"
using namespace sculpt;
std::uint64_t h = 1469598103934665603ull;
void mix(double d) { std::uint64_t b; std::memcpy(&b, &d, 8); for (int i = 0; i < 8; ++i) { h ^= (b >> (8 * i)) & 255; h *= 1099511628211ull; } }
void add(const Solid& s) {
  const PolygonMesh m = to_mesh(s);
  for (const auto& v : m.vertices) mix(v.x()), mix(v.y()), mix(v.z());
  for (const auto& f : m.faces) for (int i : f) mix(i);
  mix(volume(s)); mix(tree_stats(s).nodes);
}
int main() {
  std::mt19937_64 rng(7);
  for (int t = 0; t < 40; ++t) {
    auto u = [&] { return std::uniform_real_distribution<double>(-1, 1)(rng); };
    Solid a = sphere(0.8 + 0.2 * u(), {.segments = 16 + t % 5 * 8});
    Solid b = rotate(box({u(), u(), u()}, {1.5, 1.5, 1.5}), {u(), u(), 1}, 90 * u());
    Solid c = translate(rotate(cone(0.5, 1.2, {.segments = 20}), {1, u(), u()}, 45 * u()), {u(), u(), u()});
    Solid r = (a - b) | c;
    add(r);
    add(from_mesh(to_mesh(r)));
    add(scale(r, {1.5, 0.75, 2}));
    for (const auto& cell : leaf_cells(c, Eigen::AlignedBox3d(Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(2, 2, 2)))) mix(cell.volume);
  }
  add(revolution::revolve({{0, 0}, {1, 0}, {0.7, 0.5}, {0.9, 1.2}, {0, 1.3}}, circular_path(40)));
  std::printf("%016llx\n", (unsigned long long)h);
}
