#pragma once
/// @file
/// The processes of `mpirun -np N chasles ...` (docs/sweeps.md). Started by mpirun with more
/// than one process, the program opens the MPI plugin (libchasles_mpi.so, mpi/chasles_mpi.h)
/// with dlopen; otherwise it loads nothing and runs alone, as without MPI. A sweep then runs
/// its share of the points on every rank and rank 0 alone writes the table; any other command
/// runs on rank 0 alone. Errors are printed once, by rank 0, and every rank exits with rank 0's
/// code.

#include <cstdint>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "chasles/analysis/sweep.h"
#include "chasles/scene/solve.h"

namespace chasles::cli {

/// A failure another rank reported, as rank 0 prints it: its message line and exit code.
class RankFailure : public std::exception {
 public:
  RankFailure(int code, std::string line) : code_(code), line_(std::move(line)) {}
  const char* what() const noexcept override { return line_.c_str(); }
  int code() const { return code_; }

 private:
  int code_;
  std::string line_;
};

class Cluster {
 public:
  /// The one of this process.
  static Cluster& Get();

  /// The number of processes mpirun started, from its environment (OMPI_COMM_WORLD_SIZE, or
  /// PMI_SIZE of MPICH's and Slurm's launchers); 1 when none is set.
  static int LaunchedSize();
  /// This process's rank from the same environment (0 when none is set).
  static int LaunchedRank();

  /// Opens the plugin (CHASLES_MPI_PLUGIN if set, else libchasles_mpi.so beside the program:
  /// ../lib, ../<libdir>, its own folder, then the loader's search path) and initialises MPI.
  /// Throws InputError saying what is missing when it cannot.
  void Start();
  /// MPI_Finalize, when started.
  void Finish();

  bool distributed() const { return size_ > 1; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  SweepShare share() const { return {rank_, size_}; }

  /// Sends this rank's part to rank 0: returns every rank's part there (in rank order), none
  /// elsewhere. Collective, and once per run: a sweep command calls it when its share is done,
  /// the error handler when the command failed before.
  std::vector<SweepPart> Exchange(const SweepPart& mine);
  bool exchanged() const { return exchanged_; }

  /// Every rank's exit code made rank 0's. Collective.
  int AgreeExitCode(int code);

  /// The sweep point this rank is at (a solve sweep stops at the first that fails).
  void set_point(std::int64_t k) { point_ = k; }
  std::int64_t point() const { return point_; }

 private:
  struct Plugin;
  Cluster() = default;
  int rank_ = 0, size_ = 1;
  bool exchanged_ = false;
  std::int64_t point_ = -1;
  Plugin* plugin_ = nullptr;
};

/// A sweep's end on every rank: when distributed, sends this rank's rows of `table` (with
/// `warnings` and `check_failed`) to rank 0, where the rows of every rank are merged into
/// `table`, `warnings` and `check_failed` as the serial sweep leaves them. Returns whether
/// this process writes the results (rank 0, or not distributed). Rank 0 throws RankFailure
/// when another rank failed before or during its share.
bool GatherSweep(SweepTable* table, SweepWarnings* warnings, bool* check_failed);

}  // namespace chasles::cli
