#pragma once
/// \file solid_values.hpp
/// Script values of the solids area (builtins_solids.cpp): a BSP solid (type "solid") with the
/// operators `a | b` (union), `a & b` (intersection), `a - b` (difference).
/// Other areas (revolve, ...) return solids with `solid_value(...)` and read them with
/// `args.object<SolidValue>(i, "a solid").solid`.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "bsp/boundary.hpp"
#include "bsp/solid.hpp"
#include "language/interpreter.hpp"
#include "language/value.hpp"
#include "mesh/self_intersection.hpp"

namespace sculpt::language {

struct SolidValue final : Object {
  explicit SolidValue(Solid s) : solid(std::move(s)) {}
  Solid solid;
  /// The boundary mesh, extracted once per value (solids are immutable script values), so
  /// exporting one solid to several files extracts its boundary only once.
  [[nodiscard]] const PolygonMesh& boundary() const {
    if (!boundary_cache_) {
      OutputRoundingReport report;
      boundary_cache_ = to_mesh(solid, {.report = &report});
      boundary_problem_ = report.problem;
    }
    return *boundary_cache_;
  }
  /// The boundary for a screen: boundary() when it is made already, else the exact boundary
  /// without output rounding, its vertices at their approximations where those are within 2^-20
  /// grid steps (to_mesh with clean = false and approximate; not kept).
  [[nodiscard]] PolygonMesh display_boundary() const {
    return boundary_cache_ ? *boundary_cache_ : to_mesh(solid, {.clean = false, .approximate = true});
  }
  /// Why boundary() is not clean for other tools (output rounding could not make it so), or empty.
  [[nodiscard]] const std::string& boundary_problem() const {
    (void)boundary();
    return boundary_problem_;
  }
  /// The solid as an rvalue for an in-place operation (bsp/set_operations.hpp), for whoever
  /// alone holds this value (Value::sole_object). The operation empties it once it has checked
  /// its operands and taken the storage; an error before that leaves it whole.
  [[nodiscard]] Solid&& handed_over() {
    boundary_cache_.reset();
    exact_boundary.reset();
    return std::move(solid);
  }
  /// A mesh that bounds `solid` exactly, when the solid was built from it (implicit: the mesh
  /// with its vertices snapped to the grid, the very triangles from_mesh cut the tree from, checked
  /// closed and unintersecting; zero-area triangles may remain). volume() and area() sum over it
  /// instead of extracting the boundary from the tree. Null otherwise.
  std::shared_ptr<const PolygonMesh> exact_boundary;
  /// The solid's volume: from exact_boundary when known, else from the tree's boundary.
  [[nodiscard]] double volume() const;
  /// The solid's surface area, likewise.
  [[nodiscard]] double area() const;
  [[nodiscard]] std::string type_name() const override { return "solid"; }
  [[nodiscard]] std::string repr() const override;
  [[nodiscard]] std::optional<Value> binary(ast::Op op, const Value& other, bool self_on_left) const override;
  /// `w - x` etc. reusing this solid's tree (in-place set operations); this object is left empty.
  [[nodiscard]] std::optional<Value> binary_sole(ast::Op op, const Value& other) override;

 private:
  mutable std::optional<PolygonMesh> boundary_cache_;
  mutable std::string boundary_problem_;
};

/// A polygon mesh that is not a solid (type "mesh"): a surface patch (`patch`, sec. 5.2).
/// `export` writes it as it is.
struct MeshValue final : Object {
  explicit MeshValue(PolygonMesh m) : mesh(std::move(m)) {}
  PolygonMesh mesh;
  [[nodiscard]] std::string type_name() const override { return "mesh"; }
  [[nodiscard]] std::string repr() const override {
    return "<mesh: " + std::to_string(mesh.vertices.size()) + " vertices, " + std::to_string(mesh.faces.size()) +
           " faces>";
  }
};

/// Wraps a solid as a script value.
Value solid_value(Solid solid);

/// STL files of more triangles than this are written binary unless told otherwise: ASCII STL
/// takes about 250 bytes a triangle (25 MB here), binary 50.
inline constexpr std::size_t kAutoBinaryStlTriangles = 100'000;

/// Writes `mesh` to `path` (write_mesh: the format from the extension, atomically), creating
/// missing folders first; `binary`: binary STL or PLY; nullopt: binary for an STL file of more than
/// kAutoBinaryStlTriangles triangles, else ASCII. \throw IoError, InvalidInput (write_mesh)
void write_mesh_file(const PolygonMesh& mesh, const std::filesystem::path& path,
                     std::optional<bool> binary = std::nullopt);

/// Writes the boundary of solid `s` to `path` as write_mesh_file does (export, sculpt -o).
/// Returns a warning when the mesh is not known to be clean for other tools, else "".
std::string export_solid(const SolidValue& s, const std::filesystem::path& path,
                         std::optional<bool> binary = std::nullopt);

/// The name of the global most recently bound to a solid, or "" (:show, sculpt -o).
std::string latest_solid_global(const Interpreter& interpreter);

/// Empty when `mesh` (a valid closed mesh) stays free of self-intersections with its vertices
/// snapped to `grid`; else what meets where, for an error message. A valid mesh with features
/// below the grid step can intersect itself once snapped (import, implicit).
std::string snapped_self_intersection(const PolygonMesh& mesh, const kernel::Grid& grid);
/// The same with the snapped copy made by the caller (snapped_to_grid(mesh, grid)).
std::string snapped_self_intersection(const PolygonMesh& mesh, const PolygonMesh& snapped, const kernel::Grid& grid);
/// The message for faces `pair` of the snapped copy of `mesh` meeting (what
/// snapped_self_intersection says), for a caller that searched the snapped copy itself.
std::string snapped_crossing_message(const PolygonMesh& mesh, const FacePair& pair, const kernel::Grid& grid);

/// `mesh` with every vertex moved to its point of `grid`, the points from_mesh builds the solid on.
PolygonMesh snapped_to_grid(const PolygonMesh& mesh, const kernel::Grid& grid);

}  // namespace sculpt::language
