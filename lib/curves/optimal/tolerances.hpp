#pragma once
/// \file tolerances.hpp
/// The margins and thresholds of the exact solver (optimal/), in one place.
///
/// The solver's answers are exact: every error it reports is segment_error() (Definition 2.3 of
/// Ihm & Naylor 1990) bit for bit. Most chords are decided earlier by cheaper tests (squared
/// distances without square roots, capsule bounds of SegmentErrorTree, slope intervals of cone
/// pruning). Each such test keeps a margin far above the rounding of its few operations (about
/// 1e-16 relative) and far below any difference that matters, so it never rejects a chord the
/// exact measure would accept; borderline chords go to the exact measure (ChordDistance).
/// The spans decide how a chord is measured (directly or through the tree), never its value.

namespace sculpt::curves::detail {

/// Relative margin of every cheap test against a tolerance.
inline constexpr double kRelativeMargin = 1e-9;
/// Added to squared bounds: eps^2 |d|^2 underflows for tiny eps, where a relative margin is no margin.
inline constexpr double kUnderflowMargin = 1e-300;

/// A squared bound such as eps^2 |p_j - p_i|^2, raised by both margins: a squared cross product
/// |(p_k - p_i) x (p_j - p_i)|^2 above it certainly puts p_k farther than eps from the chord line.
[[nodiscard]] constexpr double beyond_squared(double squared) {
  return squared * (1.0 + kRelativeMargin) + kUnderflowMargin;
}

/// FeasibilitySolver::error: chords spanning up to this many points are measured by
/// segment_error() directly, longer ones through SegmentErrorTree.
inline constexpr int kDirectErrorSpan = 256;
/// Stored mode (store_errors): chords spanning up to this many points are scanned directly (the
/// tree's bounds are weak on rough data such as scattered points; scans with early exit are
/// predictable); longer ones are checked against kSpreadProbes points, then through the tree.
inline constexpr int kDirectSpan = 1024;
inline constexpr int kSpreadProbes = 32;
/// build_rows measures chords spanning more points than this through the tree (nearly straight
/// stretches, e.g. around an inflection, make long rows).
inline constexpr int kRowTreeSpan = 512;
/// Streaming probes (min_count by layers): chords spanning more points than this meet the O(1)
/// slope filter before the tree.
inline constexpr int kSlopeFilterSpan = 64;
/// Cone pruning samples the points from p_i on, far from i only every ((k - i) / kConeSamples)-th
/// (O(kConeSamples log reach) per scan); the slope filter every ((k - i) / kSlopeFilterSamples)-th.
inline constexpr int kConeSamples = 32;
inline constexpr int kSlopeFilterSamples = 64;
/// The projection plane of cone pruning: a second chord from p_i that is this close to the line
/// of the first (relative to its length) does not define a plane; any plane through the line
/// will do (every plane is sound, this one keeps most of the bending).
inline constexpr double kStraightRatio = 1e-9;

}  // namespace sculpt::curves::detail
