#pragma once
/// @file
/// "Did you mean" suggestions for misspelt names (keys, units, materials, shapes).

#include <string>
#include <string_view>
#include <vector>

namespace chasles {

/// Edit distance between two strings (case-sensitive): insertions, deletions, substitutions
/// and swaps of neighbouring letters each count one (optimal string alignment).
int EditDistance(std::string_view a, std::string_view b);

/// The known names closest to `name`, compared case-insensitively: only those at the smallest
/// distance, in the given order, at most `max_count`. Empty when nothing is close enough to be
/// a plausible typo: only a change of case for names of one or two letters, one edit up to four
/// letters, two up to eight, then a quarter of the length. The single source of "did you mean"
/// hints in chasles.
std::vector<std::string> SuggestNames(std::string_view name, const std::vector<std::string>& known,
                                      int max_count = 3);

/// " (did you mean 'a', 'b' or 'c'?)" for the given suggestions, or "" when there are none.
std::string DidYouMeanHint(const std::vector<std::string>& suggestions);

/// DidYouMeanHint(SuggestNames(name, known)).
std::string DidYouMean(std::string_view name, const std::vector<std::string>& known);

}  // namespace chasles
