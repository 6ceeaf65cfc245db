#pragma once
/// @file
/// Threads that share work and start only as far as the system lets them. A thread that cannot
/// be started (an address-space or process limit: std::system_error) is not an error: the work
/// goes to the threads that did start, the calling thread among them, so a request for 1000
/// threads under a tight limit runs on fewer instead of ending the program.

#include <functional>

namespace chasles {

/// Calls `work` on up to `threads` threads at once (the calling thread is one of them; fewer
/// when the system refuses more) and returns when every call has returned, with the number of
/// threads that ran. The calls share the work themselves (an atomic counter of items), so the
/// result does not depend on how many ran. An exception out of the calling thread's `work` is
/// thrown again after the others have ended; `work` on the other threads must not throw.
int RunOnThreads(int threads, const std::function<void()>& work);

}  // namespace chasles
