#pragma once
/// @file
/// The files the program reads back: a run's CSV and JSON summary, a sweep's table (chasles
/// plot, chasles report, the Python module's read_csv). Each is read with a size cap, so a
/// device such as /dev/zero or a file far larger than any table is refused instead of filling
/// memory; a JSON summary is then parsed with a cap on its nesting (chasles/report/json_input.h).
/// (Scenes have their own reader with the same rules, chasles/scene/scene.h; meshes theirs,
/// chasles/files/mesh_reader.h.)

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace chasles {

/// The most bytes of a table or a summary read unless --max-input-bytes says otherwise:
/// 256 MiB, some 4 million rows of a 10-column run.
inline constexpr size_t kDefaultMaxInputBytes = size_t{256} << 20;

/// A byte count for messages: "1048577 bytes (1.0 MiB)".
std::string FormatByteSize(unsigned long long bytes);

/// Why a capped read stopped (ReadCappedFile): the file could not be opened or read (with the
/// errno), it is a folder, or it is longer than the cap (`size`: a regular file's size, known
/// before a byte is read; none for a pipe or a device read one byte past the cap).
struct CappedReadFailure {
  enum class Kind { kOpen, kRead, kFolder, kTooLarge };
  Kind kind = Kind::kOpen;
  int error = 0;
  std::optional<unsigned long long> size;
};

/// The whole file at `path`, read with a cap of `max_bytes`: a regular file is refused by its
/// size before a byte is read, a pipe or a device (which may never end) after max_bytes + 1
/// bytes. Each reader words its own errors: `fail` is called with why the read stopped and must
/// throw (std::logic_error if it returns).
std::string ReadCappedFile(const std::string& path, size_t max_bytes,
                           const std::function<void(const CappedReadFailure&)>& fail);

/// The whole file at `path` (`what` names it in errors: "the table to plot"). Throws InputError
/// "PATH: ..." for a folder, a file that cannot be opened or read, and one larger than
/// `max_bytes`: a regular file by its size before a byte is read, a pipe or a device after
/// max_bytes + 1 bytes; the message says how to raise the limit (`option`, e.g.
/// "--max-input-bytes N").
std::string ReadInputFile(const std::string& path, const std::string& what, size_t max_bytes,
                          const std::string& option);

/// What a byte says as the first of a UTF-8 sequence (RFC 3629, section 4): the sequence's
/// length in bytes (1 for ASCII, 0 when no sequence begins with it) and the range [lo, hi] its
/// second byte must lie in (no overlong forms, no surrogates, nothing above U+10FFFF); the
/// later bytes lie in [0x80, 0xBF].
struct Utf8Lead {
  size_t length = 0;
  unsigned char lo = 0x80, hi = 0xBF;
};
Utf8Lead DecodeUtf8Lead(unsigned char c);

/// The offset of the first byte of `text` that is not part of well-formed UTF-8 (RFC 3629: no
/// overlong forms, no surrogates, nothing above U+10FFFF), or std::string_view::npos.
size_t FindInvalidUtf8(std::string_view text);

}  // namespace chasles
