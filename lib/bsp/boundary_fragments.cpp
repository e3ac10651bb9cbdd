#include "bsp/boundary_fragments.hpp"

namespace sculpt::detail {

using kernel::ConvexPolygon;
using kernel::Side;

namespace {

class Extractor {
 public:
  explicit Extractor(const Solid& s) : solid_(s) {
    arena_.planes = s.planes();
  }

  // Pushes `poly` down the subtree `t` and calls out(piece, in) for every leaf reached.
  template <typename Out>
  void push_down(TreeRef t, ConvexPolygon poly, Out&& out) {
    stack_.clear();
    stack_.push_back({t, std::move(poly)});
    while (!stack_.empty()) {
      auto [r, p] = std::move(stack_.back());
      stack_.pop_back();
      if (is_leaf(r)) {
        out(std::move(p), r == kIn);
        continue;
      }
      const BspNode& n = solid_.nodes()[std::size_t(r)];
      const std::int32_t opp = arena_.opposite(n.plane);
      kernel::PolygonSplit s = kernel::split(arena_.planes, p, n.plane, opp);
      switch (s.side) {
        case Side::Negative: stack_.push_back({n.negative, std::move(p)}); break;
        case Side::Positive: stack_.push_back({n.positive, std::move(p)}); break;
        case Side::Both:
          stack_.push_back({n.negative, std::move(s.negative)});
          stack_.push_back({n.positive, std::move(s.positive)});
          break;
        case Side::On:  // a descendant on the same plane violates the invariant; follow both
          stack_.push_back({n.negative, p});
          stack_.push_back({n.positive, std::move(p)});
          break;
      }
    }
  }

  Fragments run() {
    Fragments result;
    std::vector<std::pair<ConvexPolygon, bool>> negative_pieces;
    for (std::size_t i = 0; i < solid_.nodes().size(); ++i) {
      const BspNode& n = solid_.nodes()[i];
      negative_pieces.clear();
      push_down(n.negative, solid_.polygons()[i],
                [&](ConvexPolygon p, bool in) { negative_pieces.emplace_back(std::move(p), in); });
      for (auto& [piece, neg_in] : negative_pieces) {
        const bool ni = neg_in;
        push_down(n.positive, std::move(piece), [&](ConvexPolygon p, bool pos_in) {
          if (ni != pos_in) result.fragments.push_back({std::move(p), pos_in});
        });
      }
    }
    result.planes = std::move(arena_.planes);
    return result;
  }

 private:
  const Solid& solid_;
  Arena arena_;
  std::vector<std::pair<TreeRef, ConvexPolygon>> stack_;
};

}  // namespace

Fragments boundary_fragments(const Solid& solid) { return Extractor(solid).run(); }

}  // namespace sculpt::detail
