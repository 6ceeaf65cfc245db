#pragma once
/// @file
/// Progress of a long command on standard error (simulate, solve --sweep).
///
/// On a terminal: one line redrawn in place, at most every 0.2 s, from the first second on.
/// Off a terminal (a log file, CI): one line every 10 s of wall time (--progress-interval). A rate
/// in wall time rather than in percent: a short run prints nothing, a long one shows it is alive at
/// a steady pace (360 lines an hour at most) however unevenly its simulated time advances, and a
/// run stuck inside one tenth of its span still reports. Nothing at all with --quiet.

#include <chrono>
#include <string>

namespace chasles::cli {

class Progress {
 public:
  /// `what`: the activity ("simulating"); `unit`: the unit of the counts ("s" for simulated
  /// time, "" for a count of values); `interval`: seconds between lines off a terminal.
  Progress(std::string what, std::string unit, bool quiet, double interval = kLogInterval);
  /// Seconds between progress lines off a terminal, by default.
  static constexpr double kLogInterval = 10.0;
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports `done` of `total` when it is time to.
  void Update(double done, double total);

 private:
  std::string what_, unit_;
  bool quiet_, tty_;
  std::chrono::duration<double> interval_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace chasles::cli
