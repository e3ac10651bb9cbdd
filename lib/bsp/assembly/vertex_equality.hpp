#pragma once
/// \file vertex_equality.hpp
/// Internal to mesh assembly: exact zero test "the vertex p ∩ q ∩ r lies on plane s" for the
/// vertex merge (Bernstein & Fussell 2009, sec. 4: the side of a plane-based vertex is the sign
/// of det[p; q; r; s] times W = det of the three normals). For a zero test only det matters
/// (W != 0 for a vertex), so neither W, nor the floating-point filter (which cannot decide a
/// zero), nor the predicate counters are needed; and the 2x2 minors of the vertex's own rows
/// are computed once for every plane it is tested against.

#include "kernel/predicates.hpp"

namespace sculpt::bsp::detail {

/// The vertex p ∩ q ∩ r prepared for exact on-plane tests (keeps references to the planes).
struct VertexMinors {
  const kernel::Plane* rows[3];
  const kernel::ApproxPoint* at;  ///< approximate_vertex(p, q, r), for the general path
  bool small;                     ///< every |d| < 2^72: the minors below are set
  kernel::Int128 m01, m02, m12;   ///< a_i b_j - a_j b_i of rows i, j
  kernel::Int128 n01, n02, n12;   ///< c_i d_j - c_j d_i of rows i, j
};

/// \pre p, q, r are independent (a vertex); `at` = approximate_vertex(p, q, r) outlives the result.
VertexMinors vertex_minors(const kernel::Plane& p, const kernel::Plane& q, const kernel::Plane& r,
                           const kernel::ApproxPoint& at);

/// Exact: the vertex lies on plane s (det[p; q; r; s] == 0). When p, q, r and s all have
/// |d| < 2^72 the determinant is expanded by the 2x2 minors m (columns a, b) and n (columns
/// c, d): |m| < 2^107 and |n| < 2^126 fit Int128, det = sum of six products m n. If every
/// product has bit_length(m) + bit_length(n) <= 124, each is below 2^124 and the sum below
/// 6 * 2^124 < 2^127: summed in Int128 (axis-aligned and sphere ring planes make most minors
/// small or zero). Otherwise in 256 bits (products < 2^233, sum < 2^236). Larger offsets:
/// kernel::orient decides.
bool vertex_on_plane(const VertexMinors& v, const kernel::Plane& s);

}  // namespace sculpt::bsp::detail
