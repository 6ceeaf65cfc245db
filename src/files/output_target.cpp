// Checking an output's target before any work (chasles/files/output_set.h).

#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "files/internal/output_target.h"
#include "files/internal/temporaries.h"

namespace chasles {

namespace internal {

namespace fs = std::filesystem;

void CannotWrite(const std::string& path, const std::string& option, const std::string& reason) {
  throw InputError(fmt::format("cannot write '{}'{}: {}", path,
                               option.empty() ? "" : fmt::format(" ({})", option), reason));
}

std::string TemporaryPathFor(const std::string& target) {
  static std::atomic<unsigned long> counter{0};
  const fs::path p(target);
  const std::string name = p.filename().string().substr(0, 200);
  return (p.parent_path() / fmt::format(".{}.{}-{}.tmp", name, ::getpid(), counter++)).string();
}

std::string TargetKey(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    return fmt::format("@{}:{}", static_cast<unsigned long long>(st.st_dev),
                       static_cast<unsigned long long>(st.st_ino));
  }
  const fs::path p(path);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  char real[PATH_MAX];
  if (::realpath(dir.c_str(), real) != nullptr) {
    return (fs::path(real) / p.filename()).string();
  }
  std::error_code ec;
  const fs::path absolute = fs::absolute(p, ec);
  return (ec ? p : absolute).lexically_normal().string();
}

}  // namespace internal

namespace {

namespace fs = std::filesystem;
using internal::CannotWrite;

/// Why a node that exists is no place for an output, by its type.
std::string NotARegularFile(mode_t mode) {
  if (S_ISDIR(mode)) return "it is a folder; give a file name";
  const char* what = S_ISLNK(mode)                    ? "a symbolic link"
                     : S_ISCHR(mode) || S_ISBLK(mode) ? "a device"
                     : S_ISFIFO(mode)                 ? "a FIFO (a named pipe)"
                     : S_ISSOCK(mode)                 ? "a socket"
                                                      : "not a regular file";
  return fmt::format(
      "it is {}; chasles writes only regular files, which it replaces whole (give another "
      "name, or - for standard output where the option allows it)",
      what);
}

/// The nearest existing ancestor of `dir`, to say why a folder is missing.
[[noreturn]] void ExplainMissingFolder(const std::string& path, const std::string& option,
                                       const fs::path& dir) {
  std::error_code ec;
  for (fs::path q = dir.parent_path(); !q.empty() && q != q.root_path(); q = q.parent_path()) {
    const fs::file_status s = fs::status(q, ec);
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) {
        CannotWrite(path, option, fmt::format("'{}' is a file, not a folder", q.string()));
      }
      break;
    }
  }
  CannotWrite(path, option,
              fmt::format("the folder '{}' does not exist (create it first)", dir.string()));
}

/// Creates and removes a temporary in `dir`: proof that a file can be made there (a read-only
/// file system, /proc, a folder without write permission say no). Errors name `shown`.
void ProbeFolder(const std::string& shown, const std::string& option, const fs::path& dir) {
  internal::Temporaries& temps = internal::Temporaries::Get();
  internal::Temporaries::Handle handle;
  const std::string probe = internal::TemporaryPathFor((dir / "probe").string());
  const int fd = temps.Create(probe, &handle);
  if (fd < 0) {
    CannotWrite(shown, option,
                fmt::format("no file can be created in the folder '{}': {}", dir.string(),
                            std::strerror(errno)));
  }
  ::close(fd);
  temps.Remove(handle);
}

}  // namespace

bool IsStandardOutput(const std::string& path) {
  return path == "-";
}

void CheckOutputTarget(const std::string& path, const std::string& option) {
  if (path.empty()) CannotWrite(path, option, "no file name was given");
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) CannotWrite(path, option, NotARegularFile(st.st_mode));
  } else if (errno != ENOENT && errno != ENOTDIR) {
    CannotWrite(path, option, std::strerror(errno));
  }
  const fs::path p(path);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  struct stat ds {};
  if (::stat(dir.c_str(), &ds) != 0) {
    if (errno != ENOENT && errno != ENOTDIR) {
      CannotWrite(path, option,
                  fmt::format("the folder '{}': {}", dir.string(), std::strerror(errno)));
    }
    ExplainMissingFolder(path, option, dir);
  }
  if (!S_ISDIR(ds.st_mode)) {
    CannotWrite(path, option, fmt::format("'{}' is a file, not a folder", dir.string()));
  }
  ProbeFolder(path, option, dir);
}

void CheckOutputFolder(const std::string& dir, const std::string& option) {
  if (dir.empty()) CannotWrite(dir, option, "no folder name was given");
  std::error_code ec;
  for (fs::path q = dir; !q.empty(); q = q.parent_path()) {
    const fs::file_status s = fs::status(q, ec);
    if (!fs::exists(s)) {
      if (q == q.root_path() || q.parent_path() == q) break;
      continue;
    }
    if (!fs::is_directory(s)) {
      throw InputError(
          fmt::format("cannot create the output folder '{}'{}: '{}' is a file, not a "
                      "folder",
                      dir, option.empty() ? "" : fmt::format(" ({})", option), q.string()));
    }
    // The folder itself, or the nearest existing one where the missing ones will be made.
    ProbeFolder(dir, option, q);
    return;
  }
  // A relative path none of whose parts exists: made in the current folder.
  ProbeFolder(dir, option, ".");
}

void CreateOutputFolder(const std::string& dir) {
  std::error_code ec;
  for (fs::path q = dir; !q.empty() && q != q.root_path(); q = q.parent_path()) {
    const fs::file_status s = fs::status(q, ec);
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) {
        throw InputError(
            fmt::format("cannot create the output folder '{}': '{}' is a file, not "
                        "a folder",
                        dir, q.string()));
      }
      break;
    }
  }
  fs::create_directories(dir, ec);
  if (ec) {
    throw InputError(fmt::format("cannot create the output folder '{}': {}", dir, ec.message()));
  }
}

}  // namespace chasles
