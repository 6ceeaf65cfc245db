#pragma once
/// @file
/// A run's output files, all or nothing. Every file is first written in full (and flushed to
/// disk) under a temporary name beside its target; only when all are complete are they renamed
/// into place, one after the other with SIGINT, SIGTERM and SIGHUP held back, so a signal
/// either finds no file of the run in place or finds them all. A failure removes what the set
/// wrote; so does SIGINT/SIGTERM/SIGHUP while the temporaries exist (the handler only unlinks
/// the temporaries it knows and re-raises the signal). SIGKILL and power loss are not covered.

#include <string>
#include <vector>

namespace chasles {

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  /// Removes any temporary still present (a failure on the way).
  ~OutputSet();

  /// Queues a file. Nothing is written until Commit().
  void Add(std::string path, std::string content);

  /// Checks every target (its folder exists and is a folder, the target is not a folder),
  /// writes each to its temporary, then renames all into place. Throws InputError naming the
  /// path and the reason; then no file of the set is left in place and no temporary remains.
  void Commit();

 private:
  struct File {
    std::string path, content, temp;
    int slot = -1;  // index in the signal handler's list of temporaries
  };
  void Discard();
  std::vector<File> files_;
  bool committed_ = false;
};

/// Throws InputError if `path` cannot be an output file: its folder does not exist, a part of
/// its folder is a regular file, or `path` is a folder. The message names the path and says
/// which.
void CheckOutputTarget(const std::string& path);

/// Creates the folder `dir` and its parents if missing. Throws InputError naming the folder
/// and the reason (a part of it is a regular file, permission denied).
void CreateOutputFolder(const std::string& dir);

}  // namespace chasles
