#include "internal/scene_text.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "chasles/files/input_file.h"
#include "chasles/scene/scene_error.h"

namespace chasles::scene_internal {

namespace {

std::string SizeText(size_t bytes) {
  return fmt::format("{} bytes ({:.1f} MiB)", bytes, static_cast<double>(bytes) / (1 << 20));
}

/// `size` is the file's size, or "" when it has none (a pipe or a device read past the limit).
[[noreturn]] void TooLarge(const std::string& path, const std::string& size, size_t max_bytes) {
  throw SceneError(
      path, 0, 0, "",
      fmt::format("the scene is {} the maximum scene size of {}; a scene that "
                  "large is refused before it is parsed (raise the limit with "
                  "--max-scene-bytes N if it is meant to be read)",
                  size.empty() ? std::string("longer than") : fmt::format("{}, more than", size),
                  SizeText(max_bytes)));
}

/// Closes the descriptor however the read ends.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string ReadSceneFileText(const std::string& path, size_t max_bytes) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) {
    const int error = errno;
    throw SceneError(path, 0, 0, "",
                     error == ENOENT
                         ? std::string("cannot open the file (does it exist?)")
                         : fmt::format("cannot open the file: {}", std::strerror(error)));
  }
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) {
    throw SceneError(path, 0, 0, "", fmt::format("cannot read the file: {}", std::strerror(errno)));
  }
  if (S_ISDIR(st.st_mode)) {
    throw SceneError(path, 0, 0, "", "this is a folder, not a scene file");
  }
  const bool regular = S_ISREG(st.st_mode);
  if (regular && static_cast<unsigned long long>(st.st_size) > max_bytes) {
    TooLarge(path, SizeText(static_cast<size_t>(st.st_size)), max_bytes);
  }
  std::string text;
  if (regular) text.reserve(static_cast<size_t>(st.st_size));
  std::vector<char> buffer(1 << 16);
  for (;;) {
    const ssize_t n = ::read(f.fd, buffer.data(), buffer.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw SceneError(path, 0, 0, "",
                       fmt::format("cannot read the file: {}", std::strerror(errno)));
    }
    if (n == 0) break;
    text.append(buffer.data(), static_cast<size_t>(n));
    // A pipe or a device (/dev/zero) may never end: stop one byte past the limit.
    if (text.size() > max_bytes) TooLarge(path, "", max_bytes);
  }
  return text;
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
