#pragma once
/// @file
/// A JSON summary read back (chasles plot, chasles report): its text, read with the size cap of
/// chasles/files/input_file.h, parsed with a cap on its nesting, so a summary of 300 000 nested
/// arrays is refused instead of overflowing the stack of whatever walks it.

#include <string>

#include <nlohmann/json.hpp>

namespace chasles {

/// The deepest nesting of arrays and objects in a JSON file read back. A chasles summary is
/// nested at most 5 deep; 64 leaves room for any hand-made summary.
inline constexpr int kMaxJsonDepth = 64;

/// `text` (read from `path`) as JSON, its arrays and objects nested at most kMaxJsonDepth
/// deep. Throws InputError "PATH: not JSON: ..." or "PATH: arrays and objects nested deeper
/// than 64 levels ...".
nlohmann::json ParseJsonText(const std::string& text, const std::string& path);

}  // namespace chasles
