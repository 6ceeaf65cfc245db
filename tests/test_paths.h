#pragma once
/// @file
/// Where the tests find the source tree and the chasles program of their build. The two paths
/// are compiled into one object (test_paths.cpp) rather than into every test, so that a clone in
/// another folder compiles that file again and the compiler cache serves every test
/// (scripts/common.sh).

namespace chasles::test {

/// The source folder (CMake's PROJECT_SOURCE_DIR), without a trailing slash.
const char* SourceDir();

/// The chasles program of this build.
const char* CliPath();

}  // namespace chasles::test
