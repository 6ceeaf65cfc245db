#pragma once
/// @file
/// Output files that are complete or absent: written under a temporary name beside the target
/// and renamed over it only once fully written and flushed, so an interrupted run never leaves
/// a file that looks finished.

#include <string>
#include <string_view>

namespace chasles {

/// Writes `content` to `path` atomically (same directory temporary + rename; an OutputSet of
/// one file, see output_set.h). Throws InputError (a std::runtime_error) naming the path and
/// the reason on failure; the temporary is removed then.
void WriteFileAtomically(const std::string& path, std::string_view content);

}  // namespace chasles
