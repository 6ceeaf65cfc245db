#include "internal/scene_text.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <vector>

#include <fmt/format.h>

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
  int line = 1;
  size_t line_start = 0;
  const auto fail = [&](size_t at, const std::string& what) {
    throw SceneError(name, line, static_cast<int>(at - line_start) + 1, "",
                     fmt::format("{}; a scene file must be UTF-8 text", what));
  };
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  size_t i = 0;
  while (i < n) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      if (c == 0) fail(i, "a NUL byte (0x00)");
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      ++i;
      continue;
    }
    // RFC 3629, section 4: the lead byte gives the length and the range of the second byte.
    size_t len = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      if (c == 0xE0) lo = 0xA0;  // no overlong forms
      if (c == 0xED) hi = 0x9F;  // no surrogates U+D800..U+DFFF
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      if (c == 0xF0) lo = 0x90;  // no overlong forms
      if (c == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
    } else {
      fail(i, fmt::format("the byte 0x{:02X} is not valid UTF-8", c));
    }
    if (i + len > n) fail(i, fmt::format("the text ends inside a UTF-8 character (0x{:02X})", c));
    for (size_t k = 1; k < len; ++k) {
      const unsigned char b = s[i + k];
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) {
        std::string bytes;
        for (size_t m = 0; m <= k; ++m) bytes += fmt::format(" 0x{:02X}", s[i + m]);
        fail(i, fmt::format("the bytes{} are not valid UTF-8", bytes));
      }
    }
    i += len;
  }
}

}  // namespace chasles::scene_internal
