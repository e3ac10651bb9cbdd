// Mesh assembly alone (lib/bsp/mesh_assembly.hpp): builds each benchmark solid once, extracts
// its boundary fragments once (bsp::detail::boundary_fragments), then times only assemble_mesh.
// Prints one parseable line per case:
//   bench impl=sculpt stage=assembly case=<case> n=<n> runs=<r> time_ms=<median> min_ms=<min> cpu_ms=<median>
//         fragments=<f> occurrences=<corners> vertices=<v> faces=<f> volume=<v> area=<a>
//         source=<extracted|carried>  (carried: the boundary the solid carries, if it does)
//         allocations=<operator new calls per assemble_mesh call (last run)>
//   bench_assembly                 sphere_minus_cube 32, 128, 256, menger 3, boxes 1000
//   bench_assembly CASE N [RUNS]   one case (solids as in bench_bsp.cpp, CASES.md)
//   bench_assembly CASE N RUNS stages  also times each stage of assemble_mesh (median over the runs)
//                                  and counts its allocations
//   bench_assembly CASE N RUNS carried  times only the carried boundary (for profiling)
//   bench_assembly CASE N RUNS DUMP  also writes the mesh in a canonical text form to DUMP
//                                  (faces as coordinate cycles starting at the smallest, sorted),
//                                  to compare two builds' output independently of numbering
//                                  (the carried boundary's mesh to DUMP.carried)
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bsp/assembly/coplanar_faces.hpp"
#include "bsp/assembly/faces.hpp"
#include "bsp/assembly/sheets.hpp"
#include "bsp/tree/boundary_fragments.hpp"
#include "bsp/assembly/junction_removal.hpp"
#include "bsp/assembly/mesh_assembly.hpp"
#include "bsp/assembly/vertex_merge.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "support/bench_solids.hpp"

using namespace sculpt;

// Allocation counter (this benchmark only): every operator new goes through these replacements,
// so allocations per assemble_mesh call can be counted (fixed costs matter at small sizes).
namespace {
long g_allocations = 0;
}  // namespace
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

Solid sphere_minus_cube(int n) { return sphere(1.0, {.segments = n}) - box({0, 0, 0}, {1, 1, 1}); }


// CPU time of this thread (ms): steadier than wall time on a shared, oversubscribed machine.
double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

struct Measures {
  long double volume = 0, area = 0;
};

Measures measure(const PolygonMesh& m) {  // faces may be non-convex: vector area per face
  Measures r;
  for (const auto& f : m.faces) {
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const Eigen::Vector3d a = m.vertices[std::size_t(f[0])], b = m.vertices[std::size_t(f[i])],
                            c = m.vertices[std::size_t(f[i + 1])];
      r.volume += a.dot(b.cross(c)) / 6.0;
      area += 0.5 * (b - a).cross(c - a);
    }
    r.area += area.norm();
  }
  return r;
}

// The stages of assemble_mesh (mesh_assembly.cpp) one by one, each timed: median CPU ms per stage.
void time_stages(const bsp::detail::Fragments& f, int runs, const char* source) {
  const char* names[] = {"vertex_merge", "t_junctions", "coplanar", "straight", "sheets", "output"};
  constexpr int kStages = 6;
  std::vector<std::vector<double>> t(kStages);
  bsp::detail::JunctionResult last;
  int sizes[kStages][2] = {};  // faces and corners after each stage (last run)
  long allocations[kStages] = {};  // operator new calls of each stage (last run)
  for (int r = 0; r < runs; ++r) {
    double t0 = cpu_ms();
    long a0 = g_allocations;
    int stage = 0;
    auto lap = [&](const bsp::detail::FaceList* after = nullptr) {
      const double t1 = cpu_ms();
      if (after != nullptr) sizes[stage][0] = after->size(), sizes[stage][1] = after->corners();
      allocations[stage] = g_allocations - a0;
      a0 = g_allocations;
      t[std::size_t(stage++)].push_back(t1 - t0);
      t0 = t1;
    };
    bsp::detail::MergedFragments merged = bsp::detail::merge_vertices(f);  // with the plane ids and the faces
    const bsp::detail::PlaneIds& ids = merged.ids;
    lap(&merged.faces);
    const bsp::detail::VertexGeometry geometry(f.planes, ids, merged.vertices);
    last = bsp::detail::remove_t_junctions(std::move(merged.faces), geometry, ids);
    bsp::detail::FaceList faces;
    lap(&last.faces);
    faces = bsp::detail::merge_coplanar_faces(std::move(last.faces), merged.vertices.size(), ids);
    lap(&faces);
    faces = bsp::detail::remove_straight_vertices(std::move(faces), merged.vertices.size(), geometry);
    lap(&faces);
    const bsp::detail::Sheets sheets = bsp::detail::split_non_manifold(std::move(faces), merged.vertices, f.planes);
    lap(&sheets.faces);
    const PolygonMesh mesh = bsp::detail::output_mesh(sheets, merged.vertices, f.planes);
    lap();
  }
  std::printf("stages source=%s", source);
  for (int k = 0; k < kStages; ++k) {
    std::sort(t[std::size_t(k)].begin(), t[std::size_t(k)].end());
    std::printf(" %s=%.3f", names[k], t[std::size_t(k)][t[std::size_t(k)].size() / 2]);
  }
  std::printf(" open_edges=%d by_lines=%d by_search=%d\n", last.open, last.by_lines, last.by_search);
  std::printf("sizes source=%s", source);  // faces/corners after each stage
  for (int k = 0; k + 1 < kStages; ++k) std::printf(" %s=%d/%d", names[k], sizes[k][0], sizes[k][1]);
  std::printf("\nallocations source=%s", source);
  for (int k = 0; k < kStages; ++k) std::printf(" %s=%ld", names[k], allocations[k]);
  std::printf("\n");
}

