#include "bsp/local/deferred_build.hpp"

#include <stdexcept>
#include <utility>

#include "bsp/tree/boundary_clipper.hpp"
#include "bsp/tree/solid_access.hpp"

namespace sculpt::bsp::detail {

DeferredBuild::DeferredBuild(kernel::PlaneTable planes, FragmentList fragments, std::optional<bool> far_in,
                             const AutopartitionOptions& options, std::shared_ptr<const TriangleMesh> source)
    : planes_(std::move(planes)),
      fragments_(std::move(fragments)),
      far_in_(far_in),
      options_(options),
      source_(std::move(source)) {}

DeferredBuild::DeferredBuild(kernel::PlaneTable planes, FragmentList fragments, std::optional<bool> far_in,
                             std::function<Solid()> build)
    : planes_(std::move(planes)), fragments_(std::move(fragments)), far_in_(far_in), build_(std::move(build)) {}

Solid DeferredBuild::build() {
  // Nothing here is consumed, so a build stopped by Ctrl-C (base/cancel.hpp) can run again later:
  // the builder works from its parameters, autopartition from copies.
  if (build_) return build_();
  Arena arena;
  arena.planes = planes_;
  AutopartitionOptions options = options_;
  options.carry_boundary = true;
  return autopartition(arena, fragments_, options);
}

Solid solid_from_boundary(kernel::PlaneTable planes, FragmentList fragments, std::optional<bool> far_in,
                          const AutopartitionOptions& options, std::shared_ptr<const TriangleMesh> source) {
  if (fragments.empty()) {
    if (!far_in) throw std::logic_error("solid_from_boundary: no fragments and no status");
    return Solid::leaf(*far_in);
  }
  return SolidAccess::deferred(
      std::make_unique<DeferredBuild>(std::move(planes), std::move(fragments), far_in, options, std::move(source)));
}

Solid solid_with_tree_later(kernel::PlaneTable planes, FragmentList fragments, bool far_in,
                            std::function<Solid()> build) {
  return SolidAccess::deferred(
      std::make_unique<DeferredBuild>(std::move(planes), std::move(fragments), far_in, std::move(build)));
}

std::optional<bool> far_status(const Solid& solid) {
  if (const std::optional<bool> known = SolidAccess::deferred_far_in(solid)) return known;
  if (solid.tree_deferred()) return std::nullopt;  // never built for this
  const Solid::BoundaryView view = solid.boundary_view();
  if (view.fragments && !bounds(*view.fragments).valid && !view.fragments->empty()) return std::nullopt;
  // The leaf reached by a piece of the world box face x = max (Clipper::far_status), walked on
  // the solid's own planes: only the negative part of a split is followed, so the opposite plane
  // (the positive part's new edge) is never needed.
  const kernel::PlaneTable& planes = solid.planes();
  kernel::ConvexPolygon poly = kernel::world_polygon(planes, 0);
  TreeRef t = solid.root();
  while (!is_leaf(t)) {
    const BspNode& n = solid.nodes()[std::size_t(t)];
    kernel::PolygonSplit s = kernel::split(planes, poly, n.plane, n.plane);
    if (s.side == kernel::Side::Both) {
      poly = std::move(s.negative);
      t = n.negative;
    } else {
      t = s.side == kernel::Side::Positive ? n.positive : n.negative;
    }
  }
  return t == kIn;
}

}  // namespace sculpt::bsp::detail
