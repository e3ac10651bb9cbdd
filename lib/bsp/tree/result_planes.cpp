#include "bsp/tree/result_planes.hpp"

#include <atomic>
#include <cstdint>
#include <vector>

#include "base/parallel.hpp"

namespace sculpt::bsp::detail {

namespace {

// Calls f on every plane reference of fragment g (support, then each corner's edge, p and q).
template <typename F>
void for_each_plane(const FragmentRef& g, F&& f) {
  f(g.polygon.support);
  for (const kernel::Corner& c : g.polygon.corners) f(c.edge), f(c.p), f(c.q);
}

}  // namespace

// Each plane is numbered by the first chunk that uses it, after the planes of the chunks before it.
kernel::PlaneTable result_planes(kernel::PlaneTable&& planes, FragmentList& fragments) {
  constexpr std::size_t kChunk = 4096;
  constexpr std::uint32_t kUnused = ~std::uint32_t(0);
  const std::size_t n = fragments.size(), chunks = (n + kChunk - 1) / kChunk;
  const auto world = kernel::kWorldPlanes;
  // The first chunk that uses each plane (a minimum, so the order of the chunks' runs does not matter).
  std::vector<std::atomic<std::uint32_t>> first(std::size_t(planes.size()));
  for (auto& x : first) x.store(kUnused, std::memory_order_relaxed);
  parallel_chunks(n, kChunk, [&](std::size_t begin, std::size_t end) {
    const auto chunk = std::uint32_t(begin / kChunk);
    for (std::size_t i = begin; i < end; ++i)
      for_each_plane(fragments[i], [&](std::int32_t p) {
        if (p < world) return;
        std::atomic<std::uint32_t>& at = first[std::size_t(p)];
        std::uint32_t now = at.load(std::memory_order_relaxed);
        while (chunk < now && !at.compare_exchange_weak(now, chunk, std::memory_order_relaxed)) {}
      });
  });
  std::size_t used = 0;
  for (const auto& x : first) used += x.load(std::memory_order_relaxed) != kUnused;
  if (2 * used >= std::size_t(planes.size() - world)) return std::move(planes);
  // Each chunk numbers the planes it uses first, in the order it meets them (only that chunk
  // writes their entries of `local`).
  std::vector<std::int32_t> local(std::size_t(planes.size()), -1);
  std::vector<std::int32_t> count(chunks, 0);
  parallel_chunks(n, kChunk, [&](std::size_t begin, std::size_t end) {
    const auto chunk = std::uint32_t(begin / kChunk);
    std::int32_t& k = count[chunk];
    for (std::size_t i = begin; i < end; ++i)
      for_each_plane(fragments[i], [&](std::int32_t p) {
        if (p >= world && first[std::size_t(p)].load(std::memory_order_relaxed) == chunk && local[std::size_t(p)] < 0)
          local[std::size_t(p)] = k++;
      });
  });
  std::vector<std::int32_t> base(chunks + 1, world);
  for (std::size_t c = 0; c < chunks; ++c) base[c + 1] = base[c] + count[c];
  // The new table in order, then every reference renumbered.
  std::vector<std::int32_t> order(std::size_t(base[chunks] - world));
  for (std::size_t p = std::size_t(world); p < local.size(); ++p)
    if (local[p] >= 0) {
      local[p] += base[first[p].load(std::memory_order_relaxed)];
      order[std::size_t(local[p] - world)] = std::int32_t(p);
    }
  kernel::PlaneTable table;
  table.reserve(std::size_t(world) + order.size());
  for (const std::int32_t p : order) table.add(planes[p], planes.auxiliary(p));
  parallel_chunks(n, kChunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      fragments.renumber_planes(i, [&](std::int32_t p) { return p >= world ? local[std::size_t(p)] : p; });
  });
  return table;
}

}  // namespace sculpt::bsp::detail
