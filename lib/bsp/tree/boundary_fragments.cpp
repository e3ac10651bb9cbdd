#include "bsp/tree/boundary_fragments.hpp"

#include <algorithm>

#include "bsp/tree/node_polygons.hpp"

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::Side;

namespace {

class Extractor {
 public:
  explicit Extractor(const Solid& s) : solid_(s) {
    if (std::any_of(s.polygons().begin(), s.polygons().end(), pending)) {
      arena_ = with_node_polygons(s);  // its plane table extends the solid's
      polygons_ = &arena_.polygons;
    } else {
      arena_.planes = s.planes();
    }
  }

  // Pushes `poly` down the subtree `t` and calls out(piece, in) for every leaf reached.
  template <typename Out>
  void push_down(TreeRef t, ConvexPolygon poly, Out&& out) {
    stack_.clear();
    const kernel::CornerBox box = kernel::corner_box(poly);
    stack_.push_back({t, std::move(poly), box});
    // The polygon on top of the stack descends in place; only splits push a second one. Its
    // corner box is kept with it, so most nodes are passed with one quick box test.
    while (!stack_.empty()) {
      Piece& top = stack_.back();
      const TreeRef r = top.at;
      if (is_leaf(r)) {
        out(std::move(top.polygon), r == kIn);
        stack_.pop_back();
        continue;
      }
      const BspNode& n = solid_.nodes()[std::size_t(r)];
      const Side quick = kernel::box_side(top.box, arena_.planes[n.plane]);
      if (quick == Side::Negative || quick == Side::Positive) {
        top.at = quick == Side::Negative ? n.negative : n.positive;
        continue;
      }
      const std::int32_t opp = arena_.opposite(n.plane);
      kernel::PolygonSplit s = kernel::split(arena_.planes, top.polygon, n.plane, opp);
      switch (s.side) {
        case Side::Negative: top.at = n.negative; break;
        case Side::Positive: top.at = n.positive; break;
        case Side::Both: {
          const kernel::CornerBox nb = kernel::corner_box(s.negative), pb = kernel::corner_box(s.positive);
          top = {n.negative, std::move(s.negative), nb};
          stack_.push_back({n.positive, std::move(s.positive), pb});
          break;
        }
        case Side::On: {  // a descendant on the same plane violates the invariant; follow both
          top.at = n.negative;
          Piece copy = top;
          copy.at = n.positive;
          stack_.push_back(std::move(copy));
          break;
        }
      }
    }
  }

  Fragments run() {
    Fragments result;
    std::vector<std::pair<ConvexPolygon, bool>> negative_pieces;
    // Nodes reachable from the root (storage may hold unreachable nodes, see Solid).
    std::vector<TreeRef> order;
    if (!is_leaf(solid_.root())) order.push_back(solid_.root());
    for (std::size_t j = 0; j < order.size(); ++j) {
      const BspNode& m = solid_.nodes()[std::size_t(order[j])];
      if (!is_leaf(m.negative)) order.push_back(m.negative);
      if (!is_leaf(m.positive)) order.push_back(m.positive);
    }
    // Subtree sizes (children come after parents in `order`): the polygon goes first into the
    // smaller subtree, so fewer pieces travel through the larger one.
    std::vector<std::int32_t> size(solid_.nodes().size(), 0);
    auto size_of = [&](TreeRef r) { return is_leaf(r) ? 0 : size[std::size_t(r)]; };
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
      const BspNode& m = solid_.nodes()[std::size_t(*it)];
      size[std::size_t(*it)] = 1 + size_of(m.negative) + size_of(m.positive);
    }
    for (const TreeRef node : order) {
      const std::size_t i = std::size_t(node);
      const BspNode& n = solid_.nodes()[i];
      // An auxiliary plane carries no face of any operand, hence no boundary (the boundary of
      // a regularized set operation lies on its operands' boundaries).
      if (solid_.planes().auxiliary(n.plane)) continue;
      const bool neg_first = size_of(n.negative) <= size_of(n.positive);
      const TreeRef first = neg_first ? n.negative : n.positive, second = neg_first ? n.positive : n.negative;
      negative_pieces.clear();
      push_down(first, (*polygons_)[i],
                [&](ConvexPolygon p, bool in) { negative_pieces.emplace_back(std::move(p), in); });
      for (auto& [piece, first_in] : negative_pieces) {
        const bool fi = first_in;
        push_down(second, std::move(piece), [&](ConvexPolygon p, bool second_in) {
          if (fi != second_in) result.fragments.push_back({std::move(p), neg_first ? second_in : fi});
        });
      }
    }
    result.planes = std::move(arena_.planes);
    return result;
  }

 private:
  const Solid& solid_;
  Arena arena_;
  const std::vector<ConvexPolygon>* polygons_ = &solid_.polygons();
  struct Piece {
    TreeRef at;
    ConvexPolygon polygon;
    kernel::CornerBox box;
  };
  std::vector<Piece> stack_;
};

}  // namespace

Fragments boundary_fragments(const Solid& solid) { return Extractor(solid).run(); }

}  // namespace sculpt::bsp::detail
