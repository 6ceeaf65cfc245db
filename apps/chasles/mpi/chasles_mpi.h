#pragma once
/// @file
/// The C interface of the MPI plugin (libchasles_mpi.so, chasles_mpi.cpp): the few MPI calls a
/// sweep split over `mpirun -np N` ranks needs (docs/sweeps.md). The program never links libmpi;
/// it opens the plugin with dlopen only when mpirun started it (cluster.cpp), so it runs the
/// same on a machine without MPI. Every function returns 0 on success, else an MPI error code.

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// The version of this interface; the program refuses a plugin of another.
#define CHASLES_MPI_ABI 1
typedef int (*chasles_mpi_abi_fn)(void);

/// MPI_Init (only the main thread calls MPI), then this process's rank and the world's size.
typedef int (*chasles_mpi_init_fn)(int* rank, int* size);

/// Receives one rank's bytes on rank 0, in rank order.
typedef void (*chasles_mpi_sink_fn)(void* context, int rank, const char* data, int64_t size);

/// Gathers `size` bytes of every rank to rank 0, which gets each through `sink` in rank order
/// (the other ranks get none). Collective: every rank calls it once.
typedef int (*chasles_mpi_gather_fn)(const char* data, int64_t size, chasles_mpi_sink_fn sink,
                                     void* context);

/// Broadcasts rank 0's `*value` to every rank. Collective.
typedef int (*chasles_mpi_broadcast_int_fn)(int* value);

/// MPI_Finalize.
typedef int (*chasles_mpi_finalize_fn)(void);

#ifdef __cplusplus
}
#endif
