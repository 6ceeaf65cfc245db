// Files read in place and arrays made present in one call (chasles/files/mapped_file.h).

#include "chasles/files/mapped_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstdint>
#include <system_error>
#include <utility>
#include <vector>
#if __has_include(<sys/mman.h>)
#include <sys/mman.h>
#define CHASLES_HAVE_MMAN 1
#endif

namespace chasles {
namespace {

[[noreturn]] void ThrowErrno(int error, const char* what) {
  throw std::system_error(error, std::generic_category(), what);
}

// Reads up to n bytes into `out`, at `offset` (pread) or, for an offset of -1, where the file
// stands (read: a pipe or a device); fewer only at the end of the file.
std::size_t ReadFd(int fd, unsigned char* out, std::size_t n, std::int64_t offset) {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t r = offset < 0
                          ? ::read(fd, out + done, n - done)
                          : ::pread(fd, out + done, n - done,
                                    static_cast<off_t>(offset + static_cast<std::int64_t>(done)));
    if (r < 0) {
      if (errno == EINTR) continue;
      ThrowErrno(errno, "read");
    }
    if (r == 0) break;
    done += static_cast<std::size_t>(r);
  }
  return done;
}

}  // namespace

MappedFile::MappedFile(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) ThrowErrno(errno, "open");
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int error = errno;
    Close();
    ThrowErrno(error, "fstat");
  }
  regular_ = S_ISREG(st.st_mode);
  size_ = regular_ && st.st_size > 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
}

MappedFile::MappedFile(MappedFile&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      regular_(other.regular_),
      size_(other.size_),
      map_(std::exchange(other.map_, nullptr)),
      length_(std::exchange(other.length_, 0)),
      buffer_(std::move(other.buffer_)),
      read_(other.read_) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    Close();
    fd_ = std::exchange(other.fd_, -1);
    regular_ = other.regular_;
    size_ = other.size_;
    map_ = std::exchange(other.map_, nullptr);
    length_ = std::exchange(other.length_, 0);
    buffer_ = std::move(other.buffer_);
    read_ = other.read_;
  }
  return *this;
}

MappedFile::~MappedFile() {
  Close();
}

void MappedFile::Close() noexcept {
#ifdef CHASLES_HAVE_MMAN
  if (map_ != nullptr) ::munmap(map_, length_);
#endif
  map_ = nullptr;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

std::size_t MappedFile::ReadAt(std::uint64_t offset, void* out, std::size_t n) const {
  return ReadFd(fd_, static_cast<unsigned char*>(out), n, static_cast<std::int64_t>(offset));
}

std::span<const unsigned char> MappedFile::Bytes() {
  if (map_ != nullptr) return {static_cast<const unsigned char*>(map_), length_};
  if (read_) return {buffer_.data(), buffer_.size()};
#ifdef CHASLES_HAVE_MMAN
  if (regular_ && size_ > 0 && size_ <= SIZE_MAX) {
    int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
    flags |= MAP_POPULATE;  // every page present at once: one call, not a fault per page
#endif
    void* p = ::mmap(nullptr, static_cast<std::size_t>(size_), PROT_READ, flags, fd_, 0);
    if (p != MAP_FAILED) {
      map_ = p;
      length_ = static_cast<std::size_t>(size_);
      return {static_cast<const unsigned char*>(map_), length_};
    }
  }
#endif
  // No mapping: read the bytes (a regular file's size of them, or to the end of any other).
  std::size_t want = regular_ ? static_cast<std::size_t>(size_) : std::size_t{1} << 16;
  for (;;) {
    const std::size_t have = buffer_.size();
    buffer_.resize(have + want);
    const std::size_t got =
        ReadFd(fd_, buffer_.data() + have, want, regular_ ? static_cast<std::int64_t>(have) : -1);
    buffer_.resize(have + got);
    if (got < want || regular_) break;
    want = buffer_.size();
  }
  read_ = true;
  return {buffer_.data(), buffer_.size()};
}

void PrefaultForWrite(void* data, std::size_t bytes) noexcept {
#if defined(CHASLES_HAVE_MMAN) && defined(MADV_POPULATE_WRITE)
  constexpr std::size_t kMinBytes = std::size_t{1} << 16;
  if (data == nullptr || bytes < kMinBytes) return;
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if (page_size <= 0) return;
  const auto page = static_cast<std::uintptr_t>(page_size);
  const auto begin = reinterpret_cast<std::uintptr_t>(data) & ~(page - 1);
  const auto end = reinterpret_cast<std::uintptr_t>(data) + bytes;
  // Errors (EINVAL before Linux 5.14, ENOMEM, ...) leave the pages to fault in as usual.
  (void)::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace chasles
