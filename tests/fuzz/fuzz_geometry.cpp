// libFuzzer target over the geometry built-ins (issue 14): the fuzzer's bytes are decoded as a
// small structured program (at most kMaxOps operations), written as sculpt script text and run
// statement by statement in one interpreter, so the language glue (number literals, argument
// conversion, the solid operators, export/import through files) is fuzzed with the geometry.
// Every solid the program makes is then checked in C++ against invariants that must hold for any
// input; a violation prints the script and aborts (libFuzzer records it as a crash).
//
// Decoding (one byte chooses the operation, the following bytes its arguments; missing bytes read
// as 0; an operand is "an earlier value", chosen modulo the values made so far):
//   box       corners on a 1/16 grid in [-8, 8), optionally moved by k * 2^-15 (features near
//             the kernel's grid step), extents 1/16 .. 4
//   sphere / cylinder / cone   radius and height 1/8 .. 4 (1/16 grid), 3 .. 24 segments (sphere:
//             3 .. 12, it has about segments^2 / 2 faces; under ASan one 16-segment sphere
//             operation takes about a second)
//   translate by a 1/16-grid vector (optionally plus k * 2^-15)
//   rotate    about an axis of small integers in [-3, 3] by a multiple of 90, of 45, of 30, a
//             general angle (k / 64 degrees) or a tiny one (k * 1e-4 degrees)
//   scale     by one factor or per-axis factors from {1, 2, 3, -1, -2, 0.5, 1.5, 0.75, -0.5, 0.1}
//   union / difference / intersection of two earlier values (possibly the same one)
//   union_all of two or three earlier values
//   revolve   of a profile of 2 .. 5 [r, z] points (z increasing, r >= 0, possibly 0 at the ends)
//             along circle(n), circle(r, n) or ellipse(a, b, n), n in 3 .. 24
//   import    of an earlier value exported to .off/.obj/.ply/.stl (export then import), or of a
//             small closed mesh the harness writes: a tetrahedron or an octahedron with perturbed
//             vertices (dyadic or not), or of two such meshes in one file, the second possibly
//             inside out: they may cross, and import takes where the winding number is positive
//   touching  an earlier value | a box on the outside of its bounding box: the faces coplanar,
//             or touching along an edge or at a corner (on the snapped extreme vertices, so a
//             cylinder's or cone's vertex can lie on the box's face)
//
// Invariants (each solid; docs/kernel.md for the bounds):
//   - to_mesh is closed and consistently oriented: every edge once in each direction, every vertex
//     one fan (duplicated vertices only as the 2-manifold exception), no face repeats a vertex;
//     the empty solid gives the empty mesh
//   - volume(solid) equals the mesh's signed volume (1e-9 relative)
//   - s - s is empty; a | a and a & a (when the program makes them) have a's volume
//   - classify() of a few grid points away from the boundary agrees with a ray-parity count on
//     the mesh; "on" only within 1e-6 of the mesh
//   - set operations: V(a|b) + V(a&b) = V(a) + V(b) and V(a-b) = V(a) - V(a&b) (1e-9 relative:
//     the operations are exact on exact operands, transforms or not); union_all = the fold of |
//   - exact maps (translations, quarter turns about coordinate axes, integer scales) keep the
//     volume (times |det|) to 1e-9; other maps within surface area x one grid step
//   - box volume is the product of its extents; revolve's volume is revolved_volume() of the
//     snapped profile and path (exact polytope, 1e-9)
//   - import of an exported solid: volume within area x grid step (non-grid vertices snap);
//     import of a harness mesh: the signed volume of its snapped vertices (1e-9)
//   - import of two crossing shells a, b in one file: the volume of a | b (b inside out: a - b)
//     made from the shells imported one by one (1e-9; winding numbers add)
//   - a box touching a solid's bounding box from outside: V(a | box) = V(a) + V(box) (1e-9)
// Errors: a ScriptError carrying a typed library error (invalid input, geometry error, out of
// range) is an expected outcome; any other error text (a std::logic_error, say) is a finding, as
// is an export/import round trip refused as "not a closed manifold".
//
// FUZZ_GEOMETRY_VERBOSE=1 prints each program and every error it meets (to read a reproducer).
// FUZZ_GEOMETRY_STRICT=1 also aborts on what docs/kernel.md lists as not yet solved (distinct
// mesh vertices with identical coordinates, zero-area faces); by default they are counted and the
// counts printed at exit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/convex_path.hpp"
#include "bsp/set_operations.hpp"
#include "kernel/grid.hpp"
#include "language/interpreter.hpp"
#include "language/parser.hpp"
#include "language/solid_values.hpp"
#include "revolution/revolve.hpp"
#include "revolution/revolve_boundary.hpp"
#include "support/mesh_checks.hpp"

