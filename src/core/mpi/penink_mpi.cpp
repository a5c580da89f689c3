// penink_mpi.so: src/core/mpi_module.hpp over Open MPI's MPI_COMM_WORLD.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "core/mpi_module.hpp"

namespace {

constexpr std::uint64_t piece = std::uint64_t(1) << 30;

int fail(int code, const char* what, char* error, std::size_t error_size) {
    char reason[MPI_MAX_ERROR_STRING] = {};
    int len = 0;
    MPI_Error_string(code, reason, &len);
    std::snprintf(error, error_size, "%s: %s", what, reason);
    return code;
}

int init(int* rank, int* size, char* error, std::size_t error_size) {
    int code = MPI_Init(nullptr, nullptr);
    if (code != MPI_SUCCESS) return fail(code, "MPI_Init", error, error_size);
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    if ((code = MPI_Comm_rank(MPI_COMM_WORLD, rank)) != MPI_SUCCESS) return fail(code, "MPI_Comm_rank", error, error_size);
    if ((code = MPI_Comm_size(MPI_COMM_WORLD, size)) != MPI_SUCCESS) return fail(code, "MPI_Comm_size", error, error_size);
    return 0;
}

// Polls done(flag) until it sets the flag, without holding a core: MPI_Recv and MPI_Send spin, and
// a rank waiting on rank 0 for seconds (penink drainage's ranks while rank 0 reads the DEM; a rank
// whose finished bands rank 0 takes after another's) would take a core from the rank it waits on.
// A thousand polls first, then a sleep of 0.1 ms growing to 1 ms between polls.
template <class Done> int poll_sleeping(Done&& done) {
    long sleep_ns = 100'000;
    for (int polls = 0;; ++polls) {
        int yes = 0;
        const int code = done(yes);
        if (code != MPI_SUCCESS || yes) return code;
        if (polls < 1000) continue;
        const timespec ts{0, sleep_ns};
        nanosleep(&ts, nullptr);
        sleep_ns = std::min(sleep_ns * 2, 1'000'000L);
    }
}
// Waits until a message from `from` with `tag` has arrived.
int wait_for(int from, int tag) {
    return poll_sleeping([&](int& arrived) { return MPI_Iprobe(from, tag, MPI_COMM_WORLD, &arrived, MPI_STATUS_IGNORE); });
}
// A send that waits for its receiver the same way (a large message waits until the receiver
// takes it: rank 0 takes the finished bands in row order, after those of the other ranks).
int send_sleeping(const void* p, int n, MPI_Datatype type, int to, int tag) {
    MPI_Request request;
    const int code = MPI_Isend(p, n, type, to, tag, MPI_COMM_WORLD, &request);
    if (code != MPI_SUCCESS) return code;
    return poll_sleeping([&](int& sent) { return MPI_Test(&request, &sent, MPI_STATUS_IGNORE); });
}

int send(int to, int tag, const void* bytes, std::uint64_t n, char* error, std::size_t error_size) {
    int code = send_sleeping(&n, 1, MPI_UINT64_T, to, tag);
    if (code != MPI_SUCCESS) return fail(code, "MPI_Isend", error, error_size);
    const auto* p = static_cast<const char*>(bytes);
    for (std::uint64_t at = 0; at < n; at += piece)
        if ((code = send_sleeping(p + at, int(std::min(piece, n - at)), MPI_BYTE, to, tag)) != MPI_SUCCESS)
            return fail(code, "MPI_Isend", error, error_size);
    return 0;
}

int receive(int from, int tag, PeninkMpiAlloc alloc, void* ctx, char* error, std::size_t error_size) {
    std::uint64_t n = 0;
    int code = wait_for(from, tag);
    if (code != MPI_SUCCESS) return fail(code, "MPI_Iprobe", error, error_size);
    code = MPI_Recv(&n, 1, MPI_UINT64_T, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (code != MPI_SUCCESS) return fail(code, "MPI_Recv", error, error_size);
    auto* p = static_cast<char*>(alloc(ctx, n));
    if (!p && n) {
        std::snprintf(error, error_size, "no room for a message of %llu bytes", static_cast<unsigned long long>(n));
        return MPI_ERR_NO_MEM;
    }
    for (std::uint64_t at = 0; at < n; at += piece)
        if ((code = MPI_Recv(p + at, int(std::min(piece, n - at)), MPI_BYTE, from, tag, MPI_COMM_WORLD,
                             MPI_STATUS_IGNORE)) != MPI_SUCCESS)
            return fail(code, "MPI_Recv", error, error_size);
    return 0;
}

int broadcast(int root, const void* bytes, std::uint64_t n, PeninkMpiAlloc alloc, void* ctx, char* error,
              std::size_t error_size) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    int code = MPI_Bcast(&n, 1, MPI_UINT64_T, root, MPI_COMM_WORLD);
    if (code != MPI_SUCCESS) return fail(code, "MPI_Bcast", error, error_size);
    char* p = rank == root ? const_cast<char*>(static_cast<const char*>(bytes)) : static_cast<char*>(alloc(ctx, n));
    if (!p && n) {
        std::snprintf(error, error_size, "no room for a message of %llu bytes", static_cast<unsigned long long>(n));
        return MPI_ERR_NO_MEM;
    }
    for (std::uint64_t at = 0; at < n; at += piece)
        if ((code = MPI_Bcast(p + at, int(std::min(piece, n - at)), MPI_BYTE, root, MPI_COMM_WORLD)) != MPI_SUCCESS)
            return fail(code, "MPI_Bcast", error, error_size);
    return 0;
}

void abort_all(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

// Ranks that end before the others wait for them here, sleeping (wait_for), not in MPI_Finalize,
// whose wait spins: the ranks that fill their bands and end would otherwise take cores from rank
// 0 for the rest of its build. Every rank tells rank 0 it has ended, and leaves once rank 0 has
// heard from all; errors are left to MPI_Finalize.
constexpr int ended_tag = 32000;
void finalize() {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank), MPI_Comm_size(MPI_COMM_WORLD, &size);
    char byte = 0;
    if (rank == 0) {
        for (int r = 1; r < size; ++r)
            if (wait_for(r, ended_tag) == MPI_SUCCESS) MPI_Recv(&byte, 1, MPI_BYTE, r, ended_tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        for (int r = 1; r < size; ++r) MPI_Send(&byte, 1, MPI_BYTE, r, ended_tag, MPI_COMM_WORLD);
    } else if (send_sleeping(&byte, 1, MPI_BYTE, 0, ended_tag) == MPI_SUCCESS && wait_for(0, ended_tag) == MPI_SUCCESS) {
        MPI_Recv(&byte, 1, MPI_BYTE, 0, ended_tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
    MPI_Finalize();
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void penink_mpi_open(PeninkMpiApi* api) {
    *api = {init, send, receive, broadcast, abort_all, finalize};
}
