#include "internal/scene_text.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "chasles/files/input_file.h"
#include "chasles/scene/scene_error.h"

namespace chasles::scene_internal {

std::string ReadSceneFileText(const std::string& path, size_t max_bytes) {
  return ReadCappedFile(path, max_bytes, [&](const CappedReadFailure& f) {
    switch (f.kind) {
      case CappedReadFailure::Kind::kOpen:
        throw SceneError(path, 0, 0, "",
                         f.error == ENOENT
                             ? std::string("cannot open the file (does it exist?)")
                             : fmt::format("cannot open the file: {}", std::strerror(f.error)));
      case CappedReadFailure::Kind::kRead:
        throw SceneError(path, 0, 0, "",
                         fmt::format("cannot read the file: {}", std::strerror(f.error)));
      case CappedReadFailure::Kind::kFolder:
        throw SceneError(path, 0, 0, "", "this is a folder, not a scene file");
      case CappedReadFailure::Kind::kTooLarge:
        throw SceneError(path, 0, 0, "",
                         fmt::format("the scene is {} the maximum scene size of {}; a scene that "
                                     "large is refused before it is parsed (raise the limit with "
                                     "--max-scene-bytes N if it is meant to be read)",
                                     f.size ? fmt::format("{}, more than", FormatByteSize(*f.size))
                                            : std::string("longer than"),
                                     FormatByteSize(max_bytes)));
    }
  });
}

void CheckSceneText(std::string_view text, const std::string& name) {
  // The first byte that is not UTF-8 (or a NUL, which is), with its line and column.
  const size_t at = std::min(FindInvalidUtf8(text), text.find('\0'));
  if (at == std::string_view::npos) return;
  const size_t line_start = at == 0 ? 0 : text.rfind('\n', at - 1) + 1;  // npos + 1 = 0
  const int line =
      1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  const auto fail = [&](const std::string& what) {
    throw SceneError(name, line, static_cast<int>(at - line_start) + 1, "",
                     fmt::format("{}; a scene file must be UTF-8 text", what));
  };
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const unsigned char c = s[at];
  if (c == 0) fail("a NUL byte (0x00)");
  const Utf8Lead lead = DecodeUtf8Lead(c);
  if (lead.length == 0) fail(fmt::format("the byte 0x{:02X} is not valid UTF-8", c));
  if (at + lead.length > text.size()) {
    fail(fmt::format("the text ends inside a UTF-8 character (0x{:02X})", c));
  }
  // FindInvalidUtf8 stopped here: one of the later bytes is out of its range.
  std::string bytes;
  for (size_t k = 0; k < lead.length; ++k) {
    bytes += fmt::format(" 0x{:02X}", s[at + k]);
    if (k > 0 && (s[at + k] < (k == 1 ? lead.lo : 0x80) || s[at + k] > (k == 1 ? lead.hi : 0xBF))) {
      break;
    }
  }
  fail(fmt::format("the bytes{} are not valid UTF-8", bytes));
}

}  // namespace chasles::scene_internal
