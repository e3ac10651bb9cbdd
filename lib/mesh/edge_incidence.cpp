#include "mesh/edge_incidence.hpp"

#include <algorithm>
#include <string>
#include <tuple>

#include "base/errors.hpp"

namespace sculpt {

std::vector<HalfEdgeRecord> sorted_edge_records(const PolygonMesh& mesh) {
  std::vector<HalfEdgeRecord> records;
  size_t total = 0;
  for (const auto& f : mesh.faces) total += f.size();
  records.reserve(total);
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const auto& f = mesh.faces[fi];
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      if (a == b) continue;
      records.push_back({std::min(a, b), std::max(a, b), static_cast<int>(fi),
                         static_cast<int>(k), a < b});
    }
  }
  std::sort(records.begin(), records.end(), [](const HalfEdgeRecord& x, const HalfEdgeRecord& y) {
    return std::tie(x.lo, x.hi, x.face, x.corner) < std::tie(y.lo, y.hi, y.face, y.corner);
  });
  return records;
}

void check_face_indices(const PolygonMesh& mesh, std::string_view who) {
  const auto n = static_cast<long long>(mesh.vertices.size());
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const auto& f = mesh.faces[fi];
    if (f.size() < 3)
      throw InvalidInput(std::string(who) + ": face " + std::to_string(fi) + " has " +
                         std::to_string(f.size()) + " vertices (at least 3 needed)");
    for (int id : f)
      if (id < 0 || id >= n)
        throw InvalidInput(std::string(who) + ": face " + std::to_string(fi) +
                           " refers to vertex " + std::to_string(id) + " but the mesh has " +
                           std::to_string(n) + " vertices");
  }
}

}  // namespace sculpt