namespace {

using namespace sculpt;
using namespace sculpt::language;
using Eigen::Vector3d;

constexpr int kMaxOps = 6;
constexpr double kStep = kernel::kGridStep;

bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && *v != '0';
}
const bool kVerbose = env_flag("FUZZ_GEOMETRY_VERBOSE");
const bool kStrict = env_flag("FUZZ_GEOMETRY_STRICT");

// Counts of what docs/kernel.md lists as not yet solved, printed at exit.
struct Known {
  long programs = 0, solids = 0, errors = 0, duplicate_vertices = 0, zero_area_faces = 0;
  std::map<std::string, long> error_kinds;
  ~Known() {
    std::fprintf(stderr,
                 "fuzz_geometry: %ld programs, %ld solids checked, %ld typed errors; meshes with distinct vertices at "
                 "the same point (not pinches) %ld, with zero-area faces %ld\n",
                 programs, solids, errors, duplicate_vertices, zero_area_faces);
    for (const auto& [k, n] : error_kinds) std::fprintf(stderr, "fuzz_geometry:   %6ld x %s\n", n, k.c_str());
  }
} known;

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t u8() { return at_ < size_ ? data_[at_++] : 0; }
  int s8() { return static_cast<std::int8_t>(u8()); }
  int s16() { return static_cast<std::int16_t>(static_cast<std::uint16_t>(u8() | (u8() << 8))); }
  [[nodiscard]] bool done() const { return at_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

std::string num(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return {buf, r.ptr};
}
std::string vec(const Vector3d& v) {
  // Appended piece by piece: "[" + num(...) trips a false -Wrestrict in GCC 12's inlined std::string.
  std::string s = "[";
  s += num(v.x());
  s += ", ";
  s += num(v.y());
  s += ", ";
  s += num(v.z());
  s += "]";
  return s;
}

// A coordinate on the 1/16 grid in [-8, 8), sometimes moved by a few kernel grid steps.
double coordinate(Bytes& in) {
  const int flags = in.u8();
  double c = in.s8() / 16.0;
  if ((flags & 3) == 3) c += in.s8() * kStep;
  return c;
}
Vector3d point(Bytes& in) { return {coordinate(in), coordinate(in), coordinate(in)}; }
double extent(Bytes& in) {  // 1/16 .. 4, sometimes plus a few grid steps
  const int b = in.u8();
  double e = (1 + b % 64) / 16.0;
  if (b >= 224) e += (b - 223) * kStep;
  return e;
}
double radius(Bytes& in) { return (2 + in.u8() % 63) / 16.0; }  // 1/8 .. 4
int segments(Bytes& in) { return 3 + in.u8() % 22; }            // 3 .. 24

[[noreturn]] void finding(const std::string& script, const std::string& what) {
  std::fprintf(stderr, "\n==== fuzz_geometry: invariant violated ====\n%s\n---- program ----\n%s----\n", what.c_str(),
               script.c_str());
  std::abort();
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

void check_near(const std::string& script, const std::string& what, double got, double expected, double tolerance) {
  if (!(std::abs(got - expected) <= tolerance))
    finding(script, what + ": got " + fmt(got) + ", expected " + fmt(expected) + " (difference " +
                        fmt(got - expected) + ", tolerance " + fmt(tolerance) + ")");
}

// ---- ray parity on a mesh (long double, independent of lib/bsp) ----

using P = std::array<long double, 3>;
P to_p(const Vector3d& v) { return {v.x(), v.y(), v.z()}; }
P sub(const P& a, const P& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
long double dot(const P& a, const P& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P cross(const P& a, const P& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
P axpy(long double s, const P& a, const P& b) { return {s * a[0] + b[0], s * a[1] + b[1], s * a[2] + b[2]}; }

struct Triangle {
  P a, b, c;
};

std::vector<Triangle> fan_triangles(const PolygonMesh& m) {
  std::vector<Triangle> t;
  for (const auto& f : m.faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k)
      t.push_back({to_p(m.vertices[std::size_t(f[0])]), to_p(m.vertices[std::size_t(f[k])]),
                   to_p(m.vertices[std::size_t(f[k + 1])])});
  return t;
}

// Distance from p to triangle (Ericson, Real-Time Collision Detection 5.1.5).
long double distance(const P& p, const Triangle& t) {
  const P ab = sub(t.b, t.a), ac = sub(t.c, t.a), ap = sub(p, t.a);
  const long double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto len = [&](const P& q) { return std::sqrt(dot(sub(p, q), sub(p, q))); };
  if (d1 <= 0 && d2 <= 0) return len(t.a);
  const P bp = sub(p, t.b);
  const long double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return len(t.b);
  const long double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return len(axpy(d1 / (d1 - d3), ab, t.a));
  const P cp = sub(p, t.c);
  const long double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return len(t.c);
  const long double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return len(axpy(d2 / (d2 - d6), ac, t.a));
  const long double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return len(axpy((d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(t.c, t.b), t.b));
  const long double denom = 1 / (va + vb + vc);
  const P q = axpy(vb * denom, ab, axpy(vc * denom, ac, t.a));  // a + v ab + w ac
  return len(q);
}

// Parity of the crossings of the ray p + s d (s > 0): 1 inside, 0 outside, -1 when the ray grazes
// an edge or a vertex or runs along a face (the caller tries another direction).
int ray_parity(const P& p, const P& d, const std::vector<Triangle>& tris) {
  int crossings = 0;
  for (const Triangle& t : tris) {
    const P e1 = sub(t.b, t.a), e2 = sub(t.c, t.a);
    const P h = cross(d, e2);
    const long double det = dot(e1, h);
    const long double scale = std::sqrt(dot(e1, e1) * dot(e2, e2));
    if (scale == 0) continue;  // degenerate triangle: no area to cross
    const P s = sub(p, t.a);
    if (std::abs(det) <= 1e-12L * scale) {
      // Ray parallel to the triangle's plane: harmless unless it lies in it.
      const P n = cross(e1, e2);
      if (std::abs(dot(n, s)) <= 1e-12L * std::sqrt(dot(n, n)) * (1 + std::sqrt(dot(s, s)))) return -1;
      continue;
    }
    const long double inv = 1 / det;
    const long double u = dot(s, h) * inv;
    const P q = cross(s, e1);
    const long double v = dot(d, q) * inv;
    const long double w = dot(e2, q) * inv;  // ray parameter
    const long double eps = 1e-9L;
    if (u < -eps || v < -eps || u + v > 1 + eps || w < -eps) continue;
    if (u < eps || v < eps || u + v > 1 - eps || w < eps) return -1;  // too close to call
    ++crossings;
  }
  return crossings % 2;
}

// ---- the program ----

struct Program {
  Interpreter interpreter{{.out = nullptr, .allow_files = true, .max_steps = 200000}};
  std::ostringstream printed;
  std::string script;  // every statement run so far (for the report)
  std::vector<std::string> names;  // values made so far (each a solid)
  std::string dir;

  explicit Program(std::string directory) : dir(std::move(directory)) {}

  // Runs one statement; returns the error text if it failed with a ScriptError.
  std::optional<std::string> run(const std::string& statement) {
    script += statement + "\n";
    auto source = std::make_shared<SourceFile>();
    source->name = "<fuzz>";
    source->text = statement;
    try {
      interpreter.run(source);
    } catch (const ScriptError& e) {
      const std::string text = format_error(e);
      script += "#   -> " + text.substr(0, text.find('\n')) + "\n";
      if (kVerbose) std::fprintf(stderr, "error: %s\n", text.c_str());
      return text;
    }
    return std::nullopt;
  }

  const Solid* solid(const std::string& name) const {
    const Value* v = interpreter.global(name);
    if (v == nullptr) return nullptr;
    const SolidValue* s = v->object<SolidValue>();
    return s == nullptr ? nullptr : &s->solid;
  }
};

// A typed library error (or a refusal the docs describe) is an expected outcome; anything else is a finding.
void check_error(const Program& prog, const std::string& error) {
  ++known.errors;
  std::string kind;
  for (const char* k : {"invalid input: ", "geometry error: ", "out of range: "}) {
    const std::size_t at = error.find(k);
    if (at != std::string::npos) {
      // The kind and the first words of the message, for the summary at exit.
      const std::size_t start = error.rfind(' ', at == 0 ? 0 : at - 1);
      kind = error.substr(start == std::string::npos ? 0 : start + 1, at - start + std::strlen(k) + 28);
      break;
    }
  }
  if (kind.empty() && error.find("meet when the vertices are snapped") != std::string::npos) kind = "import: snapped mesh self-intersects";
  if (kind.empty() && error.find("is not a closed manifold") != std::string::npos) kind = "import: not a closed manifold";
  if (kind.empty() && error.find("oriented the wrong way") != std::string::npos) kind = "import: a shell oriented the wrong way";
  if (kind.empty()) finding(prog.script, "untyped error: " + error);
  kind = kind.substr(0, kind.find('\n'));
  ++known.error_kinds[kind];
}

struct Facts {
  double volume = 0, area = 0;
  PolygonMesh mesh;
};

// Invariants of one solid on its own.
Facts check_solid(Program& prog, const std::string& name, Bytes& in) {
  const Solid* s = prog.solid(name);
  if (s == nullptr) finding(prog.script, name + " is not a solid");
  ++known.solids;
  Facts f;
  f.mesh = to_mesh(*s);
  f.volume = volume(*s);
  f.area = surface_area(*s);
  const PolygonMesh& m = f.mesh;
  // Where to classify: the box's centre and three points from the bytes (read first, so the
  // layout of the input does not depend on the result).
  std::array<Vector3d, 4> at;
  at[0] = Vector3d::Constant(0.5);
  for (int k = 1; k < 4; ++k) at[std::size_t(k)] = {in.u8() / 255.0, in.u8() / 255.0, in.u8() / 255.0};
  if (s->is_empty()) {
    if (!m.faces.empty() || f.volume != 0) finding(prog.script, name + ": empty solid with a non-empty mesh or volume");
    return f;
  }
  if (m.faces.empty()) finding(prog.script, name + ": non-empty solid (a tree) with an empty mesh");
  if (auto r = checks::VerticesManifold(m); !r) finding(prog.script, name + ": to_mesh: " + r.message());
  for (std::size_t k = 0; k < m.faces.size(); ++k) {
    std::vector<int> c = m.faces[k];
    std::sort(c.begin(), c.end());
    if (std::adjacent_find(c.begin(), c.end()) != c.end())
      finding(prog.script, name + ": to_mesh: face " + std::to_string(k) + " repeats a vertex");
  }
  // Known, not yet solved (docs/kernel.md): distinct exact vertices that round alike, zero-area faces.
  {
    // A pinch duplicates a vertex once per sheet; the copies are in different fans of one point.
    // Copies that share a face (or an edge) are not a pinch.
    bool suspicious = false;
    for (const auto& face : m.faces) {
      std::map<std::tuple<double, double, double>, int> in_face;
      for (int v : face) {
        const Vector3d& p = m.vertices[std::size_t(v)];
        if (++in_face[{p.x(), p.y(), p.z()}] > 1) suspicious = true;
      }
    }
    if (suspicious) {
      ++known.duplicate_vertices;
      if (kStrict) finding(prog.script, name + ": a face has two distinct vertices with the same coordinates");
    }
    if (auto r = checks::NoDegenerateFaces(m); !r) {
      ++known.zero_area_faces;
      if (kStrict) finding(prog.script, name + ": " + r.message());
    }
  }
  // Volume from the mesh.
  double max_coord = 0;
  for (const Vector3d& v : m.vertices) max_coord = std::max(max_coord, v.cwiseAbs().maxCoeff());
  const double mesh_v = static_cast<double>(checks::reference_signed_volume(m));
  check_near(prog.script, name + ": volume() vs the mesh's signed volume", f.volume, mesh_v,
             1e-9 * std::abs(mesh_v) + 1e-12 * f.area * (1 + max_coord));
  if (!(f.volume > 0)) finding(prog.script, name + ": non-empty solid with volume " + fmt(f.volume));
  // s - s (s | s and s & s when the program makes them: the operations' checks).
  if (!subtract(*s, *s).is_empty()) finding(prog.script, name + " - " + name + " is not empty");
  // Classification against ray parity, at grid points in the bounding box.
  Eigen::AlignedBox3d box;
  for (const Vector3d& v : m.vertices) box.extend(v);
  const std::vector<Triangle> tris = fan_triangles(m);
  const P directions[] = {{0.5773502691896258L, 0.5773502691896257L, 0.5773502691896259L},
                          {0.2672612419124244L, -0.5345224838248488L, 0.8017837257372732L},
                          {-0.7071067811865475L, 0.1414213562373095L, -0.6928203230275509L}};
  for (const Vector3d& t : at) {
    const Vector3d world = box.min() + (box.max() - box.min()).cwiseProduct(t);
    const Vector3d p = kernel::to_world(kernel::snap(world));
    const Location where = classify(*s, p).location;
    long double dmin = 1e300L;
    for (const Triangle& tri : tris) dmin = std::min(dmin, distance(to_p(p), tri));
    if (dmin < 1e-6L) continue;  // near the boundary: rounding of the mesh could decide either way
    if (where == Location::Boundary) finding(prog.script, name + ": classify says \"on\" at " + vec(p) + ", " + fmt(double(dmin)) + " from the mesh");
    for (const P& d : directions) {
      const int parity = ray_parity(to_p(p), d, tris);
      if (parity < 0) continue;
      if ((parity == 1) != (where == Location::Inside))
        finding(prog.script, name + ": classify says \"" + (where == Location::Inside ? "in" : "out") + "\" at " + vec(p) +
                                 " but the ray parity on the mesh says " + (parity == 1 ? "in" : "out"));
      break;
    }
  }
  return f;
}

// The harness's own closed meshes, written as OFF: a tetrahedron or an octahedron with perturbed vertices.
PolygonMesh small_mesh(Bytes& in) {
  PolygonMesh m;
  const int kind = in.u8();
  const double size = radius(in);
  const Vector3d centre = point(in) / 2;
  if (kind % 2 == 0) {
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  } else {
    m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  }
  static const double units[] = {1.0 / 16, 1.0 / 1024, kStep, 1e-7, 0.0123};
  const double unit = units[(kind / 2) % 5];
  for (Vector3d& v : m.vertices) v = centre + size * v + Vector3d(in.s8(), in.s8(), in.s8()) * unit / 8;
  return m;
}

void write_off(const PolygonMesh& m, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << m.vertices.size() << " " << m.faces.size() << " 0\n";
  for (const Vector3d& v : m.vertices) out << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : m.faces) {
    out << f.size();
    for (int v : f) out << " " << v;
    out << "\n";
  }
}

const std::string& work_dir() {
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() / ("sculpt_fuzz_geometry_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  return dir;
}

bool exact_rotation(const Vector3d& axis, double degrees) {
  const int zeros = int(axis.x() == 0) + int(axis.y() == 0) + int(axis.z() == 0);
  return zeros == 2 && std::fmod(degrees, 90.0) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  Program prog(work_dir());
  std::vector<Facts> facts;  // of prog.names, in order
  ++known.programs;
  for (int op = 0; op < kMaxOps && !in.done(); ++op) {
    const std::string name = "v" + std::to_string(op);
    const int code = in.u8() % 14;
    const int count = static_cast<int>(prog.names.size());
    auto pick = [&]() { return static_cast<int>(in.u8() % std::max(count, 1)); };
    std::string expr;
    std::function<void(const Facts&)> check_op = [](const Facts&) {};
    // Operations on earlier values fall back to a box when there is none yet.
    const bool needs_operand = (code >= 3 && code <= 8) || code == 10 || code == 13;
    const int kind = needs_operand && count == 0 ? 0 : code;
    switch (kind) {
      case 0: {  // box
        const Vector3d lo = point(in);
        const Vector3d hi = lo + Vector3d(extent(in), extent(in), extent(in));
        expr = "box(" + vec(lo) + ", " + vec(hi) + ")";
        const double expected = (hi - lo).prod();
        check_op = [&prog, expected, name](const Facts& f) {
          check_near(prog.script, name + ": box volume", f.volume, expected, 1e-12 * expected);
        };
        break;
      }
      case 1: {  // a sphere has about segments^2 / 2 faces: 3 .. 12 segments keep it small
        const double r = radius(in);
        expr = "sphere(" + num(r) + ", segments=" + std::to_string(3 + in.u8() % 10) + ")";
        break;
      }
      case 2: {
        const int which = in.u8();
        const double r = radius(in), h = radius(in);
        expr = std::string(which % 2 ? "cone(" : "cylinder(") + num(r) + ", " + num(h) + ", segments=" +
               std::to_string(segments(in)) + ")";
        break;
      }
      case 3: {  // translate
        const int a = pick();
        const Vector3d v = point(in);
        expr = "translate(" + prog.names[a] + ", " + vec(v) + ")";
        const Facts& fa = facts[a];
        check_op = [&prog, &fa, name](const Facts& f) {
          check_near(prog.script, name + ": translated volume", f.volume, fa.volume, 1e-9 * fa.volume);
        };
        break;
      }
      case 4: {  // rotate
        const int a = pick();
        Vector3d axis(in.u8() % 7 - 3, in.u8() % 7 - 3, in.u8() % 7 - 3);
        if (axis.isZero()) axis = Vector3d(0, 0, 1);
        const int mode = in.u8();
        const int k = in.s8();
        double degrees = 0;
        switch (mode % 5) {
          case 0: degrees = 90.0 * (k % 5); break;
          case 1: degrees = 45.0 * (k % 9); break;
          case 2: degrees = 30.0 * (k % 13); break;
          case 3: degrees = in.s16() / 64.0; break;
          default: degrees = k * 1e-4; break;
        }
        expr = "rotate(" + prog.names[a] + ", " + vec(axis) + ", " + num(degrees) + ")";
        const Facts& fa = facts[a];
        const bool exact = exact_rotation(axis, degrees);
        check_op = [&prog, &fa, name, exact](const Facts& f) {
          const double tol = exact ? 1e-9 * fa.volume : fa.area * kStep + 1e-9 * fa.volume;
          check_near(prog.script, name + ": rotated volume", f.volume, fa.volume, tol);
        };
        break;
      }
      case 5: {  // scale
        const int a = pick();
        static const double factors[] = {1, 2, 3, -1, -2, 0.5, 1.5, 0.75, -0.5, 0.1};
        const int mode = in.u8();
        Vector3d v;
        if (mode % 2 == 0) {
          v = Vector3d::Constant(factors[in.u8() % 10]);
          expr = "scale(" + prog.names[a] + ", " + num(v.x()) + ")";
        } else {
          v = Vector3d(factors[in.u8() % 10], factors[in.u8() % 10], factors[in.u8() % 10]);
          expr = "scale(" + prog.names[a] + ", " + vec(v) + ")";
        }
        const Facts& fa = facts[a];
        const bool exact = v == v.array().round().matrix();
        const double det = std::abs(v.prod());
        const double grow = v.cwiseAbs().maxCoeff();
        check_op = [&prog, &fa, name, exact, det, grow](const Facts& f) {
          const double expected = det * fa.volume;
          const double tol = exact ? 1e-9 * expected : grow * grow * fa.area * kStep + 1e-9 * expected;
          check_near(prog.script, name + ": scaled volume", f.volume, expected, tol);
        };
        break;
      }
      case 6:
      case 7: {  // set operations
        const int a = pick(), b = pick();
        const int which = in.u8() % 3;
        const char* op_text[] = {" | ", " - ", " & "};
        expr = prog.names[a] + op_text[which] + prog.names[b];
        const std::string na = prog.names[a], nb = prog.names[b];
        const Facts &fa = facts[a], &fb = facts[b];
        check_op = [&prog, &fa, &fb, na, nb, name, a, b, which](const Facts& f) {
          const Solid& sa = *prog.solid(na);
          const Solid& sb = *prog.solid(nb);
          // The script's result is one of the three; the other two are made here.
          const double u = which == 0 ? f.volume : volume(unite(sa, sb));
          const double d = which == 1 ? f.volume : volume(subtract(sa, sb));
          const double i = which == 2 ? f.volume : volume(intersect(sa, sb));
          const double tol = 1e-9 * (fa.volume + fb.volume);
          check_near(prog.script, name + ": V(a|b) + V(a&b) vs V(a) + V(b)", u + i, fa.volume + fb.volume, tol);
          check_near(prog.script, name + ": V(a-b) vs V(a) - V(a&b)", d, fa.volume - i, tol);
          if (a == b) {
            check_near(prog.script, name + ": V(a|a)", u, fa.volume, tol);
            check_near(prog.script, name + ": V(a&a)", i, fa.volume, tol);
            if (d != 0) finding(prog.script, name + ": V(a-a) = " + fmt(d));
          }
        };
        break;
      }
      case 8: {  // union_all
        const int n = 2 + in.u8() % 2;
        std::vector<int> items;
        for (int k = 0; k < n; ++k) items.push_back(pick());
        expr = "union_all([";
        for (int k = 0; k < n; ++k) expr += (k ? ", " : "") + prog.names[items[k]];
        expr += "])";
        std::vector<std::string> item_names;
        for (int k : items) item_names.push_back(prog.names[k]);
        check_op = [&prog, item_names, name](const Facts& f) {
          Solid fold = *prog.solid(item_names[0]);
          for (std::size_t k = 1; k < item_names.size(); ++k) fold = unite(fold, *prog.solid(item_names[k]));
          const double v = volume(fold);
          check_near(prog.script, name + ": union_all vs the fold of |", f.volume, v, 1e-9 * v);
          // Same set: the symmetric difference is empty.
          const Solid& s = *prog.solid(name);
          if (!subtract(s, fold).is_empty() || !subtract(fold, s).is_empty())
            finding(prog.script, name + ": union_all differs from the fold of | as a set");
        };
        break;
      }
      case 9: {  // revolve
        const int n_points = 2 + in.u8() % 4;
        std::vector<Eigen::Vector2d> profile;
        double z = in.s8() / 16.0;
        for (int k = 0; k < n_points; ++k) {
          double r = (in.u8() % 64) / 16.0;
          if ((k == 0 || k == n_points - 1) && (in.u8() % 3 == 0)) r = 0;
          profile.emplace_back(r, z);
          z += (1 + in.u8() % 32) / 16.0;
        }
        std::string list = "[";
        for (std::size_t k = 0; k < profile.size(); ++k)
          list += (k ? ", [" : "[") + num(profile[k].x()) + ", " + num(profile[k].y()) + "]";
        list += "]";
        const int path_kind = in.u8() % 3;
        const int n = segments(in);
        ConvexPath path;
        std::string path_text;
        if (path_kind == 0) {
          path = circular_path(n);
          path_text = "circle(" + std::to_string(n) + ")";
        } else if (path_kind == 1) {
          const double r = radius(in);
          path = circular_path(n, r);
          path_text = "circle(" + num(r) + ", " + std::to_string(n) + ")";
        } else {
          const double ea = radius(in), eb = radius(in);
          path = ellipse_path(ea, eb, n);
          path_text = "ellipse(" + num(ea) + ", " + num(eb) + ", " + std::to_string(n) + ")";
        }
        expr = "revolve(" + list + ", " + path_text + ")";
        check_op = [&prog, profile, path, name](const Facts& f) {
          const revolution::SnappedRevolution snapped = revolution::snap_revolution(profile, path);
          const double expected = revolution::revolved_volume(snapped.profile, snapped.path);
          check_near(prog.script, name + ": revolve volume vs revolved_volume of the snapped inputs", f.volume, expected,
                     1e-9 * expected);
        };
        break;
      }
      case 10: {  // export an earlier value, import it back
        const int a = pick();
        static const char* formats[] = {"off", "obj", "ply", "stl"};
        const std::string path = prog.dir + "/m." + formats[in.u8() % 4];
        if (auto error = prog.run("export(" + prog.names[a] + ", \"" + path + "\")")) {
          check_error(prog, *error);
          break;
        }
        // strict: an export that does not read back as a clean mesh stays a finding (without it,
        // import takes the region of positive winding number).
        expr = "import(\"" + path + "\", strict=true)";
        const Facts& fa = facts[a];
        check_op = [&prog, &fa, name](const Facts& f) {
          check_near(prog.script, name + ": volume after export and import", f.volume, fa.volume,
                     2 * fa.area * kStep + 1e-9 * fa.volume);
        };
        break;
      }
      case 12: {  // import two small closed meshes in one file: they may cross (winding import)
        PolygonMesh a = small_mesh(in), b = small_mesh(in);
        const bool inverted = in.u8() % 2 == 1;  // b's faces turned inside out
        if (inverted)
          for (auto& face : b.faces) std::reverse(face.begin(), face.end());
        PolygonMesh both = a;
        const int offset = static_cast<int>(a.vertices.size());
        both.vertices.insert(both.vertices.end(), b.vertices.begin(), b.vertices.end());
        for (auto face : b.faces) {
          for (int& v : face) v += offset;
          both.faces.push_back(face);
        }
        for (const auto& [file, mesh] : {std::pair{"a.off", &a}, std::pair{"b.off", &b}, std::pair{"ab.off", &both}}) {
          write_off(*mesh, prog.dir + "/" + file);
          std::ostringstream text;
          text.precision(17);
          text << "# " << file << ":";
          for (const Vector3d& v : mesh->vertices) text << " [" << v.x() << ", " << v.y() << ", " << v.z() << "]";
          prog.script += text.str() + "\n";
        }
        // The reference, from the two shells imported one by one (b as written: inverted, it is
        // refused, so it is read the right way round): the winding number of the pair is
        // w_a + w_b (or w_a - w_b), positive exactly on a | b (or a - b).
        if (inverted)
          for (auto& face : b.faces) std::reverse(face.begin(), face.end());
        write_off(b, prog.dir + "/b.off");
        std::optional<std::string> error = prog.run("wa = import(\"" + prog.dir + "/a.off\", strict=true)");
        if (!error) error = prog.run("wb = import(\"" + prog.dir + "/b.off\", strict=true)");
        if (!error) error = prog.run(std::string("wr = wa ") + (inverted ? "-" : "|") + " wb");
        if (error) {
          check_error(prog, *error);
          break;
        }
        const double expected = volume(*prog.solid("wr"));
        expr = "import(\"" + prog.dir + "/ab.off\")";
        check_op = [&prog, expected, name](const Facts& f) {
          check_near(prog.script, name + ": winding import vs the shells' set operation", f.volume, expected,
                     1e-9 * std::abs(expected) + 1e-12);
        };
        break;
      }
      case 13: {  // a box touching an earlier value's bounding box from outside: volumes add
        const int a = pick();
        const Facts& fa = facts[a];
        if (fa.mesh.vertices.empty()) break;
        Vector3d lo = fa.mesh.vertices[0], hi = lo;
        for (const Vector3d& v : fa.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        const int axis = in.u8() % 3;
        const bool upper = in.u8() % 2 == 1;
        Vector3d blo, bhi;
        for (int k = 0; k < 3; ++k) {
          if (k == axis) {
            const double e = extent(in);
            blo[k] = upper ? hi[k] : lo[k] - e;
            bhi[k] = upper ? hi[k] + e : lo[k];
            continue;
          }
          // across the other axes: the same span (faces coplanar), about half of it, or beyond a
          // side (touching along an edge or at a corner). The middle is rounded down to the 1/16
          // grid: a half grid step would be snapped by box() and the volumes would not add.
          double mid = std::floor(8 * (lo[k] + hi[k])) / 16;
          if (!(mid > lo[k])) mid = hi[k];
          switch (in.u8() % 4) {
            case 0:
              blo[k] = lo[k], bhi[k] = hi[k];
              break;
            case 1:
              blo[k] = lo[k], bhi[k] = mid;
              break;
            case 2:
              blo[k] = hi[k], bhi[k] = hi[k] + extent(in);
              break;
            default:
              blo[k] = lo[k] - extent(in), bhi[k] = mid;
              break;
          }
          if (!(bhi[k] > blo[k])) bhi[k] = blo[k] + 1.0 / 16;
        }
        // On the kernel grid, as box() puts them (a sphere's extreme vertices are not grid points):
        // the touching side rounded away from the solid, so the box touches it or stays a
        // fraction of a step clear, and the volumes still add.
        for (int k = 0; k < 3; ++k) {
          const bool away_up = k == axis && upper, away_down = k == axis && !upper;
          const double lo_steps = blo[k] / kStep, hi_steps = bhi[k] / kStep;
          blo[k] = (away_up ? std::ceil(lo_steps) : std::round(lo_steps)) * kStep;
          bhi[k] = (away_down ? std::floor(hi_steps) : std::round(hi_steps)) * kStep;
          if (!(bhi[k] > blo[k])) bhi[k] = blo[k] + 1.0 / 16;
        }
        const double box_volume = (bhi - blo).prod();
        expr = prog.names[a] + " | box(" + vec(blo) + ", " + vec(bhi) + ")";
        check_op = [&prog, &fa, box_volume, name](const Facts& f) {
          check_near(prog.script, name + ": a box touching from outside adds its volume", f.volume,
                     fa.volume + box_volume, 1e-9 * (fa.volume + box_volume));
        };
        break;
      }
      default: {  // import a small closed mesh written by the harness
        const PolygonMesh m = small_mesh(in);
        const std::string path = prog.dir + "/r.off";
        write_off(m, path);
        std::ostringstream text;
        text.precision(17);
        text << "# r.off:";
        for (const Vector3d& v : m.vertices) text << " [" << v.x() << ", " << v.y() << ", " << v.z() << "]";
        prog.script += text.str() + "\n";
        // strict: the volume check below is for a clean mesh; a harness mesh that intersects
        // itself is refused as before (the winding import has its own tests).
        expr = "import(\"" + path + "\", strict=true)";
        PolygonMesh snapped = m;
        for (Vector3d& v : snapped.vertices) v = kernel::to_world(kernel::snap(v));
        const double expected = static_cast<double>(checks::reference_signed_volume(snapped));
        check_op = [&prog, expected, name](const Facts& f) {
          check_near(prog.script, name + ": imported volume vs the snapped mesh's", f.volume, expected,
                     1e-9 * std::abs(expected));
        };
        break;
      }
    }
    if (expr.empty()) continue;
    std::optional<std::string> error = prog.run(name + " = " + expr);
    // A vertex of one part touching another part's face or edge is a corner of both in the export
    // (mesh/touching_vertices.hpp), so the strict import never sees faces meeting.
    if (error && kind == 10 && error->find("self-intersection") != std::string::npos)
      finding(prog.script, "an exported to_mesh is refused on strict import: " + *error);
    if (error) {
      // Text formats and binary PLY carry doubles exactly; binary STL rounds to float32 (lossy).
      if (kind == 10 && expr.find(".stl") == std::string::npos &&
          error->find("not a closed manifold") != std::string::npos)
        finding(prog.script, "an exported to_mesh is refused on import: " + *error);
      check_error(prog, *error);
      continue;
    }
    Facts f = check_solid(prog, name, in);
    check_op(f);
    prog.names.push_back(name);
    facts.push_back(std::move(f));
  }
  if (kVerbose) std::fprintf(stderr, "---- program ----\n%s", prog.script.c_str());
  return 0;
}
