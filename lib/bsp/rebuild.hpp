#pragma once
/// \file rebuild.hpp
/// A new tree for a solid from its own boundary (Thibault & Naylor 1987, autopartition): the same
/// point set, exactly (the boundary fragments are plane-based; nothing is rounded), with a tree
/// that reflects only the current boundary. A tree grown by many set operations (a workpiece
/// carved stroke by stroke) keeps every plane that once split a cell near the strokes; the
/// rebuilt tree has only the planes of faces that still exist, plus balancing splits.

#include <Eigen/Geometry>

#include "bsp/from_mesh.hpp"
#include "bsp/solid.hpp"

namespace sculpt {

/// The solid with a tree built from its boundary fragments (carried, or extracted from the tree).
Solid rebuild_from_boundary(const Solid& solid);
/// The same with the planes chosen as from_mesh chooses them (the expected depth of a point query,
/// `options`' candidates, samples and charges; its grid and snapping settings do not apply): the
/// B-rep to BSP build of the solid's exact boundary, which needs no snapping, so it cannot fold
/// or meet degenerate faces as a rebuild from the rounded mesh could (issue 35).
Solid rebuild_from_boundary(const Solid& solid, const FromMeshOptions& options);

/// Which subtrees rebuild_region() rebuilds.
struct RegionRebuildOptions {
  /// A subtree of at most this many nodes whose cell meets the region is a candidate; a larger
  /// one is not rebuilt, its children that meet the region are looked at instead.
  int max_subtree_nodes = 1536;
  /// Candidates smaller than this are left alone (little to gain for the cost of looking).
  int min_subtree_nodes = 256;
  /// At most this many nodes are rebuilt per call, the largest candidates first.
  int max_nodes = 1536;
  /// A rebuilt subtree replaces the old one only if it has at most this share of its nodes.
  double keep_below = 0.75;
  /// Nothing is rebuilt while the tree has at most this many nodes per boundary fragment of the
  /// solid (0: always look; a solid that carries no boundary is always looked at).
  double above_nodes_per_fragment = 0;
  /// The nodes a rebuilt subtree is expected to have per boundary fragment in its cell: a
  /// candidate whose fragments predict more than keep_below of its nodes is not rebuilt.
  double nodes_per_fragment = 0.6;
};

/// What rebuild_region() did.
struct RegionRebuildStats {
  int candidates = 0;    ///< subtrees that qualified
  int rebuilt = 0;       ///< subtrees replaced
  int nodes_before = 0;  ///< nodes of the replaced subtrees
  int nodes_after = 0;   ///< nodes that replaced them
};

/// Keeps a tree grown by local set operations in check (SCULPT's strokes): the subtrees whose
/// cells meet `region` (world units; e.g. a stroke's extent) are rebuilt from the solid's boundary
/// inside their cells (autopartition restricted to a cell, Thibault & Naylor 1987), each only if
/// the new subtree is smaller by options.keep_below. The same point set, exactly. In place: the
/// solid's storage is reused as by the in-place set operations (nothing outside the rebuilt
/// subtrees moves; their old nodes become free slots), so the cost follows the nodes rebuilt,
/// at most about options.max_nodes, not the tree's size. `stats`, if given, is filled.
Solid rebuild_region(Solid&& solid, const Eigen::AlignedBox3d& region, const RegionRebuildOptions& options = {},
                     RegionRebuildStats* stats = nullptr);
/// rebuild_region() over the extent of `near` (the box of its carried boundary, else of its
/// mesh), e.g. the sweep of a stroke just carved.
Solid rebuild_region(Solid&& solid, const Solid& near, const RegionRebuildOptions& options = {},
                     RegionRebuildStats* stats = nullptr);

}  // namespace sculpt
