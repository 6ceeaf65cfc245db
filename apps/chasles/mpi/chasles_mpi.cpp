// The MPI plugin (chasles_mpi.h): the only code that calls MPI, loaded by the program with
// dlopen under mpirun.

#include "chasles_mpi.h"

#include <mpi.h>

#include <climits>
#include <vector>

extern "C" {

__attribute__((visibility("default"))) int chasles_mpi_abi(void) {
  return CHASLES_MPI_ABI;
}

__attribute__((visibility("default"))) int chasles_mpi_init(int* rank, int* size) {
  int e = MPI_Init(nullptr, nullptr);
  if (e == MPI_SUCCESS) e = MPI_Comm_rank(MPI_COMM_WORLD, rank);
  if (e == MPI_SUCCESS) e = MPI_Comm_size(MPI_COMM_WORLD, size);
  return e;
}

__attribute__((visibility("default"))) int chasles_mpi_gather(const char* data, int64_t size,
                                                              chasles_mpi_sink_fn sink,
                                                              void* context) {
  int rank = 0, ranks = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  // The sizes first, then the bytes (MPI counts are ints: more than 2 GiB in all is refused).
  std::vector<int64_t> sizes(static_cast<size_t>(rank == 0 ? ranks : 0));
  int e = MPI_Gather(&size, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, 0, MPI_COMM_WORLD);
  if (e != MPI_SUCCESS) return e;
  std::vector<int> counts(sizes.size()), offsets(sizes.size());
  int64_t total = 0;
  for (size_t r = 0; r < sizes.size(); ++r) {
    counts[r] = static_cast<int>(sizes[r]);
    offsets[r] = static_cast<int>(total);
    total += sizes[r];
  }
  // Every rank learns whether the whole fits before any sends it.
  int fits = size <= INT_MAX && total <= INT_MAX ? 1 : 0;
  int all_fit = 0;
  e = MPI_Allreduce(&fits, &all_fit, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (e != MPI_SUCCESS) return e;
  if (!all_fit) return MPI_ERR_COUNT;
  std::vector<char> all(static_cast<size_t>(total));
  e = MPI_Gatherv(data, static_cast<int>(size), MPI_BYTE, all.data(), counts.data(), offsets.data(),
                  MPI_BYTE, 0, MPI_COMM_WORLD);
  if (e != MPI_SUCCESS) return e;
  for (size_t r = 0; r < sizes.size(); ++r) {
    sink(context, static_cast<int>(r), all.data() + offsets[r], sizes[r]);
  }
  return MPI_SUCCESS;
}

__attribute__((visibility("default"))) int chasles_mpi_broadcast_int(int* value) {
  return MPI_Bcast(value, 1, MPI_INT, 0, MPI_COMM_WORLD);
}

__attribute__((visibility("default"))) int chasles_mpi_finalize(void) {
  return MPI_Finalize();
}

}  // extern "C"
