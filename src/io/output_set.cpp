#include "chasles/io/output_set.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

namespace {

namespace fs = std::filesystem;

// The temporaries that exist right now, for the signal handler. Changed only with the signals
// held (SignalsHeld), so the handler never sees a half-written entry; it only reads them and
// calls unlink, sigaction and raise, which are async-signal-safe (POSIX.1-2017, 2.4.3).
constexpr int kSlots = 32;
constexpr size_t kPathBytes = 4096;
char g_temp[kSlots][kPathBytes];
volatile sig_atomic_t g_used[kSlots];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr int kSignalCount = 3;
struct sigaction g_previous[kSignalCount];
bool g_installed = false;

extern "C" void RemoveTemporariesAndReraise(int sig) {
  const int saved = errno;
  for (int i = 0; i < kSlots; ++i) {
    if (g_used[i]) ::unlink(g_temp[i]);
  }
  // The disposition the program had before (normally the default: terminate), then the same
  // signal again; it is delivered once this handler returns.
  for (int k = 0; k < kSignalCount; ++k) {
    if (kSignals[k] == sig) ::sigaction(sig, &g_previous[k], nullptr);
  }
  errno = saved;
  ::raise(sig);
}

/// Holds SIGINT, SIGTERM and SIGHUP back for its lifetime; a signal that arrives meanwhile is
/// delivered when it ends.
class SignalsHeld {
 public:
  SignalsHeld() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kSignals) sigaddset(&set, s);
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsHeld() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t old_;
};

// With the signals held. A signal the program ignores (nohup) stays ignored.
void InstallHandlersOnce() {
  if (g_installed) return;
  g_installed = true;
  for (int k = 0; k < kSignalCount; ++k) {
    struct sigaction now {};
    ::sigaction(kSignals[k], nullptr, &now);
    g_previous[k] = now;
    if (!(now.sa_flags & SA_SIGINFO) && now.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = RemoveTemporariesAndReraise;
    sigemptyset(&sa.sa_mask);
    for (int s : kSignals) sigaddset(&sa.sa_mask, s);
    ::sigaction(kSignals[k], &sa, nullptr);
  }
}

// With the signals held.
int Register(const std::string& temp) {
  if (temp.size() >= kPathBytes) {
    throw InputError(fmt::format("cannot write '{}': the path is too long", temp));
  }
  for (int i = 0; i < kSlots; ++i) {
    if (!g_used[i]) {
      std::memcpy(g_temp[i], temp.c_str(), temp.size() + 1);
      g_used[i] = 1;
      return i;
    }
  }
  throw InputError(fmt::format("cannot write '{}': too many output files at once", temp));
}

void Unregister(int slot) {
  if (slot >= 0) g_used[slot] = 0;
}

[[noreturn]] void CannotWrite(const std::string& path, const std::string& reason) {
  throw InputError(fmt::format("cannot write '{}': {}", path, reason));
}

/// The nearest existing ancestor of `dir`, to say why a folder is missing.
void ExplainMissingFolder(const std::string& path, const fs::path& dir) {
  std::error_code ec;
  for (fs::path q = dir.parent_path(); !q.empty() && q != q.root_path(); q = q.parent_path()) {
    const fs::file_status s = fs::status(q, ec);
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) {
        CannotWrite(path, fmt::format("'{}' is a file, not a folder", q.string()));
      }
      break;
    }
  }
  CannotWrite(path, fmt::format("the folder '{}' does not exist (create it first)", dir.string()));
}

void WriteAll(int fd, const std::string& path, const std::string& content) {
  size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      CannotWrite(path, std::strerror(errno));
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 && errno != EINVAL) CannotWrite(path, std::strerror(errno));
}

}  // namespace

void CheckOutputTarget(const std::string& path) {
  if (path.empty()) CannotWrite(path, "no file name was given");
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(fs::status(p, ec))) {
    CannotWrite(path, "it is a folder; give a file name");
  }
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const fs::file_status ds = fs::status(dir, ec);
  if (!fs::exists(ds)) ExplainMissingFolder(path, dir);
  if (!fs::is_directory(ds)) {
    CannotWrite(path, fmt::format("'{}' is a file, not a folder", dir.string()));
  }
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

OutputSet::~OutputSet() {
  if (!committed_) Discard();
}

void OutputSet::Add(std::string path, std::string content) {
  files_.push_back({std::move(path), std::move(content), "", -1});
}

void OutputSet::Discard() {
  SignalsHeld held;
  for (File& f : files_) {
    if (!f.temp.empty()) ::unlink(f.temp.c_str());
    Unregister(f.slot);
    f.slot = -1;
    f.temp.clear();
  }
}

void OutputSet::Commit() {
  try {
    for (const File& f : files_) CheckOutputTarget(f.path);
    static int counter = 0;
    for (File& f : files_) {
      const fs::path target(f.path);
      const fs::path temp =
          target.parent_path() /
          fmt::format(".{}.{}-{}.tmp", target.filename().string(), ::getpid(), counter++);
      int fd = -1;
      {
        // Registered before it exists, so a signal never leaves an unknown temporary.
        SignalsHeld held;
        InstallHandlersOnce();
        f.slot = Register(temp.string());
        f.temp = temp.string();
        fd = ::open(f.temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
          const int error = errno;
          Unregister(f.slot);
          f.slot = -1;
          f.temp.clear();
          CannotWrite(f.path, std::strerror(error));
        }
      }
      try {
        WriteAll(fd, f.path, f.content);
      } catch (...) {
        ::close(fd);
        throw;
      }
      if (::close(fd) != 0) CannotWrite(f.path, std::strerror(errno));
    }
    SignalsHeld held;
    for (size_t i = 0; i < files_.size(); ++i) {
      File& f = files_[i];
      if (::rename(f.temp.c_str(), f.path.c_str()) != 0) {
        const int error = errno;
        // Take back the files of this set already in place: none of the set stays.
        for (size_t k = 0; k < i; ++k) ::unlink(files_[k].path.c_str());
        CannotWrite(f.path, std::strerror(error));
      }
      Unregister(f.slot);
      f.slot = -1;
      f.temp.clear();
    }
    committed_ = true;
  } catch (...) {
    Discard();
    throw;
  }
}

}  // namespace chasles
