// A cup: a cylinder with a ball taken out of its base, through sculpt's umbrella header. Prints
// the solid's volume, its boundary mesh's size and its tree's height (README.md, "Using the
// library from C++").
#include <sculpt/sculpt.hpp>

#include <cstdio>

int main() {
  using namespace sculpt;
  const Solid cup = cylinder(1.0, 2.0, {.segments = 64}) - sphere(0.9, {.segments = 64});
  const PolygonMesh mesh = to_mesh(cup);
  std::printf("volume %.6f, %zu faces, height %d\n", volume(cup), mesh.faces.size(), tree_stats(cup).height);
  return volume(cup) > 0 ? 0 : 1;
}
