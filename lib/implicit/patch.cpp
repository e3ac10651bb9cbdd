#include "implicit/patch.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "base/errors.hpp"
#include "curves/digitized_curve.hpp"
#include "implicit/detail/plane_curve.hpp"

namespace sculpt::implicit {
namespace {

using Vec = Eigen::Vector3d;
using detail::PlaneCurve;
using detail::PlaneCurveEnd;
using detail::PlaneFrame;

constexpr int kMaxDepth = 8;           // 4^8 = 65,536 triangles
constexpr double kResidual = 0.25e-12;  // Newton target, times the length scale (the bound is 1e-12)

std::string fmt(const Vec& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.9g, %.9g, %.9g)", p.x(), p.y(), p.z());
  return buffer;
}

std::string fmt(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

std::string corner_name(int i) { return "P" + std::to_string(i); }

bool lexicographically_less(const Vec& a, const Vec& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// A plane with a unit normal whose first non-zero component is positive, so that the same plane
// given either way round (or computed from its corners in either order) has the same frame.
PatchPlane canonical(const Vec& normal, double offset) {
  const double length = normal.norm();
  Vec n = normal / length;
  double c = offset / length;
  for (int axis = 0; axis < 3; ++axis) {
    if (n[axis] != 0.0) {
      if (n[axis] < 0.0) n = -n, c = -c;
      break;
    }
  }
  return {n, c};
}

// One curve of the refinement: a piece of f = 0 on a plane between two mesh vertices.
struct Edge {
  int v0 = -1, v1 = -1;      // mesh vertices; points run from v0 to v1
  PlaneFrame plane;
  double residual_target = 0.0;  // Newton target of its points (absolute)
  std::vector<Vec> points;   // the traced curve; just {v0, v1} for an edge of the last level
  int boundary = -1;         // 0..2: a piece of boundary curve i; -1: an interior edge
  int level = 0;             // the level of the triangles it bounds
  int mid = -1;              // the vertex splitting it, once split
  int child0 = -1, child1 = -1;  // the pieces (v0, mid) and (mid, v1)
};

struct Triangle {
  std::array<int, 3> v{};  // counter-clockwise in the corners' order
  std::array<int, 3> e{};  // e[k] joins v[k] and v[k+1]
};

class PatchBuilder {
 public:
  PatchBuilder(const Expression& f, const PatchOptions& options) : f_(f), o_(options) {}
  PatchResult run();

 private:
  void validate();
  void setup_planes_and_corners();
  [[nodiscard]] ValueGradient eval(const Vec& p) const { return f_.value_gradient(p); }
  [[nodiscard]] Vec unit_normal(const Vec& p) const;
  void trace(Edge& edge, int segments);
  void split(int edge, int segments);
  [[nodiscard]] int child_at(int edge, int vertex) const;
  int new_edge(int a, int b, const Vec& side_normal, int level);
  [[nodiscard]] std::string describe(const Edge& edge, const PlaneCurve& curve) const;

  const Expression& f_;
  PatchOptions o_;
  double scale_ = 0.0;  // diagonal of the corners' bounding box
  Box box_;             // the traced curves must stay inside: the corners' box grown by scale_
  std::array<PatchPlane, 3> planes_{};
  std::vector<Vec> vertices_;
  std::vector<Edge> edges_;
  PatchResult result_;
};

void PatchBuilder::validate() {
  if (o_.depth < 0 || o_.depth > kMaxDepth)
    throw InvalidInput("patch: depth " + std::to_string(o_.depth) + " is outside 0.." + std::to_string(kMaxDepth) +
                       " (4^depth triangles)");
  for (int i = 0; i < 3; ++i)
    if (!o_.corners[i].allFinite()) throw InvalidInput("patch: corner " + corner_name(i) + " is not finite");
  Eigen::AlignedBox3d extent;
  for (const Vec& p : o_.corners) extent.extend(p);
  scale_ = extent.diagonal().norm();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (!((o_.corners[i] - o_.corners[j]).norm() > 1e-9 * scale_))
      throw InvalidInput("patch: corners " + corner_name(i) + " and " + corner_name(j) + " coincide");
  }
  if (!std::isfinite(o_.tolerance) || o_.tolerance < 0.0)
    throw InvalidInput("patch: tolerance must be finite and >= 0 (0: automatic)");
  if (o_.tolerance > 0.0 && o_.tolerance < 1e-9 * scale_)
    throw InvalidInput("patch: tolerance " + fmt(o_.tolerance) + " is below 1e-9 times the corners' box diagonal");
  if (o_.points_per_segment < 2) throw InvalidInput("patch: points_per_segment must be >= 2");
  if (!std::isfinite(o_.corner_tolerance) || o_.corner_tolerance < 0.0)
    throw InvalidInput("patch: corner_tolerance must be finite and >= 0");
  if (o_.max_steps <= 0) throw InvalidInput("patch: max_steps must be > 0");
  if (o_.method == curves::Method::MinCount)
    throw InvalidInput("patch: method mincount takes a tolerance; the patch needs LAs of 2^k segments");
  box_ = {.lo = extent.min() - Vec::Constant(scale_), .hi = extent.max() + Vec::Constant(scale_)};
}

Vec PatchBuilder::unit_normal(const Vec& p) const {
  const Vec g = eval(p).gradient;
  const double n = g.norm();
  if (!(n > 0.0)) throw GeometryError("patch: grad f vanishes at " + fmt(p) + ": no surface normal there");
  return g / n;
}

// The corners onto the surface (sec. 5.2: "the triangle T0 = (P0, P1, P2)" with its corners on
// f = 0) and the clipping planes h_i through them.
void PatchBuilder::setup_planes_and_corners() {
  const double target = kResidual * scale_;
  const double allowed = o_.corner_tolerance * scale_;
  std::array<Vec, 3>& P = o_.corners;
  if (o_.planes) {
    for (int i = 0; i < 3; ++i) {
      const PatchPlane& h = (*o_.planes)[i];
      if (!h.normal.allFinite() || !std::isfinite(h.offset) || !(h.normal.norm() > 0.0))
        throw InvalidInput("patch: plane " + std::to_string(i) + " needs a finite, non-zero normal and a finite offset");
      planes_[i] = canonical(h.normal, h.offset);
    }
  }
  for (int i = 0; i < 3; ++i) {
    const ValueGradient vg = eval(P[i]);
    const double g = vg.gradient.norm();
    if (!(g > 0.0)) throw InvalidInput("patch: grad f vanishes at corner " + corner_name(i) + " " + fmt(P[i]));
    const double residual = std::abs(vg.value) / g;
    if (residual > allowed)
      throw InvalidInput("patch: corner " + corner_name(i) + " " + fmt(P[i]) + " is not on the surface: |f|/|grad f| = " +
                         fmt(residual) + ", more than corner_tolerance times the corners' box diagonal (" +
                         fmt(allowed) + ")");
    if (!o_.planes) {
      // Newton along the gradient (the shortest move onto the linearized surface).
      Vec p = P[i];
      for (int k = 0; k < 20; ++k) {
        const ValueGradient c = eval(p);
        if (std::abs(c.value) <= target * c.gradient.norm()) break;
        p -= c.value / c.gradient.squaredNorm() * c.gradient;
      }
      P[i] = p;
      continue;
    }
    // Newton on f = 0 and the corner's two planes, h_(i-1) and h_i.
    const PatchPlane& a = planes_[(i + 2) % 3];
    const PatchPlane& b = planes_[i];
    for (const PatchPlane* h : {&a, &b}) {
      if (std::abs(h->normal.dot(P[i]) - h->offset) > allowed + 1e-12 * scale_)
        throw InvalidInput("patch: corner " + corner_name(i) + " " + fmt(P[i]) + " is not on its clipping plane " +
                           fmt(h->normal) + " . p = " + fmt(h->offset));
    }
    Vec p = P[i];
    for (int k = 0; k < 20; ++k) {
      const ValueGradient c = eval(p);
      const Vec r(c.value, a.normal.dot(p) - a.offset, b.normal.dot(p) - b.offset);
      if (std::abs(r[0]) <= target * c.gradient.norm() && std::abs(r[1]) <= 1e-15 * scale_ &&
          std::abs(r[2]) <= 1e-15 * scale_)
        break;
      Eigen::Matrix3d J;
      J.row(0) = c.gradient.transpose();
      J.row(1) = a.normal.transpose();
      J.row(2) = b.normal.transpose();
      if (!(std::abs(J.determinant()) > 1e-10 * c.gradient.norm()))
        throw InvalidInput("patch: at corner " + corner_name(i) + " the surface and its two planes do not meet in a point");
      p -= J.partialPivLu().solve(r);
    }
    // On a coordinate plane the corner lies on it exactly.
    for (const PatchPlane* h : {&a, &b})
      for (int axis = 0; axis < 3; ++axis)
        if (h->normal[(axis + 1) % 3] == 0.0 && h->normal[(axis + 2) % 3] == 0.0) p[axis] = h->offset * h->normal[axis];
    P[i] = p;
  }
  for (int i = 0; i < 3; ++i) {
    const ValueGradient c = eval(P[i]);
    if (std::abs(c.value) > 4.0 * target * c.gradient.norm() || (P[i] - o_.corners[i]).norm() > 2.0 * allowed + target)
      throw InvalidInput("patch: corner " + corner_name(i) + " could not be moved onto the surface (and its planes)");
  }
  if (o_.planes) return;
  // Default planes: through both corners, containing the mean of their unit normals (the paper's
  // rule for new edges, applied to the surface normals at the two ends). Computed from the corners
  // in lexicographic order, so a neighbouring patch computes the same plane.
  for (int i = 0; i < 3; ++i) {
    Vec a = P[i], b = P[(i + 1) % 3];
    if (lexicographically_less(b, a)) std::swap(a, b);
    const Vec mean = unit_normal(a) + unit_normal(b);
    const Vec n = (b - a).cross(mean);
    if (!(n.norm() > 1e-8 * (b - a).norm() * std::max(mean.norm(), 1e-300)) || !(mean.norm() > 1e-8))
      throw GeometryError("patch: no clipping plane can be chosen between " + corner_name(i) + " and " +
                          corner_name((i + 1) % 3) + " (the surface normals there cancel or run along the chord); "
                          "give .planes");
    const PatchPlane h = canonical(n, 0.0);
    planes_[i] = {h.normal, 0.5 * (h.normal.dot(a) + h.normal.dot(b))};
  }
}

std::string PatchBuilder::describe(const Edge& edge, const PlaneCurve& curve) const {
  switch (curve.end) {
    case PlaneCurveEnd::LeftBox:
      return "it leaves the box of the corners (grown by their diagonal) near " + fmt(curve.last);
    case PlaneCurveEnd::Closed:
      return "it closes on itself without passing the end point";
    case PlaneCurveEnd::Stuck:
      return "it stops at a singular point of f = 0 on the plane near " + fmt(curve.last);
    case PlaneCurveEnd::Budget:
      return "the step budget (max_steps = " + std::to_string(o_.max_steps) + ") ran out";
    case PlaneCurveEnd::Reached:
      break;
  }
  (void)edge;
  return "it reaches the end point";
}

// Traces the curve of `edge` (f = 0 on its plane, from v0 to v1) with enough points for an LA of
// `segments` segments (sec. 5.2: "each boundary curve ... is traced to produce a digitized space curve").
void PatchBuilder::trace(Edge& edge, int segments) {
  const Vec& from = vertices_[edge.v0];
  const Vec& to = vertices_[edge.v1];
  const double span = (to - from).norm();
  const long left = o_.max_steps - result_.steps;
  const PlaneCurve curve = detail::trace_on_plane(
      f_, edge.plane, from, to,
      {.tolerance = o_.tolerance > 0.0 ? o_.tolerance : 1e-3 * span,
       .max_step = span / (o_.points_per_segment * segments),
       .residual_target = edge.residual_target,
       .box = box_,
       .max_steps = std::max(left, 1L)});
  result_.steps += curve.steps;
  ++result_.traced_curves;
  if (curve.end != PlaneCurveEnd::Reached) {
    const std::string what =
        edge.boundary >= 0 ? "the boundary curve (plane " + std::to_string(edge.boundary) + ") from " + fmt(from) + " to " +
                                 fmt(to)
                           : "the level-" + std::to_string(edge.level) + " edge from " + fmt(from) + " to " + fmt(to) +
                                 " (on the plane through the averaged triangle normals)";
    throw GeometryError("patch: " + what + " does not connect its end points: " + describe(edge, curve));
  }
  edge.points = curve.points;
}

// Splits an edge at the centre vertex of its LA of order `segments` (sec. 5.2: "Q_i is the
// center point of each LA of order 2^d"); the two pieces keep the traced points.
void PatchBuilder::split(int id, int segments) {
  if (edges_[id].mid >= 0) return;
  // A piece too short for its LA (the centre of the parent's LA may fall near one end) is traced again.
  if (static_cast<int>(edges_[id].points.size()) < 2 * segments + 1) trace(edges_[id], segments);
  const Edge& e = edges_[id];
  const curves::DigitizedCurve curve{.points = e.points, .dimension = 3, .closed = false, .name = "patch edge"};
  const curves::Linearization la = curves::linearize(curve, {.segments = segments, .method = o_.method});
  const int index = la.indices[static_cast<std::size_t>(segments / 2)];
  const int mid = static_cast<int>(vertices_.size());
  vertices_.push_back(e.points[static_cast<std::size_t>(index)]);
  Edge first = e, second = e;
  first.v1 = mid;
  first.points.assign(e.points.begin(), e.points.begin() + index + 1);
  second.v0 = mid;
  second.points.assign(e.points.begin() + index, e.points.end());
  first.level = second.level = e.level + 1;
  first.mid = second.mid = -1;
  first.child0 = first.child1 = second.child0 = second.child1 = -1;
  const int c0 = static_cast<int>(edges_.size());
  edges_.push_back(std::move(first));
  edges_.push_back(std::move(second));
  edges_[id].mid = mid;
  edges_[id].child0 = c0;
  edges_[id].child1 = c0 + 1;
}

int PatchBuilder::child_at(int id, int vertex) const {
  const Edge& e = edges_[id];
  return e.v0 == vertex ? e.child0 : e.child1;
}

// A new edge a-b of level `level`, on the plane through a and b containing `side_normal` (the
// mean of its two triangles' normals; sec. 5.2). Only its end points until it is traced.
int PatchBuilder::new_edge(int a, int b, const Vec& side_normal, int level) {
  const Vec& pa = vertices_[a];
  const Vec& pb = vertices_[b];
  const Vec n = (pb - pa).cross(side_normal);
  if (!(n.norm() > 0.0))
    throw GeometryError("patch: the triangles beside the level-" + std::to_string(level) + " edge " + fmt(pa) + " - " +
                        fmt(pb) + " are degenerate");
  const PatchPlane h = canonical(n, 0.0);
  Edge e;
  e.v0 = a;
  e.v1 = b;
  e.plane = PlaneFrame::make(h.normal, 0.5 * (h.normal.dot(pa) + h.normal.dot(pb)));
  e.residual_target = kResidual * scale_;
  e.points = {pa, pb};
  e.level = level;
  edges_.push_back(std::move(e));
  return static_cast<int>(edges_.size()) - 1;
}

PatchResult PatchBuilder::run() {
  validate();
  setup_planes_and_corners();
  result_.planes = planes_;
  vertices_.assign(o_.corners.begin(), o_.corners.end());
  const int d = o_.depth;

  // The three boundary curves, each traced from its lexicographically smaller corner.
  std::array<int, 3> roots{};
  for (int i = 0; i < 3; ++i) {
    Edge e;
    e.v0 = i;
    e.v1 = (i + 1) % 3;
    if (lexicographically_less(vertices_[e.v1], vertices_[e.v0])) std::swap(e.v0, e.v1);
    e.plane = PlaneFrame::make(planes_[i].normal, planes_[i].offset);
    // Depends on the curve alone, so that a neighbouring patch traces the same points.
    e.residual_target = kResidual * (vertices_[e.v1] - vertices_[e.v0]).norm();
    e.boundary = i;
    roots[i] = static_cast<int>(edges_.size());
    edges_.push_back(std::move(e));
    trace(edges_[roots[i]], 1 << d);
  }

  // Level by level (an explicit loop, no recursion): split every edge of the current triangles
  // at the centre of its LA of order 2^(d - level), then each triangle into four.
  std::vector<Triangle> triangles{{{0, 1, 2}, roots}};
  for (int level = 0; level < d; ++level) {
    const int segments = 1 << (d - level);
    for (const Triangle& t : triangles)
      for (const int e : t.e) split(e, segments);
    std::vector<Triangle> next;
    next.reserve(4 * triangles.size());
    for (const Triangle& t : triangles) {
      const auto [v0, v1, v2] = t.v;
      const int a = edges_[t.e[0]].mid, b = edges_[t.e[1]].mid, c = edges_[t.e[2]].mid;
      const Vec &pa = vertices_[a], &pb = vertices_[b], &pc = vertices_[c];
      const Vec centre_normal = (pb - pa).cross(pc - pa).normalized();
      auto normal = [&](int x, int y, int z) {
        return (vertices_[y] - vertices_[x]).cross(vertices_[z] - vertices_[x]).normalized();
      };
      // "The clipping planes of subdivided triangles can be computed by averaging the normals of
      // the two triangles incident to the edge" (sec. 5.2).
      const int ac = new_edge(a, c, normal(v0, a, c) + centre_normal, level + 1);
      const int ab = new_edge(a, b, normal(a, v1, b) + centre_normal, level + 1);
      const int bc = new_edge(b, c, normal(c, b, v2) + centre_normal, level + 1);
      if (level + 1 < d) {
        for (const int e : {ac, ab, bc}) trace(edges_[e], segments / 2);
      }
      next.push_back({{v0, a, c}, {child_at(t.e[0], v0), ac, child_at(t.e[2], v0)}});
      next.push_back({{a, v1, b}, {child_at(t.e[0], v1), child_at(t.e[1], v1), ab}});
      next.push_back({{c, b, v2}, {bc, child_at(t.e[1], v2), child_at(t.e[2], v2)}});
      next.push_back({{a, b, c}, {ab, bc, ac}});
    }
    triangles = std::move(next);
  }

  // Faces counter-clockwise seen from where grad f points (out of the solid f <= 0).
  const Vec n0 = (vertices_[1] - vertices_[0]).cross(vertices_[2] - vertices_[0]);
  const Vec g = unit_normal(vertices_[0]) + unit_normal(vertices_[1]) + unit_normal(vertices_[2]);
  result_.flipped = n0.dot(g) < 0.0;
  result_.mesh.faces.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    if (result_.flipped)
      result_.mesh.faces.push_back({t.v[0], t.v[2], t.v[1]});
    else
      result_.mesh.faces.push_back({t.v[0], t.v[1], t.v[2]});
  }
  // The boundary vertices in order, from the leaves of each boundary curve's split tree.
  for (int i = 0; i < 3; ++i) {
    std::vector<int>& chain = result_.boundary[i];
    chain.push_back(edges_[roots[i]].v0);
    std::vector<int> stack{roots[i]};
    while (!stack.empty()) {
      const Edge& e = edges_[stack.back()];
      stack.pop_back();
      if (e.mid < 0) {
        chain.push_back(e.v1);
      } else {
        stack.push_back(e.child1);
        stack.push_back(e.child0);
      }
    }
    if (chain.front() != i) std::reverse(chain.begin(), chain.end());
  }
  result_.mesh.vertices = std::move(vertices_);
  return std::move(result_);
}

}  // namespace

PatchResult patch(const Expression& f, const PatchOptions& options) {
  PatchBuilder builder(f, options);
  return builder.run();
}

}  // namespace sculpt::implicit
