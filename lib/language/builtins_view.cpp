// show(x, name=, color=): puts solids, meshes, surfaces and curves in the live view (sculpt --view, the REPL's
// :view; lib/view, docs/viewing.md). The interpreter keeps the list (Interpreter::shown()); the
// view reads it after each run or entry.
#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "language/builtins.hpp"
#include "language/picture_items.hpp"
#include "language/solid_values.hpp"

namespace sculpt::language {
namespace {

/// At most this many parts in one view (a list given to show in a loop stays bounded).
constexpr std::size_t kMaxShownParts = 10000;

struct NamedColor {
  const char* name;
  std::array<double, 3> rgb;
};

constexpr NamedColor kNamedColors[] = {
    {"red", {0.85, 0.2, 0.2}},    {"green", {0.25, 0.7, 0.3}},    {"blue", {0.25, 0.45, 0.85}},
    {"yellow", {0.9, 0.8, 0.2}},  {"orange", {0.95, 0.55, 0.15}}, {"purple", {0.6, 0.35, 0.75}},
    {"cyan", {0.2, 0.75, 0.8}},   {"magenta", {0.85, 0.3, 0.7}},  {"grey", {0.6, 0.6, 0.6}},
    {"gray", {0.6, 0.6, 0.6}},    {"white", {0.95, 0.95, 0.95}},  {"black", {0.1, 0.1, 0.1}},
    {"brown", {0.55, 0.35, 0.2}}, {"gold", {0.85, 0.65, 0.2}}};

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

/// The color argument: "#rrggbb", a name (red, green, ...) or [r, g, b] with each in [0, 1].
std::array<double, 3> color_arg(const Arguments& args, std::string_view i) {
  if (const std::string* text = args.value(i).get<std::string>()) {
    if (text->size() == 7 && (*text)[0] == '#') {
      std::array<double, 3> rgb{};
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const int hi = hex_digit((*text)[1 + 2 * k]), lo = hex_digit((*text)[2 + 2 * k]);
        ok = ok && hi >= 0 && lo >= 0;
        rgb[k] = (16 * hi + lo) / 255.0;
      }
      if (ok) return rgb;
    }
    for (const NamedColor& c : kNamedColors)
      if (*text == c.name) return c.rgb;
    std::string names;
    for (const NamedColor& c : kNamedColors) names += std::string(names.empty() ? "" : ", ") + c.name;
    args.fail(i, "unknown color '" + *text + "' (give \"#rrggbb\", [r, g, b] in [0, 1], or one of " + names + ")");
  }
  const std::vector<double> v = args.vector(i, 3);
  for (double x : v)
    if (!(x >= 0 && x <= 1)) args.fail(i, "color components must be in [0, 1]");
  return {v[0], v[1], v[2]};
}

/// Why v cannot be a part of the view (empty: it can): what render draws, checked without making
/// a solid's boundary (the view makes it once, when it sends the scene).
std::string unviewable(const Value& v) {
  if (v.object<SolidValue>() || v.object<MeshValue>()) return {};
  auto item = picture_item(v);
  const std::string* error = std::get_if<std::string>(&item);
  return error ? *error : std::string();
}

Value show(const Arguments& args) {
  const Value& x = args.value("x");
  std::vector<Value> items;
  const List* list = x.list();
  if (list && !is_point_list(list)) {  // a list of parts (a list of points is one curve)
    if (list->empty()) args.fail("x", "the list is empty");
    for (std::size_t k = 0; k < list->size(); ++k) {
      if (const std::string error = unviewable((*list)[k]); !error.empty())
        args.fail("x", "item " + std::to_string(k + 1) + " " + error);
      items.push_back((*list)[k]);
    }
  } else {
    if (const std::string error = unviewable(x); !error.empty()) args.fail("x", "x " + error);
    items.push_back(x);
  }
  std::optional<std::array<double, 3>> color;
  if (args.has("color")) color = color_arg(args, "color");
  std::string name = args.has("name") ? args.string("name") : std::string();
  if (args.has("name") && name.empty()) args.fail("name", "the name must not be empty");
  if (name.size() > 200) args.fail("name", "the name is longer than 200 characters");
  std::vector<ShownPart>* shown = args.shown();
  if (!shown) return x;
  if (name.empty()) name = "part " + std::to_string(shown->size() + 1);
  for (std::size_t k = 0; k < items.size(); ++k) {
    ShownPart part{items.size() == 1 ? name : name + " " + std::to_string(k + 1), color, items[k]};
    bool replaced = false;
    for (ShownPart& old : *shown)
      if (old.name == part.name) old = part, replaced = true;
    if (replaced) continue;
    if (shown->size() >= kMaxShownParts)
      args.fail("more than " + std::to_string(kMaxShownParts) + " parts shown (show a union instead)");
    shown->push_back(std::move(part));
  }
  return x;
}

}  // namespace

void register_view(BuiltinTable& table) {
  table.add(
      {.name = "show",
       .doc = "Puts x (a solid, mesh, B-spline surface, spline, curve, linearization, motion (its path), list "
              "of points, or a list of them) in the live view (sculpt --view FILE, :view in the "
              "REPL; docs/viewing.md) as a part called name, in color (\"#rrggbb\", [r, g, b] with each "
              "in [0, 1], or red, green, blue, yellow, orange, purple, cyan, magenta, grey, white, black, "
              "brown, gold). Showing a name again replaces that part; a list gives parts \"name 1\", "
              "\"name 2\", .... Without any show the view shows the last solid made. Returns x.",
       .params = {arg("x").any("what render draws, or a list of them"), arg("name").string().optional("\"part N\""),
                  arg("color").any("\"#rrggbb\", a color name or [r, g, b]").optional("none")},
       .run = show});
}

}  // namespace sculpt::language
