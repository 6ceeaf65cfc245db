#pragma once
/// @file
/// The unified diff of two texts, as `diff -u` prints it (three lines of context, "@@ -a,b
/// +c,d @@" hunks, "\ No newline at end of file" where a last line has none), so that `patch`
/// applies it. Lines are compared whole; the edit script is a shortest one (Myers 1986).

#include <string>
#include <string_view>

namespace chasles::cli {

/// The diff turning `before` (labelled `from` in the "---" line) into `after` (`to`, "+++");
/// empty when the texts are equal.
std::string UnifiedDiff(std::string_view before, std::string_view after, const std::string& from,
                        const std::string& to);

}  // namespace chasles::cli
