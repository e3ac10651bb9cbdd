#include "language/suggest.hpp"

#include <algorithm>
#include <limits>
#include <tuple>

namespace sculpt::language {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: Levenshtein plus transposition of adjacent letters ("alpah").
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

namespace {

std::size_t common_prefix(std::string_view a, std::string_view b) {
  std::size_t n = 0;
  while (n < a.size() && n < b.size() && a[n] == b[n]) ++n;
  return n;
}

/// Every letter of `a` appears in `b` in the same order ("lnrz" in "linearize").
bool in_order(std::string_view a, std::string_view b) {
  std::size_t j = 0;
  for (char c : b)
    if (j < a.size() && a[j] == c) ++j;
  return j == a.size();
}

}  // namespace

std::optional<std::string> closest_name(std::string_view name, const std::vector<std::string>& candidates) {
  // Ranked in tiers, each better than the next whatever the distances: a shared prefix of at least
  // three letters (the longest wins), then the name's letters in order in the candidate (an
  // abbreviation), then a short edit distance, where a distance above 1 also needs the
  // same first letter (":help bounds" suggested "round", two edits away).
  const std::size_t limit = std::max<std::size_t>(1, name.size() / 3);
  std::optional<std::string> best;
  std::tuple<int, std::size_t, std::size_t> best_rank{3, 0, 0};  // tier, then the tier's order
  for (const std::string& candidate : candidates) {
    if (candidate == name) continue;
    const std::size_t prefix = common_prefix(name, candidate);
    const std::size_t d = edit_distance(name, candidate);
    std::tuple<int, std::size_t, std::size_t> rank{3, 0, 0};
    if (prefix >= 3 && (prefix == name.size() || prefix == candidate.size() || d <= name.size() / 2)) {
      rank = {0, std::numeric_limits<std::size_t>::max() - prefix, d};
    } else if (name.size() >= 3 && candidate.size() >= 3 && !name.empty() && name[0] == candidate[0] &&
               in_order(name, candidate) && candidate.size() <= 2 * name.size()) {
      rank = {1, d, candidate.size()};
    } else if (d <= limit && d < name.size() && (d == 1 || name[0] == candidate[0])) {
      // A one-letter name is not a typo of another; of equal distances the length nearest wins
      // ("sqtr": "sqrt", not "str").
      rank = {2, d, candidate.size() > name.size() ? candidate.size() - name.size() : name.size() - candidate.size()};
    }
    if (std::get<0>(rank) < 3 && rank < best_rank) {
      best_rank = rank;
      best = candidate;
    }
  }
  return best;
}

}  // namespace sculpt::language
