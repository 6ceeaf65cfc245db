#pragma once
/// @file
/// What the output set needs to know about a target before it writes: its temporary's name,
/// whether two names are one file, and the error that names it. Private to the files layer.

#include <string>

namespace chasles::internal {

/// The temporary beside `target`: ".NAME.PID-N.tmp", NAME cut to 200 bytes (a name near the
/// file system's 255-byte limit would otherwise have no room for the suffix), N counting the
/// temporaries of the process.
std::string TemporaryPathFor(const std::string& target);

/// The same text for two paths that name one file: "@DEVICE:INODE" for a file that exists,
/// else the folder's real path and the name; for a folder that does not exist yet the path
/// made absolute and normal.
std::string TargetKey(const std::string& path);

/// InputError "cannot write 'PATH' (OPTION): REASON" (without " (OPTION)" when it is empty).
[[noreturn]] void CannotWrite(const std::string& path, const std::string& option,
                              const std::string& reason);

}  // namespace chasles::internal
