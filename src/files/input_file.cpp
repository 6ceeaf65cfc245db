// Reading back the files the program wrote, with a cap on their size (chasles/files/input_file.h).

#include "chasles/files/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

namespace {

/// Closes the descriptor however the read ends.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string FormatByteSize(unsigned long long bytes) {
  return fmt::format("{} bytes ({:.1f} MiB)", bytes, static_cast<double>(bytes) / (1 << 20));
}

std::string ReadCappedFile(const std::string& path, size_t max_bytes,
                           const std::function<void(const CappedReadFailure&)>& fail) {
  using Kind = CappedReadFailure::Kind;
  const auto stop = [&](Kind kind, int error, std::optional<unsigned long long> size = {}) {
    fail(CappedReadFailure{kind, error, size});
    throw std::logic_error("ReadCappedFile: the failure handler returned");
  };
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) stop(Kind::kOpen, errno);
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) stop(Kind::kRead, errno);
  if (S_ISDIR(st.st_mode)) stop(Kind::kFolder, 0);
  const bool regular = S_ISREG(st.st_mode);
  if (regular && static_cast<unsigned long long>(st.st_size) > max_bytes) {
    stop(Kind::kTooLarge, 0, static_cast<unsigned long long>(st.st_size));
  }
  std::string text;
  if (regular) text.reserve(static_cast<size_t>(st.st_size));
  std::vector<char> buffer(1 << 16);
  for (;;) {
    const ssize_t n = ::read(f.fd, buffer.data(), buffer.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      stop(Kind::kRead, errno);
    }
    if (n == 0) break;
    text.append(buffer.data(), static_cast<size_t>(n));
    // A pipe or a device (/dev/zero) may never end: stop one byte past the limit.
    if (text.size() > max_bytes) stop(Kind::kTooLarge, 0);
  }
  return text;
}

std::string ReadInputFile(const std::string& path, const std::string& what, size_t max_bytes,
                          const std::string& option) {
  return ReadCappedFile(path, max_bytes, [&](const CappedReadFailure& f) {
    switch (f.kind) {
      case CappedReadFailure::Kind::kOpen:
        throw InputError(fmt::format("{}: cannot open {}: {}", path, what, std::strerror(f.error)));
      case CappedReadFailure::Kind::kRead:
        throw InputError(fmt::format("{}: cannot read {}: {}", path, what, std::strerror(f.error)));
      case CappedReadFailure::Kind::kFolder:
        throw InputError(fmt::format("{}: this is a folder, not {}", path, what));
      case CappedReadFailure::Kind::kTooLarge:
        throw InputError(fmt::format(
            "{}: {} is {} the limit of {}; it is refused before it is parsed (raise the limit "
            "with {} if it is meant to be read)",
            path, what,
            f.size ? fmt::format("{}, more than", FormatByteSize(*f.size))
                   : std::string("longer than"),
            FormatByteSize(max_bytes), option));
    }
  });
}

Utf8Lead DecodeUtf8Lead(unsigned char c) {
  Utf8Lead lead;
  if (c < 0x80) {
    lead.length = 1;
  } else if (c >= 0xC2 && c <= 0xDF) {
    lead.length = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    lead.length = 3;
    if (c == 0xE0) lead.lo = 0xA0;  // no overlong forms
    if (c == 0xED) lead.hi = 0x9F;  // no surrogates U+D800..U+DFFF
  } else if (c >= 0xF0 && c <= 0xF4) {
    lead.length = 4;
    if (c == 0xF0) lead.lo = 0x90;  // no overlong forms
    if (c == 0xF4) lead.hi = 0x8F;  // nothing above U+10FFFF
  }
  return lead;
}

size_t FindInvalidUtf8(std::string_view text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  size_t i = 0;
  while (i < n) {
    const Utf8Lead lead = DecodeUtf8Lead(s[i]);
    if (lead.length == 0 || i + lead.length > n) return i;
    for (size_t k = 1; k < lead.length; ++k) {
      const unsigned char b = s[i + k];
      if (b < (k == 1 ? lead.lo : 0x80) || b > (k == 1 ? lead.hi : 0xBF)) return i;
    }
    i += lead.length;
  }
  return std::string_view::npos;
}

}  // namespace chasles
