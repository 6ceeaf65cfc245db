#pragma once
/// @file
/// The output temporaries that exist in the process right now, for the signal guard
/// (GuardOutputsAgainstSignals, chasles/files/output_set.h). Private to the files layer.
///
/// One mutex guards the list. Every temporary is registered before it is created and forgotten
/// only after it was renamed or removed, both under the mutex; the guard's thread takes the
/// same mutex before it removes them, so a batch of renames done under Hold() is never cut in
/// two by a signal. Any number of temporaries, from any threads.

#include <list>
#include <mutex>
#include <string>

namespace chasles::internal {

class Temporaries {
 public:
  using Handle = std::list<std::string>::iterator;

  /// The process's list (never destroyed: the guard's thread may use it during exit).
  static Temporaries& Get();

  /// Held for a batch of renames: the signal guard waits until it is released.
  std::unique_lock<std::mutex> Hold() { return std::unique_lock<std::mutex>(mutex_); }

  /// Creates the file `path` (new, write only) registered first. Returns the descriptor, or -1
  /// with errno set (then nothing is registered).
  int Create(const std::string& path, Handle* handle);
  /// Unlinks the temporary and forgets it.
  void Remove(Handle handle);
  /// Forgets a temporary that was renamed into place; the caller holds Hold().
  void ForgetHeld(Handle handle) { paths_.erase(handle); }
  /// Unlinks a temporary and forgets it; the caller holds Hold().
  void RemoveHeld(Handle handle);

  /// The guard's thread, on signal `sig`: waits for any batch of renames, removes every
  /// temporary and ends the process by the signal's default action.
  [[noreturn]] void RemoveAllAndEnd(int sig);

 private:
  Temporaries() = default;
  std::mutex mutex_;
  std::list<std::string> paths_;
};

}  // namespace chasles::internal
