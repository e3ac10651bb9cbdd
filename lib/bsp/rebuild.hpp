#pragma once
/// \file rebuild.hpp
/// A new tree for a solid from its own boundary (Thibault & Naylor 1987, autopartition): the same
/// point set, exactly (the boundary fragments are plane-based; nothing is rounded), with a tree
/// that reflects only the current boundary. A tree grown by many set operations (a workpiece
/// carved stroke by stroke) keeps every plane that once split a cell near the strokes; the
/// rebuilt tree has only the planes of faces that still exist, plus balancing splits.

#include "bsp/solid.hpp"

namespace sculpt {

/// The solid with a tree built from its boundary fragments (carried, or extracted from the tree).
Solid rebuild_from_boundary(const Solid& solid);

}  // namespace sculpt
