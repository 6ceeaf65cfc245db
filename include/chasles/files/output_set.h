#pragma once
/// @file
/// The one way every file of the program is written: a run's CSV and JSON, kept runs, reports,
/// browser pages, plots, and the text that goes to standard output ("-").
///
/// A command makes one OutputSet, names every target it will write with Expect() before any
/// work (so a wrong path costs nothing), adds the contents when they are made, and commits:
///  1. every target is checked when expected: two targets of the set naming one file, a target
///     that is not a regular file (a folder, a device, a FIFO, a socket, a symbolic link), a
///     missing folder, or a folder where no file can be created are errors naming the option,
///     the path and the reason; "-" is standard output;
///  2. each file is written in full and flushed (fsync) under a temporary name beside its
///     target (`.NAME.PID-N.tmp`);
///  3. the targets' folders are locked (flock, so two processes writing one --out folder never
///     leave a mixed pair) and the temporaries renamed into place together, with signals held
///     process-wide (GuardOutputsAgainstSignals);
///  4. what goes to standard output is written last, its errors checked.
/// A failure removes the temporaries and any file of the set already renamed; so does SIGINT,
/// SIGTERM or SIGHUP once GuardOutputsAgainstSignals() has been called. The state is per
/// set: any number of sets, of any size, may be written at once from any threads.
/// SIGKILL and power loss are not covered (a temporary may be left; its name ends in .tmp).

#include <memory>
#include <string>
#include <vector>

namespace chasles {

/// True for "-", the name that stands for standard output where an option takes a file.
bool IsStandardOutput(const std::string& path);

class OutputSet {
 public:
  OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  /// Removes any temporary still present (a failure on the way); a set never committed writes
  /// nothing.
  ~OutputSet();

  /// Checks `path` as a target now (CheckOutputTarget; "-" is standard output) and keeps it:
  /// `option` names what gave it ("-o", "--html") in the errors. Throws InputError when it
  /// names the same file as a target already expected or added.
  void Expect(const std::string& path, const std::string& option);

  /// A folder the targets under it go into (simulate --out): checked now (CheckOutputFolder)
  /// and created at Commit, before the files; removed again if the commit fails and it was
  /// made by it.
  void ExpectFolder(const std::string& dir, const std::string& option);

  /// Queues `content` for `path` ("-": standard output). A path not expected is checked now as
  /// by Expect. Nothing is written until Commit().
  void Add(const std::string& path, std::string content);

  /// Writes every file to its temporary, renames all into place, then writes standard output.
  /// Throws InputError naming the path and the reason; then no file of the set is left in
  /// place and no temporary remains.
  void Commit();

 private:
  struct File;
  struct Target;
  const Target* Find(const std::string& path) const;
  void Discard();
  void WriteTemporaries();
  void RenameAll();
  std::vector<std::unique_ptr<Target>> targets_;
  std::vector<std::unique_ptr<File>> files_;
  std::vector<std::string> folders_;  // to create at Commit, outermost first
  std::vector<std::string> created_;  // folders Commit made
  std::string standard_output_;
  bool has_standard_output_ = false;
  bool committed_ = false;
};

/// Throws InputError if `path` cannot be an output file: it is empty, it exists and is not a
/// regular file (a folder, a device, a FIFO, a socket, a symbolic link), its folder does not
/// exist or a part of it is a regular file, or no file can be created in its folder (tried
/// with a temporary that is removed at once). `option` ("-o"), when given, is named in the
/// message. "-" is not a path here: the caller decides whether standard output is allowed.
void CheckOutputTarget(const std::string& path, const std::string& option = "");

/// Throws InputError if the folder `dir` neither exists (as a folder) nor can be created: a
/// part of it is a regular file, or its nearest existing ancestor is not a folder where
/// folders can be made. Creates nothing.
void CheckOutputFolder(const std::string& dir, const std::string& option = "");

/// Creates the folder `dir` and its parents if missing. Throws InputError naming the folder
/// and the reason (a part of it is a regular file, permission denied).
void CreateOutputFolder(const std::string& dir);

/// Makes SIGINT, SIGTERM and SIGHUP remove every output temporary of the process before it
/// ends by the signal (with its default action, so the exit status still says which). Call
/// it once at the start of a program, before any thread is started: it blocks those signals
/// in the calling thread (and so in every thread started after it) and starts one thread that
/// waits for them; a commit's renames hold it off until they are done, so a signal finds
/// either none or all of a set's files in place. A signal the program ignores (nohup) stays
/// ignored, and one it handles itself is left alone. Without it (a library user) the signals
/// are not intercepted: they may leave a temporary, as SIGKILL may.
void GuardOutputsAgainstSignals();

}  // namespace chasles
