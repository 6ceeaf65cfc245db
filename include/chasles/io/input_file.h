#pragma once
/// @file
/// The files the program reads back: a run's CSV and JSON summary, a sweep's table (chasles
/// plot, chasles report, the Python module's read_csv). Each is read with a size cap, so a
/// device such as /dev/zero or a file far larger than any table is refused instead of filling
/// memory, and JSON is parsed with a cap on its nesting, so a summary of 300 000 nested arrays
/// is refused instead of overflowing the stack of whatever walks it. (Scenes have their own
/// reader with the same rules, chasles/scene/scene.h; meshes theirs, chasles/io/mesh_reader.h.)

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace chasles {

/// The most bytes of a table or a summary read unless --max-input-bytes says otherwise:
/// 256 MiB, some 4 million rows of a 10-column run.
inline constexpr size_t kDefaultMaxInputBytes = size_t{256} << 20;

/// The deepest nesting of arrays and objects in a JSON file read back. A chasles summary is
/// nested at most 5 deep; 64 leaves room for any hand-made summary.
inline constexpr int kMaxJsonDepth = 64;

/// The whole file at `path` (`what` names it in errors: "the table to plot"). Throws InputError
/// "PATH: ..." for a folder, a file that cannot be opened or read, and one larger than
/// `max_bytes`: a regular file by its size before a byte is read, a pipe or a device after
/// max_bytes + 1 bytes; the message says how to raise the limit (`option`, e.g.
/// "--max-input-bytes N").
std::string ReadInputFile(const std::string& path, const std::string& what, size_t max_bytes,
                          const std::string& option);

/// `text` (read from `path`) as JSON, its arrays and objects nested at most kMaxJsonDepth
/// deep. Throws InputError "PATH: not JSON: ..." or "PATH: arrays and objects nested deeper
/// than 64 levels ...".
nlohmann::json ParseJsonText(const std::string& text, const std::string& path);

/// The offset of the first byte of `text` that is not part of well-formed UTF-8 (RFC 3629: no
/// overlong forms, no surrogates, nothing above U+10FFFF), or std::string_view::npos.
size_t FindInvalidUtf8(std::string_view text);

}  // namespace chasles
