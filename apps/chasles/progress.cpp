#include "progress.h"

#include <unistd.h>
#include <cstdio>

#include <fmt/format.h>

namespace chasles::cli {

namespace {
constexpr std::chrono::milliseconds kTerminalDelay{1000}, kTerminalInterval{200};
}  // namespace

Progress::Progress(std::string what, std::string unit, bool quiet, double interval)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      quiet_(quiet),
      tty_(::isatty(::fileno(stderr)) != 0),
      interval_(interval),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

Progress::~Progress() {
  // Leave the terminal line clean for the report (a log keeps its lines).
  if (shown_ && tty_) std::fprintf(stderr, "\r%70s\r", "");
}

void Progress::Update(double done, double total) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (tty_) {
    if (now - start_ < kTerminalDelay || now - last_ < kTerminalInterval) return;
  } else if (now - last_ < interval_) {
    return;
  }
  last_ = now;
  shown_ = true;
  const std::string u = unit_.empty() ? "" : " " + unit_;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string line = fmt::format("{}: {}{:.6g}{} of {:.6g}{} ({:3.0f}%), {:.0f} s elapsed",
                                       what_, unit_ == "s" ? "t = " : "", done, u, total, u,
                                       total > 0 ? 100.0 * done / total : 0.0, elapsed);
  if (tty_) {
    std::fprintf(stderr, "\r  %s", line.c_str());
  } else {
    std::fprintf(stderr, "chasles: %s\n", line.c_str());
  }
  std::fflush(stderr);
}

}  // namespace chasles::cli
