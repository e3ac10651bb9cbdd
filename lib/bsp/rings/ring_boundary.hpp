#pragma once
/// \file ring_boundary.hpp
/// The boundary a ring revolution (primitives.hpp, revolve_rings) carries, known exactly from its
/// planes (Ihm & Naylor 1990 sec. 6: faces between rings, caps), and the corner approximations it
/// needs, computed in batches: kernel::approximate_vertex's arithmetic operation for operation (so
/// the same bits) on normals converted once per plane, in a loop without calls, so the divisions
/// of consecutive corners overlap.

#include <cstdint>
#include <span>
#include <vector>

#include "bsp/tree_builder.hpp"

namespace sculpt::bsp::detail {

/// A vertex as three plane indices: the point p ∩ q ∩ r.
struct VertexPlanes {
  std::int32_t p, q, r;
};

/// approximate_vertex(planes[t.p], planes[t.q], planes[t.r]) for every triple, bit for bit.
std::vector<kernel::ApproxPoint> approximate_vertices(const kernel::PlaneTable& planes,
                                                      std::span<const VertexPlanes> triples);

/// The boundary of a ring revolution: band k's face j is the quadrilateral between rings k and
/// k + 1 under path edge j (a triangle at a ring of scale 0), and the end rings of positive scale
/// are caps. `ring[k]` is ring k's plane z - z_k, `face[k]` band k's face planes (builder indices),
/// `scale[k]` ring k's scale; the opposites of the ring planes below each band are added to `b`.
/// Each corner carries approximate_vertex(support, p, q) of its own labels (docs/kernel.md).
FragmentList ring_boundary(TreeBuilder& b, const std::vector<std::int32_t>& ring,
                                            const std::vector<std::vector<std::int32_t>>& face,
                                            const std::vector<double>& scale);

}  // namespace sculpt::bsp::detail
