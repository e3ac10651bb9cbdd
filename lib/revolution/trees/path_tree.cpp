#include "revolution/trees/path_tree.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "base/errors.hpp"

namespace sculpt::revolution::detail {
namespace {

/// Where a subtree goes: the root, or one child of a node.
struct Slot {
  int node;  // -1: root
  bool outside;
};

class Builder {
 public:
  Builder(const ConvexPath& path, const PathTreeOptions& options) : n_(path.edges()), opt_(options) {}

  PathTree build(const ConvexPath& path) {
    const std::array<int, 4> ext = extremes(path);
    // Sub-curves between consecutive extremes (counter-clockwise); empty ones are dropped.
    std::vector<std::array<int, 2>> subs;  // first vertex, edge count
    for (int q = 0; q < 4; ++q) {
      const int a = ext[q], b = ext[(q + 1) % 4];
      const int count = (b - a + n_) % n_;
      if (count > 0) subs.push_back({a, count});
    }
    if (subs.size() == 1) subs = {{ext[0], n_}};  // unreachable for a strictly convex path
    // Chord of each sub-curve; the in-cell is the intersection of their inside halfplanes.
    // With only two sub-curves the two chords coincide: the second one's cap is the inside.
    Slot slot{-1, false};
    for (std::size_t s = 0; s < subs.size(); ++s) {
      const auto [a, count] = subs[s];
      if (subs.size() == 2 && s == 1) {
        // A single edge here lies on the first chord, whose inside is then outside the path.
        if (count == 1)
          set(slot, kOut);
        else
          cap(a, count, slot);
        break;
      }
      const int k = add({a, vertex(a + count), count == 1 ? PathTree::Kind::Face : PathTree::Kind::Chord,
                         kIn, kOut},
                        slot);
      if (count > 1) cap(a, count, {k, true});
      slot = {k, false};
      if (s + 1 == subs.size()) set(slot, kIn);
    }
    run();
    return std::move(tree_);
  }

 private:
  struct Task {
    int first, count;  // a chain of `count` edges starting at vertex `first`
    Slot slot;
  };

  int vertex(int i) const { return ((i % n_) + n_) % n_; }

  /// Indices of the rightmost, topmost, leftmost and bottommost vertices, counter-clockwise in
  /// that order. Of two tied vertices the later one (counter-clockwise) is taken.
  std::array<int, 4> extremes(const ConvexPath& path) const {
    const auto& v = path.vertices;
    auto key = [&](int i, int q) {
      switch (q) {
        case 0: return v[i].x();
        case 1: return v[i].y();
        case 2: return -v[i].x();
        default: return -v[i].y();
      }
    };
    std::array<int, 4> out{};
    for (int q = 0; q < 4; ++q) {
      double best = key(0, q);
      for (int i = 1; i < n_; ++i) best = std::max(best, key(i, q));
      for (int i = 0; i < n_; ++i)
        if (key(i, q) == best && key(vertex(i + 1), q) != best) out[q] = i;
    }
    return out;
  }

  void set(Slot s, int child) {
    if (s.node < 0)
      tree_.root = child;
    else if (s.outside)
      tree_.nodes[s.node].outside = child;
    else
      tree_.nodes[s.node].inside = child;
  }

  int add(PathTree::Node node, Slot s) {
    tree_.nodes.push_back(node);
    const int k = static_cast<int>(tree_.nodes.size()) - 1;
    set(s, k);
    return k;
  }

  /// Queues the tree of the cap between a chain and its chord (the chord is already in place).
  void cap(int first, int count, Slot s) { tasks_.push_back({first, count, s}); }

  void run() {
    while (!tasks_.empty()) {
      const Task t = tasks_.back();
      tasks_.pop_back();
      if (t.count <= opt_.face_only_below) {
        // Few edges: their own lines, each with an out-cell outside; the last inside is in.
        Slot s = t.slot;
        for (int e = 0; e < t.count; ++e)
          s = {add({vertex(t.first + e), vertex(t.first + e + 1), PathTree::Kind::Face, kIn, kOut}, s),
               false};
        continue;
      }
      // Median edge: out-cell outside its line; then the chords from the chain's first vertex to
      // the median edge's start, and from its end to the chain's last vertex; in-cell between.
      const int left = t.count / 2, right = t.count - left - 1;
      const int m0 = vertex(t.first + left), m1 = vertex(t.first + left + 1);
      const int face = add({m0, m1, PathTree::Kind::Face, kIn, kOut}, t.slot);
      const int c0 = add({vertex(t.first), m0, left == 1 ? PathTree::Kind::Face : PathTree::Kind::Chord,
                          kIn, kOut},
                         {face, false});
      if (left > 1) cap(t.first, left, {c0, true});
      const int c1 = add({m1, vertex(t.first + t.count), right == 1 ? PathTree::Kind::Face : PathTree::Kind::Chord,
                          kIn, kOut},
                         {c0, false});
      if (right > 1) cap(m1, right, {c1, true});
    }
  }

  int n_;
  PathTreeOptions opt_;
  PathTree tree_;
  std::vector<Task> tasks_;
};

}  // namespace

PathTree build_path_tree(const ConvexPath& path, const PathTreeOptions& options) {
  if (options.face_only_below < 2)
    throw InvalidInput("path tree: face_only_below must be >= 2, got " + std::to_string(options.face_only_below));
  if (path.edges() < 3) throw InvalidInput("path tree: the path needs at least 3 edges");
  return Builder(path, options).build(path);
}

int PathTree::classify(const ConvexPath& path, const Eigen::Vector2d& q) const {
  int k = root;
  while (k >= 0) {
    const Node& node = nodes[k];
    const Eigen::Vector2d& a = path.vertices[node.from];
    const Eigen::Vector2d& b = path.vertices[node.to];
    const double side = (b - a).x() * (q - a).y() - (b - a).y() * (q - a).x();  // > 0: left = inside
    k = side >= 0.0 ? node.inside : node.outside;
  }
  return k;
}

int PathTree::height() const {
  int best = 0;
  std::vector<std::array<int, 2>> stack;  // node, depth
  if (root >= 0) stack.push_back({root, 1});
  while (!stack.empty()) {
    const auto [k, d] = stack.back();
    stack.pop_back();
    best = std::max(best, d);
    for (int c : {nodes[k].inside, nodes[k].outside})
      if (c >= 0) stack.push_back({c, d + 1});
  }
  return best;
}

}  // namespace sculpt::revolution::detail
