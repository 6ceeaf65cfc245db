#pragma once
/// @file
/// Large inputs read in place, and large arrays made present in one call: the two ways to
/// spend less on page faults, which a fresh process pays once per 4 KB page of memory it touches
/// (on a virtual machine 10-20 us each, most of the time of a program such as `chasles mass`
/// on a large mesh; docs/benchmarks.md, Mesh mass properties). Everything system-specific is
/// here, each with a plain fallback.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace chasles {

/// A file opened for reading whose bytes can be had in memory without copying them: a regular
/// file is mapped (POSIX mmap, private and read-only; on Linux its pages are made present in
/// one call), so its bytes are the system's file cache itself, not a copy in fresh memory.
/// Where mapping is unavailable or fails, and for a file that is not regular (a pipe, a
/// device), the bytes are read into a buffer instead.
///
/// The risk a mapping brings: if another program truncates the file while it is mapped, reading
/// the pages past the new end raises SIGBUS, which ends the process. Callers check the size they
/// need before mapping (so a file that is short from the start is an ordinary error), and map
/// only for a read that is over in a fraction of a second.
class MappedFile {
 public:
  /// Opens `path` for reading and takes its status. Throws std::system_error (with the errno
  /// of open or fstat) when it cannot.
  explicit MappedFile(const std::string& path);
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile();

  /// True for a regular file (whose size is known before it is read).
  bool regular() const { return regular_; }
  /// A regular file's size when it was opened; 0 for any other file.
  std::uint64_t size() const { return size_; }

  /// Reads up to `n` bytes at `offset` of a regular file without mapping it (a header, before
  /// deciding to map); returns the number read, fewer at the end of the file. Throws
  /// std::system_error on a read error.
  std::size_t ReadAt(std::uint64_t offset, void* out, std::size_t n) const;

  /// The whole file's bytes, valid while this object lives: a regular file's size() bytes
  /// mapped (or read into a buffer when mapping fails), any other file's bytes read to its
  /// end. Throws std::system_error on a read error. Calling it again returns the same bytes.
  std::span<const unsigned char> Bytes();

  /// True when Bytes() is a mapping of the file (false before Bytes() and for a buffer).
  bool mapped() const { return map_ != nullptr; }

 private:
  void Close() noexcept;

  int fd_ = -1;
  bool regular_ = false;
  std::uint64_t size_ = 0;
  void* map_ = nullptr;                // the mapping, when the file is mapped
  std::size_t length_ = 0;             // its length
  std::vector<unsigned char> buffer_;  // the bytes read, when the file is not mapped
  bool read_ = false;
};

/// Makes the memory pages of [data, data + bytes) present and writable in one system call
/// (Linux 5.14 or later: madvise MADV_POPULATE_WRITE), instead of one page fault at the first
/// write to each page; the contents are unchanged. For a large array about to be written in
/// full. Does nothing where unsupported or when it fails (the pages then fault in as usual),
/// and for a range under 64 KB.
void PrefaultForWrite(void* data, std::size_t bytes) noexcept;

}  // namespace chasles
