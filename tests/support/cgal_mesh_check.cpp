#include "support/cgal_mesh_check.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <exception>
#include <iterator>
#include <map>
#include <sstream>
#include <utility>

#include "mesh/triangulate.hpp"

namespace sculpt::checks {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

std::string where(const Point& p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// A face has zero area when all its corners lie on one line (exact orientation predicate).
bool degenerate(const std::vector<Point>& points, const std::vector<std::size_t>& face) {
  const Point& a = points[face[0]];
  std::size_t k = 1;
  while (k < face.size() && points[face[k]] == a) ++k;
  if (k == face.size()) return true;
  const Point& b = points[face[k]];
  for (std::size_t j = k + 1; j < face.size(); ++j)
    if (!CGAL::collinear(a, b, points[face[j]])) return false;
  return true;
}

}  // namespace

CgalMeshReport cgal_check(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::vector<int>>& faces) {
  CgalMeshReport r;
  auto problem = [&](const std::string& text) {
    if (r.problem.empty()) r.problem = text;
  };
  std::vector<Point> points;
  points.reserve(vertices.size());
  for (const Eigen::Vector3d& v : vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::vector<std::size_t> polygon;
    for (const int i : faces[f]) {
      if (i < 0 || std::size_t(i) >= points.size()) {
        problem("face " + std::to_string(f) + " has a vertex index out of range");
        return r;
      }
      polygon.push_back(std::size_t(i));
    }
    if (polygon.size() < 3) {
      problem("face " + std::to_string(f) + " has fewer than three corners");
      return r;
    }
    polygons.push_back(std::move(polygon));
  }

  std::map<Point, std::size_t> seen;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!seen.emplace(points[i], i).second) {
      ++r.duplicate_points;
      problem("vertices " + std::to_string(seen[points[i]]) + " and " + std::to_string(i) + " have the same coordinates " +
              where(points[i]));
    }
  for (std::size_t f = 0; f < polygons.size(); ++f)
    if (degenerate(points, polygons[f])) {
      ++r.degenerate_faces;
      problem("face " + std::to_string(f) + " has zero area (its corners are collinear) near " + where(points[polygons[f][0]]));
    }

  r.polygon_mesh = PMP::is_polygon_soup_a_polygon_mesh(polygons);
  if (!r.polygon_mesh) {
    problem("not a polygon mesh: an edge is used twice in one direction, or a vertex is non-manifold");
    return r;
  }
  try {
    Mesh mesh;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    r.closed = CGAL::is_closed(mesh);
    if (!r.closed) problem("not closed: some edge has only one face");
    // CGAL's own face triangulation (a constrained Delaunay triangulation in a projection)
    // crashes on some nearly degenerate polygons; the triangles CGAL judges come from
    // lib/mesh's exact ear clipping instead, the way an exporter to triangles would cut them.
    std::vector<std::vector<std::size_t>> triangles;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (faces[f].size() == 3) {
        triangles.push_back(polygons[f]);
        continue;
      }
      try {
        for (const IndexTriangle& t : triangulate_polygon(vertices, faces[f]))
          triangles.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
      } catch (const std::exception& e) {
        problem("face " + std::to_string(f) + " cannot be triangulated: " + e.what());
        return r;
      }
    }
    mesh.clear();
    PMP::polygon_soup_to_polygon_mesh(points, triangles, mesh);
    if (r.degenerate_faces == 0) {  // degenerate triangles are reported above; CGAL expects none here
      std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
      PMP::self_intersections(mesh, std::back_inserter(pairs));
      r.self_intersections = pairs.size();
      if (!pairs.empty()) {
        const auto h = mesh.halfedge(pairs.front().first);
        problem(std::to_string(pairs.size()) + " pairs of triangles intersect, the first near " +
                where(mesh.point(mesh.target(h))));
      }
    }
    if (r.closed) {
      r.outward = PMP::is_outward_oriented(mesh);
      if (!r.outward) problem("closed but not oriented outward");
      r.volume = PMP::volume(mesh);
    }
  } catch (const std::exception& e) {
    problem(std::string("CGAL threw: ") + e.what());
  }
  return r;
}

}  // namespace sculpt::checks
