// Built-ins of the reports area: depth-cost statistics of BSP trees (Ihm & Naylor 1990, sec. 6;
// lib/reports). See docs/depth_cost.md.
#include <filesystem>
#include <fstream>
#include <string>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/rebuild.hpp"
#include "language/builtins.hpp"
#include "language/record.hpp"
#include "language/solid_values.hpp"
#include "reports/tree_report.hpp"

namespace sculpt::language {
namespace {

void write_text(const Arguments& args, std::string_view param, const std::string& text) {
  const std::filesystem::path path = args.file_path(param);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path);
  out << text;
  if (!out) throw IoError(path.string(), "cannot write");
}

/// One solid's report as a record: the tree's sizes and the sec. 6 measures (expected depth of
/// point classification against the entropy bound), the depth histogram, and the query costs.
Value report_record(const reports::TreeReport& r) {
  const reports::DepthCost& d = r.depth;
  List histogram;
  for (const reports::DepthBin& bin : d.histogram) {
    histogram.push_back(record_value({{"depth", double(bin.depth)},
                                      {"in_cells", double(bin.in_cells)},
                                      {"out_cells", double(bin.out_cells)},
                                      {"in_probability", bin.in_probability},
                                      {"out_probability", bin.out_probability}}));
  }
  Record::Fields queries;
  for (const reports::QueryCost& q : r.queries) {
    queries.emplace_back(reports::query_shape_name(q.shape), record_value({{"size", q.size},
                                                                           {"samples", double(q.samples)},
                                                                           {"mean_nodes", q.mean_nodes},
                                                                           {"ci_low", q.ci_low},
                                                                           {"ci_high", q.ci_high},
                                                                           {"mean_leaves", q.mean_leaves}}));
  }
  const Eigen::AlignedBox3d& box = d.sample_box;
  const Value sample_box = List{Value(List{box.min().x(), box.min().y(), box.min().z()}),
                                Value(List{box.max().x(), box.max().y(), box.max().z()})};
  return record_value({{"name", r.name},
                       {"nodes", double(d.nodes)},
                       {"leaves", double(d.leaves)},
                       {"in_leaves", double(d.in_leaves)},
                       {"out_leaves", double(d.out_leaves)},
                       {"height", double(d.height)},
                       {"expected_depth", d.expected_depth},
                       {"entropy_bound", d.entropy_bound},
                       {"ratio", d.ratio},
                       {"cells_in_box", double(d.cells_in_box)},
                       {"in_volume", d.in_volume},
                       {"sample_box", sample_box},
                       {"sample_volume", d.sample_volume},
                       {"histogram", Value(std::move(histogram))},
                       {"queries", record_value(std::move(queries))}});
}

}  // namespace

void register_reports(BuiltinTable& table) {
  table.add({.name = "stats",
             .doc = "Depth-cost report of solid s, or side by side of a list of solids (the same solid built "
                    "different ways) over one sample space: exact leaf-cell volumes, expected depth of point "
                    "classification sum p_C d_C, the entropy bound H and their ratio, node/leaf/in/out counts, "
                    "height, a depth histogram, and Monte Carlo costs of point, segment and box queries "
                    "(`samples` each, 95% intervals; 0 skips them). format: \"text\" or \"json\". Printed, or "
                    "written to `file` (quiet=true: neither); `svg` also writes a chart of the depth distribution. "
                    "Folders are created. Returns the report as a record (a list of records for a list): "
                    "r[\"nodes\"], \"height\", \"expected_depth\", \"entropy_bound\", \"ratio\", \"histogram\", "
                    "\"queries\" ... (keys(r) lists them).",
             .params = {arg("s").any("a solid or a list of solids"), arg("format").string().defaults("text"),
                        arg("names").list().optional("[]"), arg("box").list().optional("[min, max]"),
                        arg("samples").integer(0, 100'000'000).defaults(double(reports::ReportOptions{}.query_samples)),
                        arg("seed").integer(0, 0x1p53).defaults(double(reports::ReportOptions{}.seed)),
                        arg("svg").string().defaults(""), arg("file").string().defaults(""),
                        arg("quiet").boolean().defaults(false)},
             .run = [](const Arguments& args) -> Value {
               std::vector<reports::NamedSolid> solids;
               if (const List* list = args.value("s").list()) {
                 for (std::size_t k = 0; k < list->size(); ++k) {
                   const auto* s = (*list)[k].object<SolidValue>();
                   if (!s) args.fail("s", "stats: item " + std::to_string(k) + " of the list is not a solid");
                   solids.push_back({"solid " + std::to_string(k + 1), s->solid});
                 }
                 if (solids.empty()) args.fail("s", "stats: the list of solids is empty");
               } else {
                 solids.push_back({"solid", args.object<SolidValue>("s").solid});
               }
               if (args.has("names")) {
                 const List& names = args.list("names");
                 if (names.size() != solids.size())
                   args.fail("names", "give one name per solid (" + std::to_string(solids.size()) + ")");
                 for (std::size_t k = 0; k < names.size(); ++k) {
                   const std::string* n = names[k].get<std::string>();
                   if (!n) args.fail("names", "names must be strings");
                   solids[k].name = *n;
                 }
               }
               reports::ReportOptions options;
               if (args.has("box")) {
                 const List& box = args.list("box");
                 if (box.size() != 2 || !box[0].list() || !box[1].list() || box[0].list()->size() != 3 ||
                     box[1].list()->size() != 3)
                   args.fail("box", "box must be [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
                 Eigen::Vector3d lo, hi;
                 for (int a = 0; a < 3; ++a) {
                   const double* l = (*box[0].list())[a].get<double>();
                   const double* h = (*box[1].list())[a].get<double>();
                   if (!l || !h) args.fail("box", "box corners must be numbers");
                   lo[a] = *l;
                   hi[a] = *h;
                 }
                 options.sample_box = Eigen::AlignedBox3d(lo, hi);
               }
               options.query_samples = static_cast<int>(args.integer("samples"));
               options.seed = static_cast<std::uint64_t>(args.integer("seed"));
               const std::string& format = args.string("format");
               if (format != "text" && format != "json") args.fail("format", "format must be \"text\" or \"json\"");
               args.charge(static_cast<std::uint64_t>(options.query_samples) * solids.size());
               const auto reports = reports::compare_trees(solids, options);
               const std::string text = format == "json" ? reports::report_json(reports) : reports::report_text(reports);
               if (!args.string("svg").empty()) write_text(args, "svg", reports::depth_chart_svg(reports));
               if (!args.string("file").empty())
                 write_text(args, "file", text);
               else if (!args.boolean("quiet"))
                 args.err() << text;
               if (!args.value("s").list()) return report_record(reports.front());
               List records;
               for (const reports::TreeReport& r : reports) records.push_back(report_record(r));
               return records;
             }});
  table.add({.name = "rebuild",
             .doc = "The same solid with a new tree built from its boundary (B-rep to BSP, planes chosen as "
                    "import chooses them), for comparing trees built different ways with stats([s, rebuild(s)]).",
             .params = {arg("s").of<SolidValue>("a solid")},
             .run = [](const Arguments& args) -> Value {
               // From the exact boundary, not the rounded mesh: snapping that mesh's vertices back
               // to the grid could fold a face or leave one of zero area (issue 35).
               return solid_value(rebuild_from_boundary(args.object<SolidValue>("s").solid, {}));
             }});
}

}  // namespace sculpt::language
