// Every file the program writes, all or nothing (chasles/files/output_set.h).

#include "chasles/files/output_set.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <thread>

#include <fmt/format.h>

#include "chasles/error.h"
#include "files/internal/output_target.h"
#include "files/internal/temporaries.h"

namespace chasles {

namespace {

namespace fs = std::filesystem;
using internal::CannotWrite;
using internal::Temporaries;

/// How long a commit waits for another process to finish renaming into the same folder.
constexpr std::chrono::seconds kFolderLockWait{10};

void WriteAll(int fd, const std::string& path, const std::string& content) {
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      CannotWrite(path, "", std::strerror(errno));
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 && errno != EINVAL) CannotWrite(path, "", std::strerror(errno));
}

/// The folder of `path` ("." for a bare name).
std::string FolderOf(const std::string& path) {
  const fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? std::string(".") : dir.string();
}

/// Exclusive flock()s on folders for a batch of renames: another process renaming into one of
/// them waits (two runs on one --out folder never leave the CSV of one and the JSON of the
/// other). Taken in the order of the folders' real paths, so two processes cannot deadlock; a
/// folder that cannot be opened for reading is not locked.
class FolderLocks {
 public:
  explicit FolderLocks(const std::vector<std::string>& folders) {
    std::vector<std::string> keys;
    for (const std::string& f : folders) keys.push_back(internal::TargetKey(f + "/."));
    std::vector<size_t> order(folders.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return keys[a] < keys[b]; });
    for (size_t k = 0; k < order.size(); ++k) {
      const size_t i = order[k];
      if (k > 0 && keys[i] == keys[order[k - 1]]) continue;
      Lock(folders[i]);
    }
  }
  ~FolderLocks() {
    for (const int fd : fds_) ::close(fd);  // closing releases the lock
  }
  FolderLocks(const FolderLocks&) = delete;
  FolderLocks& operator=(const FolderLocks&) = delete;

 private:
  void Lock(const std::string& folder) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    fds_.push_back(fd);
    const auto give_up = std::chrono::steady_clock::now() + kFolderLockWait;
    while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EWOULDBLOCK && errno != EINTR) return;  // a file system without locks
      if (std::chrono::steady_clock::now() > give_up) {
        throw InputError(fmt::format(
            "cannot write into the folder '{}': another process kept it locked for {} s while "
            "renaming its outputs there",
            folder, kFolderLockWait.count()));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  std::vector<int> fds_;
};

void WriteStandardOutput(const std::string& text) {
  std::fwrite(text.data(), 1, text.size(), stdout);
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    throw InputError(fmt::format("cannot write to standard output: {}", std::strerror(errno)));
  }
}

}  // namespace

struct OutputSet::Target {
  std::string path, option, key;
};

struct OutputSet::File {
  std::string path, content, temp;
  Temporaries::Handle handle;
  bool has_temp = false;
};

OutputSet::OutputSet() = default;

OutputSet::~OutputSet() {
  if (!committed_) Discard();
}

const OutputSet::Target* OutputSet::Find(const std::string& path) const {
  for (const auto& t : targets_) {
    if (t->path == path) return t.get();
  }
  return nullptr;
}

void OutputSet::Expect(const std::string& path, const std::string& option) {
  const auto same = [&](const Target& t) {
    const auto named = [](const std::string& opt, const std::string& p) {
      return opt.empty() ? fmt::format("'{}'", p) : fmt::format("{} '{}'", opt, p);
    };
    throw InputError(fmt::format("{} and {} name the same {}; give each output its own name",
                                 named(t.option, t.path), named(option, path),
                                 t.key == "-" ? "output, standard output" : "file"));
  };
  std::string key = "-";
  if (!IsStandardOutput(path)) {
    // A target in a folder this set makes at Commit is checked with the folder.
    const std::string folder = FolderOf(path);
    const bool made_later = std::find(folders_.begin(), folders_.end(), folder) != folders_.end() &&
                            !fs::exists(folder);
    if (!made_later) CheckOutputTarget(path, option);
    key = internal::TargetKey(path);
  }
  for (const auto& t : targets_) {
    if (t->key == key) same(*t);
  }
  targets_.push_back(std::make_unique<Target>(Target{path, option, key}));
}

void OutputSet::ExpectFolder(const std::string& dir, const std::string& option) {
  CheckOutputFolder(dir, option);
  const std::string normal = FolderOf((fs::path(dir) / "x").string());
  if (!fs::exists(normal)) folders_.push_back(normal);
}

void OutputSet::Add(const std::string& path, std::string content) {
  if (Find(path) == nullptr) Expect(path, "");
  if (IsStandardOutput(path)) {
    standard_output_ += content;
    has_standard_output_ = true;
    return;
  }
  auto f = std::make_unique<File>();
  f->path = path;
  f->content = std::move(content);
  files_.push_back(std::move(f));
}

void OutputSet::Discard() {
  Temporaries& temps = Temporaries::Get();
  for (auto& f : files_) {
    if (f->has_temp) temps.Remove(f->handle);
    f->has_temp = false;
  }
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) ::rmdir(it->c_str());
  created_.clear();
}

void OutputSet::WriteTemporaries() {
  for (const std::string& dir : folders_) {
    // Made one part at a time, so that a failed commit removes exactly what it made.
    std::vector<fs::path> missing;
    for (fs::path q = dir; !q.empty() && !fs::exists(q); q = q.parent_path()) missing.push_back(q);
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      if (::mkdir(it->c_str(), 0777) == 0) {
        created_.push_back(it->string());
      } else if (errno != EEXIST) {
        throw InputError(
            fmt::format("cannot create the output folder '{}': {}", dir, std::strerror(errno)));
      }
    }
  }
  Temporaries& temps = Temporaries::Get();
  for (auto& f : files_) {
    // Checked again: the target may have changed during the run (a FIFO, a link put there).
    struct stat st {};
    if (::lstat(f->path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) CheckOutputTarget(f->path);
    f->temp = internal::TemporaryPathFor(f->path);
    const int fd = temps.Create(f->temp, &f->handle);
    if (fd < 0) CannotWrite(f->path, "", std::strerror(errno));
    f->has_temp = true;
    try {
      WriteAll(fd, f->path, f->content);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) CannotWrite(f->path, "", std::strerror(errno));
  }
}

void OutputSet::RenameAll() {
  Temporaries& temps = Temporaries::Get();
  std::vector<std::string> folders;
  for (const auto& f : files_) folders.push_back(FolderOf(f->path));
  const std::unique_lock<std::mutex> held = temps.Hold();  // the signal guard waits for us
  const FolderLocks locks(folders);
  for (size_t i = 0; i < files_.size(); ++i) {
    File& f = *files_[i];
    if (::rename(f.temp.c_str(), f.path.c_str()) != 0) {
      const int error = errno;
      // Take back the files of this set already in place: none of the set stays.
      for (size_t k = 0; k < i; ++k) ::unlink(files_[k]->path.c_str());
      for (size_t k = i; k < files_.size(); ++k) {
        temps.RemoveHeld(files_[k]->handle);
        files_[k]->has_temp = false;
      }
      CannotWrite(f.path, "", std::strerror(error));
    }
    temps.ForgetHeld(f.handle);
    f.has_temp = false;
  }
}

void OutputSet::Commit() {
  try {
    WriteTemporaries();
    RenameAll();
    committed_ = true;
  } catch (...) {
    Discard();
    throw;
  }
  if (has_standard_output_) WriteStandardOutput(standard_output_);
}

}  // namespace chasles
