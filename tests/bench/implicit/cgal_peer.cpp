// CGAL's surface mesher (Boissonnat & Oudot's Delaunay refinement, CGAL::make_surface_mesh with
// an Implicit_surface_3) on the torus R = 1, r = 0.4 of tests/bench/implicit/solid.cpp, for a
// list of distance bounds. Built and run by tests/bench/implicit/peers.sh (not by CMake: CGAL is
// a peer here, installed by that script). For each bound: median thread CPU time of 5 runs, the
// mesh written as OFF, and a line "cgal make_surface_mesh|<setting>|<ms>|<file>" appended to
// <dir>/peers.txt, which `implicit_solid --peers <dir>` measures.
//   cgal_peer <dir> <distance bound>...
#include <CGAL/Complex_2_in_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/make_surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

using Tr = CGAL::Surface_mesh_default_triangulation_3;
using C2t3 = CGAL::Complex_2_in_triangulation_3<Tr>;
using GT = Tr::Geom_traits;
using Sphere = GT::Sphere_3;
using Point = GT::Point_3;
using FT = GT::FT;
using Function = FT (*)(Point);
using Surface = CGAL::Implicit_surface_3<GT, Function>;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

// The same polynomial form as the Expression polygonize evaluates (solid.cpp: torus()).
FT torus(Point p) {
  const double q = std::sqrt(p.x() * p.x() + p.y() * p.y()) - 1.0;
  return q * q + p.z() * p.z() - 0.16;
}

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: cgal_peer <dir> <distance bound>...\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::ofstream list(dir + "/peers.txt", std::ios::app);
  for (int a = 2; a < argc; ++a) {
    const double distance = std::stod(argv[a]);
    std::vector<double> times;
    Mesh mesh;
    for (int run = 0; run < 5; ++run) {
      const double start = cpu_ms();
      Tr tr;
      C2t3 c2t3(tr);
      // The bounding sphere's centre must be inside (f < 0): (1, 0, 0) is on the tube's core
      // circle; radius 2.5 encloses the torus (its farthest point, (-1.4, 0, 0), is 2.4 away).
      Surface surface(torus, Sphere(Point(1, 0, 0), 2.5 * 2.5), 1e-6);
      // 30 degrees minimum angle; the radius bound loose (0.2, half the tube radius) so that the
      // distance bound decides where the triangles are small.
      CGAL::Surface_mesh_default_criteria_3<Tr> criteria(30.0, 0.2, distance);
      CGAL::make_surface_mesh(c2t3, surface, criteria, CGAL::Manifold_tag(), 40);
      mesh.clear();
      CGAL::facets_in_complex_2_to_triangle_mesh(c2t3, mesh);
      times.push_back(cpu_ms() - start);
    }
    std::sort(times.begin(), times.end());
    char name[64];
    std::snprintf(name, sizeof name, "cgal_%g.off", distance);
    const std::string file = dir + "/" + name;
    std::ofstream off(file);
    off.precision(17);
    off << "OFF\n" << mesh.number_of_vertices() << " " << mesh.number_of_faces() << " 0\n";
    std::vector<int> index(mesh.number_of_vertices());
    int next = 0;
    for (auto v : mesh.vertices()) {
      index[v.idx()] = next++;
      const Point& p = mesh.point(v);
      off << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
    for (auto f : mesh.faces()) {
      off << "3";
      for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) off << " " << index[v.idx()];
      off << "\n";
    }
    list << "cgal make_surface_mesh|distance bound " << distance << "|" << times[2] << "|" << file << "\n";
    std::printf("cgal distance %g: %zu triangles, %.1f ms\n", distance, std::size_t(mesh.number_of_faces()), times[2]);
  }
  return 0;
}
