#include "mesh/edge_incidence.hpp"

#include <algorithm>
#include <string>
#include <tuple>

#include "base/checked_growth.hpp"
#include "base/errors.hpp"

namespace sculpt {

std::vector<HalfEdgeRecord> sorted_edge_records(const PolygonMesh& mesh) {
  // A counting sort by the lower vertex, then each vertex's few sides by the rest of the key:
  // the order of one std::sort by (lo, hi, face, corner), in linear time for bounded valence.
  int top = -1, bottom = 0;
  for (const auto& f : mesh.faces)
    for (int v : f) top = std::max(top, v), bottom = std::min(bottom, v);
  if (bottom < 0) {  // invalid indices (callers report them): one comparison sort
    std::vector<HalfEdgeRecord> records;
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      const auto& f = mesh.faces[fi];
      for (size_t k = 0; k < f.size(); ++k) {
        const int a = f[k], b = f[(k + 1) % f.size()];
        if (a != b) records.push_back({std::min(a, b), std::max(a, b), static_cast<int>(fi), static_cast<int>(k), a < b});
      }
    }
    std::sort(records.begin(), records.end(), [](const HalfEdgeRecord& x, const HalfEdgeRecord& y) {
      return std::tie(x.lo, x.hi, x.face, x.corner) < std::tie(y.lo, y.hi, y.face, y.corner);
    });
    return records;
  }
  // Sized and filled with Ctrl-C checks (base/checked_growth.hpp): hundreds of MB on a large mesh.
  CancelPoll poll;
  std::vector<size_t> start;
  resize_checked(start, size_t(top + 2));
  for (const auto& f : mesh.faces) {
    poll.tick();
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      if (a != b) ++start[size_t(std::min(a, b)) + 1];
    }
  }
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<HalfEdgeRecord> records;
  resize_checked(records, start.back());
  std::vector<size_t> next(start.begin(), start.end() - 1);
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    poll.tick();
    const auto& f = mesh.faces[fi];
    for (size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      if (a == b) continue;
      records[next[size_t(std::min(a, b))]++] = {std::min(a, b), std::max(a, b), static_cast<int>(fi),
                                                 static_cast<int>(k), a < b};
    }
  }
  auto before = [](const HalfEdgeRecord& x, const HalfEdgeRecord& y) {
    return std::tie(x.hi, x.face, x.corner) < std::tie(y.hi, y.face, y.corner);
  };
  for (size_t v = 0; v + 1 < start.size(); ++v) {
    poll.tick();
    const auto first = records.begin() + std::ptrdiff_t(start[v]), last = records.begin() + std::ptrdiff_t(start[v + 1]);
    if (last - first <= 16) {  // insertion sort: a vertex has a few sides
      for (auto i = first + (first != last ? 1 : 0); i < last; ++i)
        for (auto j = i; j > first && before(*j, *(j - 1)); --j) std::iter_swap(j, j - 1);
    } else {
      std::sort(first, last, before);
    }
  }
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

bool edges_paired(const PolygonMesh& mesh) {
  const std::vector<HalfEdgeRecord> records = sorted_edge_records(mesh);
  if (records.size() % 2 != 0) return false;
  for (size_t i = 0; i < records.size(); i += 2) {
    const HalfEdgeRecord& a = records[i];
    const HalfEdgeRecord& b = records[i + 1];
    if (a.lo != b.lo || a.hi != b.hi || a.forward == b.forward) return false;
    if (i + 2 < records.size() && records[i + 2].lo == a.lo && records[i + 2].hi == a.hi) return false;
  }
  return true;
}

std::vector<std::array<int, 3>> triangle_neighbours(const PolygonMesh& mesh) {
  std::vector<std::array<int, 3>> across(mesh.faces.size(), {-1, -1, -1});
  const std::vector<HalfEdgeRecord> records = sorted_edge_records(mesh);
  for (size_t i = 0; i < records.size();) {
    size_t end = i + 1;  // [i, end): the uses of one edge
    while (end < records.size() && records[end].lo == records[i].lo && records[end].hi == records[i].hi) ++end;
    const HalfEdgeRecord& a = records[i];
    const HalfEdgeRecord& b = records[end - 1];
    if (end - i == 2 && a.forward != b.forward && mesh.faces[size_t(a.face)].size() == 3 &&
        mesh.faces[size_t(b.face)].size() == 3) {
      across[size_t(a.face)][size_t(a.corner)] = b.face;
      across[size_t(b.face)][size_t(b.corner)] = a.face;
    }
    i = end;
  }
  return across;
}

}  // namespace sculpt
