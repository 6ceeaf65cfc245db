// The process's output temporaries and the signal guard (files/internal/temporaries.h,
// chasles/files/output_set.h).

#include "files/internal/temporaries.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>
#include <cerrno>
#include <mutex>
#include <system_error>
#include <thread>

#include "chasles/files/output_set.h"

namespace chasles::internal {

Temporaries& Temporaries::Get() {
  static Temporaries* const list = new Temporaries();  // never destroyed, see the header
  return *list;
}

int Temporaries::Create(const std::string& path, Handle* handle) {
  const std::lock_guard<std::mutex> lock(mutex_);
  paths_.push_front(path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    paths_.pop_front();
    errno = error;
    return -1;
  }
  *handle = paths_.begin();
  return fd;
}

void Temporaries::Remove(Handle handle) {
  const std::lock_guard<std::mutex> lock(mutex_);
  RemoveHeld(handle);
}

void Temporaries::RemoveHeld(Handle handle) {
  ::unlink(handle->c_str());
  paths_.erase(handle);
}

void Temporaries::RemoveAllAndEnd(int sig) {
  mutex_.lock();  // never released: the process ends here
  for (const std::string& p : paths_) ::unlink(p.c_str());
  // The signal again with its default action, delivered to this thread, the only one that
  // does not block it.
  struct sigaction sa {};
  sa.sa_handler = SIG_DFL;
  sigemptyset(&sa.sa_mask);
  ::sigaction(sig, &sa, nullptr);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  ::pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);  // not reached: the default action of these signals ends the process
}

}  // namespace chasles::internal

namespace chasles {

void GuardOutputsAgainstSignals() {
  static std::once_flag once;
  std::call_once(once, [] {
    sigset_t set;
    sigemptyset(&set);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction now {};
      ::sigaction(s, nullptr, &now);
      // Only signals with their default action: one ignored (nohup) stays ignored, one the
      // program handles itself stays its own.
      if (!(now.sa_flags & SA_SIGINFO) && now.sa_handler == SIG_DFL) sigaddset(&set, s);
    }
    sigset_t old;
    ::pthread_sigmask(SIG_BLOCK, &set, &old);
    try {
      std::thread([set] {
        int sig = 0;
        while (::sigwait(&set, &sig) != 0) {
        }
        internal::Temporaries::Get().RemoveAllAndEnd(sig);
      }).detach();
    } catch (const std::system_error&) {
      // No thread to wait for the signals: they keep their default action, as without a guard.
      ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    }
  });
}

}  // namespace chasles
