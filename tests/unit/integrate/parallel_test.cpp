// RunOnThreads (chasles/integrate/parallel.h): every item is done once, however many threads
// the system starts; a thread that cannot start is not an error; the calling thread's
// exception comes back after the others have ended.

#include "chasles/integrate/parallel.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace chasles {
namespace {

/// Runs `items` items on `threads` threads; true when each was done exactly once.
bool EachItemOnce(int threads, int items, int* ran) {
  std::vector<std::atomic<int>> done(static_cast<size_t>(items));
  std::atomic<int> next{0};
  *ran = RunOnThreads(threads, [&] {
    for (int k; (k = next++) < items;) ++done[static_cast<size_t>(k)];
  });
  for (const auto& d : done) {
    if (d != 1) return false;
  }
  return true;
}

TEST(RunOnThreads, DoesEveryItemOnceOnTheThreadsAsked) {
  int ran = 0;
  EXPECT_TRUE(EachItemOnce(1, 1000, &ran));
  EXPECT_EQ(ran, 1);
  EXPECT_TRUE(EachItemOnce(8, 1000, &ran));
  EXPECT_EQ(ran, 8);
  EXPECT_TRUE(EachItemOnce(0, 10, &ran));  // fewer than one: the calling thread alone
  EXPECT_EQ(ran, 1);
}

TEST(RunOnThreads, AThousandThreadsUnderAnAddressSpaceLimitRunOnFewer) {
  // In a child process: 1000 thread stacks (8 MiB each by default) cannot fit in 512 MiB more
  // than the process has, so most threads cannot start; the work is still done, once, by the
  // ones that did (before, std::terminate: the pool unwound past joinable threads).
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    rlimit limit{};
    ::getrlimit(RLIMIT_AS, &limit);
    long pages = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
      std::fclose(f);
    }
    limit.rlim_cur = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) +
                     (rlim_t{512} << 20);
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(3);
    int ran = 0;
    const bool ok = EachItemOnce(1000, 100000, &ran);
    ::_exit(ok && ran >= 1 && ran < 1000 ? 0 : 4);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "the child ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(RunOnThreads, TheCallingThreadsExceptionComesBackAfterTheOthersEnd) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> ended{0};
  EXPECT_THROW(RunOnThreads(4,
                            [&] {
                              if (std::this_thread::get_id() == caller) {
                                throw std::runtime_error("the calling thread's call");
                              }
                              ++ended;
                            }),
               std::runtime_error);
  EXPECT_EQ(ended, 3);  // the three other calls had returned
}

}  // namespace
}  // namespace chasles