void dump(const PolygonMesh& mesh, const std::string& path) {
  std::vector<std::string> faces;
  for (const auto& f : mesh.faces) {
    std::vector<std::string> corners;
    for (int v : f) {
      char buf[128];
      const Eigen::Vector3d& p = mesh.vertices[std::size_t(v)];
      std::snprintf(buf, sizeof buf, "(%.17g %.17g %.17g)", p.x(), p.y(), p.z());
      corners.emplace_back(buf);
    }
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    std::string line;
    for (const auto& c : corners) line += c;
    faces.push_back(line);
  }
  std::sort(faces.begin(), faces.end());
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) return;
  std::fprintf(out, "vertices %zu faces %zu\n", mesh.vertices.size(), mesh.faces.size());
  for (const auto& line : faces) std::fprintf(out, "%s\n", line.c_str());
  std::fclose(out);
}

// Median time of assemble_mesh on `fragments`; prints the case line and returns the mesh.
PolygonMesh time_assembly(const std::string& name, int n, int runs, const char* source, const bsp::detail::Fragments& fragments) {
  std::size_t corners = 0;
  for (const auto& f : fragments.fragments) corners += f.polygon.corners.size();
  std::vector<double> times, cpu;
  PolygonMesh mesh;
  long allocations = 0;
  for (int i = 0; i < runs + 1; ++i) {  // the first run is a discarded warm-up
    const long a0 = g_allocations;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_ms();
    mesh = bsp::detail::assemble_mesh(fragments, {});
    const double c1 = cpu_ms();
    const auto t1 = std::chrono::steady_clock::now();
    allocations = g_allocations - a0;
    if (i > 0) times.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count()), cpu.push_back(c1 - c0);
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu.begin(), cpu.end());
  const Measures m = measure(mesh);
  std::printf("bench impl=sculpt stage=assembly case=%s n=%d runs=%d time_ms=%.3f min_ms=%.3f cpu_ms=%.3f fragments=%zu "
              "occurrences=%zu vertices=%zu faces=%zu volume=%.17Lg area=%.17Lg source=%s allocations=%ld\n",
              name.c_str(), n, runs, times[times.size() / 2], times.front(), cpu[cpu.size() / 2], fragments.fragments.size(), corners,
              mesh.vertices.size(), mesh.faces.size(), m.volume, m.area, source, allocations);
  return mesh;
}

int run_case(const std::string& name, int n, int runs, const std::string& dump_path) {
  Solid solid;
  if (name == "sphere_minus_cube") {
    solid = sphere_minus_cube(n);
  } else if (name == "sphere") {
    solid = sphere(1.0, {.segments = n});  // a revolution carrying its ring boundary (the view's fine sphere)
  } else if (name == "menger") {
    solid = checks::menger_sponge(n);  // units of 1/27 as in bench_bsp
  } else if (name == "boxes") {
    solid = checks::lcg_boxes(n);
  } else {
    std::fprintf(stderr, "unknown case %s\n", name.c_str());
    return 2;
  }
  // The fragments extracted from the tree (bsp::detail::boundary_fragments), and, when the solid
  // carries its boundary through the set operations, those too (what to_mesh assembles).
  if (dump_path == "carried") {
    if (solid.has_boundary()) time_assembly(name, n, runs, "carried", bsp::detail::Fragments{solid.planes(), solid.boundary()});
    return 0;
  }
  const bsp::detail::Fragments fragments = bsp::detail::boundary_fragments(solid);
  PolygonMesh mesh = time_assembly(name, n, runs, "extracted", fragments);
  PolygonMesh carried;
  if (solid.has_boundary())
    carried = time_assembly(name, n, runs, "carried", bsp::detail::Fragments{solid.planes(), solid.boundary()});
  if (dump_path == "stages") {
    time_stages(fragments, runs, "extracted");
    if (solid.has_boundary()) time_stages(bsp::detail::Fragments{solid.planes(), solid.boundary()}, runs, "carried");
  } else if (!dump_path.empty()) {
    dump(mesh, dump_path);
    if (solid.has_boundary()) dump(carried, dump_path + ".carried");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3)
    return run_case(argv[1], std::atoi(argv[2]), argc >= 4 ? std::max(1, std::atoi(argv[3])) : 7, argc >= 5 ? argv[4] : "");
  const std::vector<std::pair<std::string, int>> cases = {{"sphere_minus_cube", 32},
                                                          {"sphere_minus_cube", 128},
                                                          {"sphere_minus_cube", 256},
                                                          {"menger", 3},
                                                          {"boxes", 1000}};
  int status = 0;
  for (const auto& [name, n] : cases) status |= run_case(name, n, name == "boxes" ? 5 : 11, "");
  return status == 0 ? 0 : 1;
}
