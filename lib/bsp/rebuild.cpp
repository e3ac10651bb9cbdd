#include "bsp/rebuild.hpp"

#include "bsp/tree/autopartition.hpp"
#include "bsp/tree/solid_access.hpp"

namespace sculpt {

Solid rebuild_from_boundary(const Solid& solid) {
  if (is_leaf(solid.root())) return solid;
  bsp::detail::Arena arena;
  (void)arena.append(solid);
  std::vector<BoundaryFragment> fragments = arena.boundary_of(solid);
  if (fragments.empty()) return solid;  // no boundary: a leaf in effect
  return bsp::detail::SolidAccess::at_grid(bsp::detail::autopartition(arena, std::move(fragments)), solid.grid());
}

}  // namespace sculpt
