// Built-ins of the solids area: primitives, transforms, classification, measures, mesh export
// and import (lib/bsp, lib/mesh; Ihm & Naylor 1990 sec. 6, Naylor et al. 1990).
#include <filesystem>
#include <sstream>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "language/builtins.hpp"
#include "language/solid_values.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/self_intersection.hpp"
#include "bsp/from_mesh.hpp"

namespace sculpt::language {
namespace {

Eigen::Vector3d vector3(const Arguments& args, std::size_t i) {
  const auto v = args.vector(i, 3);
  return {v[0], v[1], v[2]};
}

const Solid& solid_arg(const Arguments& args, std::size_t i) { return args.object<SolidValue>(i, "a solid").solid; }

// The exact kernel snaps vertices to its grid (docs/kernel.md). A valid mesh with features below
// the grid step can become self-intersecting that way (faces 1e-6 apart now touch) without any
// face turning over, which from_mesh would catch: check the snapped copy as well.
std::string snapped_self_intersection(const PolygonMesh& mesh, const kernel::Grid& grid) {
  PolygonMesh snapped = mesh;
  bool moved = false;
  for (Eigen::Vector3d& v : snapped.vertices) {
    const Eigen::Vector3d g = grid.to_world(grid.snap(v));
    moved = moved || g != v;
    v = g;
  }
  if (!moved) return {};
  const std::vector<FacePair> pairs = find_self_intersections(snapped, {.max_pairs = 1});
  if (pairs.empty()) return {};
  const Eigen::Vector3d& near = mesh.vertices[std::size_t(mesh.faces[std::size_t(pairs[0].face_a)][0])];
  std::ostringstream out;
  out << "faces " << pairs[0].face_a << " and " << pairs[0].face_b << " (near " << near.x() << ", " << near.y() << ", "
      << near.z() << ") meet when the vertices are snapped to the exact kernel's grid (step " << grid.name()
      << "): the mesh has features smaller than the grid step";
  return out.str();
}

CircularOptions circular(const Arguments& args, std::size_t i) {
  CircularOptions options{.grid = args.grid()};
  if (args.has(i)) options.segments = static_cast<int>(args.integer(i, 3, 100000));
  return options;
}

// grid(step): the names of global solids made at another grid than `grid` (they cannot be
// combined with the solids made from now on), at most `limit` of them, and how many there are.
std::pair<std::string, std::size_t> solids_at_other_grids(const Arguments& args, const kernel::Grid& grid,
                                                          std::size_t limit) {
  std::string names;
  std::size_t count = 0;
  for (const auto& [name, value] : args.globals())
    if (const SolidValue* s = value.object<SolidValue>(); s && !is_leaf(s->solid.root()) && s->solid.grid() != grid) {
      if (count++ < limit) names += (names.empty() ? "" : ", ") + name;
    }
  return {names, count};
}

}  // namespace

std::string SolidValue::repr() const {
  // The grid is shown when it is not the default (docs/language.md, "World range").
  const std::string grid = solid.grid() == kernel::Grid{} ? "" : ", grid " + solid.grid().name();
  if (solid.is_empty()) return "<solid: empty" + grid + ">";
  const TreeStats stats = tree_stats(solid);
  return "<solid: " + std::to_string(stats.nodes) + " nodes, height " + std::to_string(stats.height) + grid + ">";
}

std::optional<Value> SolidValue::binary(ast::Op op, const Value& other, bool self_on_left) const {
  const SolidValue* that = other.object<SolidValue>();
  if (!that) return std::nullopt;
  const Solid& a = self_on_left ? solid : that->solid;
  const Solid& b = self_on_left ? that->solid : solid;
  switch (op) {
    case ast::Op::Union: return solid_value(unite(a, b));
    case ast::Op::Intersect: return solid_value(intersect(a, b));
    case ast::Op::Sub: return solid_value(subtract(a, b));
    default: return std::nullopt;
  }
}

Value solid_value(Solid solid) {
  return Value(std::shared_ptr<const Object>(std::make_shared<SolidValue>(std::move(solid))));
}

void register_solids(BuiltinTable& table) {
  table.add({.name = "grid",
             .signature = "grid(step)",
             .doc = "The world range (docs/kernel.md, \"World range\"): solids made after grid(step) snap their "
                    "coordinates to multiples of step, a power of two 2^-k with k in [-32, 64] (pow(2, -10)), and "
                    "hold coordinates up to 2^25 steps: the default 2^-15 gives [-1024, 1024], 2^-13 gives "
                    "[-4096, 4096]. Returns the step in effect (grid() only reads it). Call it before the first "
                    "solid: solids made at different grids cannot be combined (a later call says which solids "
                    "are at the old grid). `sculpt --grid STEP` sets it for a whole run.",
             .params = {{"step", false}},
             .run = [](const Arguments& args) -> Value {
               if (!args.has(0)) return args.grid().step();
               kernel::Grid grid;
               try {
                 grid = kernel::Grid::from_step(args.number(0));
               } catch (const InvalidInput& e) {
                 args.fail(0, e.what());
               }
               const kernel::Grid old = args.grid();
               args.set_grid(grid);
               if (grid != old) {
                 const auto [names, count] = solids_at_other_grids(args, grid, 5);
                 if (count > 0)
                   args.out() << "note: grid(" << grid.name() << "): " << count << (count == 1 ? " solid" : " solids")
                              << " (" << names << (count > 5 ? ", ..." : "") << ") made at another grid cannot be "
                              << "combined with solids made from now on\n";
               }
               return grid.step();
             }});
  table.add({.name = "box",
             .signature = "box(min, max)",
             .doc = "The axis-aligned box with corners min and max ([x, y, z] each, min < max).",
             .params = {{"min"}, {"max"}},
             .run = [](const Arguments& args) { return solid_value(box(vector3(args, 0), vector3(args, 1), args.grid())); }});
  table.add({.name = "sphere",
             .signature = "sphere(r, segments=32)",
             .doc = "Sphere of radius r at the origin: a polyhedron with `segments` edges around the "
                    "equator and (segments + 1) / 2 rings, its vertices on the sphere.",
             .params = {{"r"}, {"segments", false}},
             .run = [](const Arguments& args) { return solid_value(sphere(args.number(0), circular(args, 1))); }});
  table.add({.name = "cylinder",
             .signature = "cylinder(r, h, segments=32)",
             .doc = "Cylinder of radius r around the z axis from z = 0 to z = h (a prism over a "
                    "regular polygon with `segments` vertices on the circle).",
             .params = {{"r"}, {"h"}, {"segments", false}},
             .run = [](const Arguments& args) {
               return solid_value(cylinder(args.number(0), args.number(1), circular(args, 2)));
             }});
  table.add({.name = "cone",
             .signature = "cone(r, h, segments=32)",
             .doc = "Cone around the z axis: base of radius r at z = 0, apex at z = h.",
             .params = {{"r"}, {"h"}, {"segments", false}},
             .run = [](const Arguments& args) {
               const CircularOptions c = circular(args, 2);
               return solid_value(cone(args.number(0), args.number(1), {.segments = c.segments, .center = c.center, .grid = c.grid}));
             }});
  table.add({.name = "union_all",
             .signature = "union_all(solids)",
             .doc = "The union of a list of solids, computed at once: each solid's boundary is clipped "
                    "by the others and one tree is built from the union's boundary (much faster than "
                    "chaining | over many solids; the same set, exactly).",
             .params = {{"solids"}},
             .run = [](const Arguments& args) {
               const List& items = args.list(0);
               args.charge(items.size());
               std::vector<Solid> solids;
               solids.reserve(items.size());
               for (std::size_t i = 0; i < items.size(); ++i) {
                 const SolidValue* s = items[i].object<SolidValue>();
                 if (!s) args.fail(0, "item " + std::to_string(i + 1) + " is " + type_name(items[i]) + ", not a solid");
                 solids.push_back(s->solid);
               }
               return solid_value(unite_all(std::move(solids)));
             }});
  table.add({.name = "translate",
             .signature = "translate(s, v)",
             .doc = "Solid s moved by the vector v (exact: v is snapped to the kernel grid).",
             .params = {{"s"}, {"v"}},
             .run = [](const Arguments& args) { return solid_value(translate(solid_arg(args, 0), vector3(args, 1))); }});
  table.add({.name = "rotate",
             .signature = "rotate(s, axis, degrees)",
             .doc = "Solid s rotated by `degrees` about `axis` through the origin (right-handed). "
                    "Multiples of 90 degrees about a coordinate axis are exact.",
             .params = {{"s"}, {"axis"}, {"degrees"}},
             .run = [](const Arguments& args) {
               return solid_value(rotate(solid_arg(args, 0), vector3(args, 1), args.number(2)));
             }});
  table.add({.name = "scale",
             .signature = "scale(s, v)",
             .doc = "Solid s scaled by the factors [sx, sy, sz] (or one number for all three); "
                    "non-zero, negative factors mirror. Whole factors are exact.",
             .params = {{"s"}, {"v"}},
             .run = [](const Arguments& args) {
               Eigen::Vector3d factors;
               if (const double* f = args.value(1).get<double>()) {
                 factors = Eigen::Vector3d::Constant(*f);
               } else {
                 factors = vector3(args, 1);
               }
               return solid_value(scale(solid_arg(args, 0), factors));
             }});
  table.add({.name = "classify",
             .signature = "classify(s, p)",
             .doc = "Where the point p lies with respect to solid s: \"in\", \"out\" or \"on\" (the "
                    "boundary), decided exactly on the kernel grid.",
             .params = {{"s"}, {"p"}},
             .run = [](const Arguments& args) -> Value {
               switch (classify(solid_arg(args, 0), vector3(args, 1)).location) {
                 case Location::Inside: return "in";
                 case Location::Outside: return "out";
                 case Location::Boundary: return "on";
               }
               return "out";
             }});
  table.add({.name = "volume",
             .signature = "volume(s)",
             .doc = "The volume of solid s (from its exact boundary).",
             .params = {{"s"}},
             .run = [](const Arguments& args) -> Value { return volume(solid_arg(args, 0)); }});
  table.add({.name = "area",
             .signature = "area(s)",
             .doc = "The surface area of solid s.",
             .params = {{"s"}},
             .run = [](const Arguments& args) -> Value { return surface_area(solid_arg(args, 0)); }});
  table.add({.name = "export",
             .signature = "export(s, \"file.off\")",
             .doc = "Writes the boundary of solid s as a mesh; the format comes from the extension: "
                    ".off, .obj, .stl, .ply. The file is replaced atomically.",
             .params = {{"s"}, {"file"}},
             .run = [](const Arguments& args) -> Value {
               const auto& s = args.object<SolidValue>(0, "a solid");
               const std::string path = args.file_path(1);
               write_mesh(s.boundary(), path);
               return {};
             }});
  table.add({.name = "import",
             .signature = "import(\"file.off\")",
             .doc = "Reads a mesh (.off, .obj, .stl, .ply), checks that it is a closed, oriented, "
                    "non-self-intersecting 2-manifold, and builds its BSP solid.",
             .params = {{"file"}},
             .run = [](const Arguments& args) -> Value {
               const std::string path = args.file_path(0);
               const PolygonMesh mesh = read_mesh(path);
               const ValidationReport report = check_closed_manifold(mesh);
               if (!report.ok()) args.fail(path + " is not a closed manifold: " + report.summary(3));
               // Consistently oriented is not enough: faces all turned inwards bound the complement,
               // and from_mesh (which expects outward faces) made a "solid" of negative volume from it.
               if (const double v = mesh_volume(mesh); !(v > 0)) {
                 std::ostringstream message;
                 message << path << ": the faces are oriented inwards (the mesh's signed volume is " << v
                         << "): reverse the order of each face's vertices";
                 args.fail(message.str());
               }
               if (const std::string e = snapped_self_intersection(mesh, args.grid()); !e.empty()) args.fail(path + ": " + e);
               return solid_value(from_mesh(mesh, {.grid = args.grid()}));
             }});
}

}  // namespace sculpt::language
