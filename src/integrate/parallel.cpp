// Threads that degrade to fewer (chasles/integrate/parallel.h).

#include "chasles/integrate/parallel.h"

#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace chasles {

int RunOnThreads(int threads, const std::function<void()>& work) {
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads: the ones running share the rest
    }
  }
  std::exception_ptr failure;
  try {
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return static_cast<int>(pool.size()) + 1;
}

}  // namespace chasles
