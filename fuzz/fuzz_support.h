#pragma once
/// @file
/// Shared by the fuzz targets: a private scratch folder for inputs that must be files, and the
/// one rule every target checks: hostile input may be refused, but only with an InputError
/// (exit 2), never a crash, a hang, another exception or a non-finite answer.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

namespace chasles::fuzz {

/// A folder of this process's own under the system temporary folder, created once.
const std::filesystem::path& ScratchDir();

/// Writes bytes to ScratchDir()/name and returns the path.
std::string WriteScratchFile(const std::string& name, std::string_view bytes);

/// Reports a broken promise and aborts, so libFuzzer keeps the input as a crash.
[[noreturn]] void Fail(const char* what, std::string_view detail);

}  // namespace chasles::fuzz
