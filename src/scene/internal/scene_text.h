#pragma once
/// @file
/// The bytes of a scene before YAML sees them: read with a size cap (so a device such as
/// /dev/zero or a 100 MB file is refused before parsing) and checked to be UTF-8 without NUL
/// bytes (ParseYaml in yaml_tree.h then parses them). Private to the scene layer.

#include <cstddef>
#include <string>
#include <string_view>

namespace chasles::scene_internal {

/// Reads the whole file at `path`, refusing (SceneError naming the path) a folder, a file that
/// cannot be opened, and more than `max_bytes` bytes: a regular file by its size before
/// reading, anything else (a pipe, a device) after reading at most max_bytes + 1 bytes.
std::string ReadSceneFileText(const std::string& path, size_t max_bytes);

/// Throws a SceneError at NAME:LINE:COL (1-based; the column counts bytes, as the parser's places
/// do) for the first byte that is not part of well-formed UTF-8 (RFC 3629: no overlong forms, no
/// surrogates, nothing above U+10FFFF) or that is a NUL.
void CheckSceneText(std::string_view text, const std::string& name);

}  // namespace chasles::scene_internal
