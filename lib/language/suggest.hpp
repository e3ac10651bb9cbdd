#pragma once
/// \file suggest.hpp
/// "did you mean ...?" for unknown names: the closest candidate by edit distance.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sculpt::language {

/// Edit distance: insertions, deletions, substitutions and swaps of adjacent letters cost 1.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `name`, if it is close enough to be a plausible typo. Ranked: a
/// shared prefix of three letters or more, then the name's letters in order in the candidate (same
/// first letter), then an edit distance of 1, or up to a third of the length with the same first
/// letter.
std::optional<std::string> closest_name(std::string_view name, const std::vector<std::string>& candidates);

}  // namespace sculpt::language
