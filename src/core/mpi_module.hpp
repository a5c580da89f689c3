// The interface between src/core/ranks.cpp and the MPI module penink_mpi.so (src/core/mpi/): plain
// C functions over MPI_COMM_WORLD. The module is dlopen()ed only when penink was started by an
// MPI launcher (mpirun, srun: launched_ranks), so no other run loads Open MPI and its libraries.
// Messages of any length: a u64 length, then pieces of at most 1 GiB (MPI counts are int).
// Every function returns 0 on success, else an MPI error code and a one-line reason in `error`.
#pragma once
#include <cstddef>
#include <cstdint>

extern "C" {

// Where a received message goes: a buffer of n bytes (null: cannot, the message is refused).
using PeninkMpiAlloc = void* (*)(void* ctx, std::uint64_t n);

struct PeninkMpiApi {
    int (*init)(int* rank, int* size, char* error, std::size_t error_size);
    int (*send)(int to, int tag, const void* bytes, std::uint64_t n, char* error, std::size_t error_size);
    int (*receive)(int from, int tag, PeninkMpiAlloc alloc, void* ctx, char* error, std::size_t error_size);
    // root's n bytes to every rank; the others' land where alloc puts them
    int (*broadcast)(int root, const void* bytes, std::uint64_t n, PeninkMpiAlloc alloc, void* ctx, char* error,
                     std::size_t error_size);
    void (*abort)(int code);
    void (*finalize)();
};

// The module's exported symbol: fills *api.
using PeninkMpiOpenFn = void (*)(PeninkMpiApi* api);
#define PENINK_MPI_OPEN_SYMBOL "penink_mpi_open"

}  // extern "C"
