// The processes of one distributed run and the messages between them: rank k of size(), byte
// messages sent from one rank to another (received in the order sent, per sender and tag),
// broadcasts, and an abort that ends every rank. launched_ranks() gives MPI's world
// (MPI_COMM_WORLD through the module penink_mpi.so, src/core/mpi_module.hpp) when penink was
// started by an MPI launcher (mpirun, mpiexec, srun), else none: the command then runs alone.
// run_thread_ranks runs n ranks as threads of one process (the same protocol, for tests).
// Errors: std::runtime_error with MPI's reason.
#pragma once
#include <cstdint>
#include <exception>
#include <iosfwd>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace penink {

class Ranks {
public:
    virtual ~Ranks() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    // Ranks of this run on this machine (their threads share its cores).
    virtual int local_size() const = 0;
    // A send may wait until the receiver takes the message; a receive waits for it. Over MPI
    // both wait polling with sleeps, leaving the core to the rank waited on (penink_mpi.so).
    virtual void send(int to, int tag, std::span<const std::uint8_t> bytes) = 0;
    virtual std::vector<std::uint8_t> receive(int from, int tag) = 0;
    // root's bytes into every rank's `bytes` (over MPI a broadcast, whose wait spins: for short
    // waits).
    virtual void broadcast(int root, std::vector<std::uint8_t>& bytes) = 0;
    // Ends the run on every rank with exit code `code` (a failure on one rank the others wait on).
    [[noreturn]] virtual void abort(int code) = 0;
};

// Whether the environment says an MPI launcher started this process (Open MPI's
// OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK, PMI's PMI_SIZE).
bool mpi_launched();

// MPI's world when mpi_launched(), initialised (MPI_Finalize when the object goes); null
// otherwise. Throws std::runtime_error when the module cannot be found or loaded (looked for
// beside the executable, then in ../lib/penink/) or MPI cannot start.
std::unique_ptr<Ranks> launched_ranks();

// A failure on one rank of a run whose other ranks wait on it: `e` reported on `log` in one line
// (a penink::Error as it is, anything else as format_error(stage, file, what)), then every rank
// ended (Ranks::abort) with its exit code (ExitCode::internal for anything but an Error).
[[noreturn]] void abort_reporting(Ranks& ranks, const char* stage, const std::string& file, const std::exception& e,
                                  std::ostream& log);

// The threads a process takes for its work: the hardware's (at most 16), shared among the ranks
// of this machine when `ranks` is given.
int rank_threads(const Ranks* ranks);
inline int rank_threads(const Ranks& ranks) { return rank_threads(&ranks); }

// Runs f on n threads, each with a Ranks of its own (rank k of n, local_size n) whose messages go
// to the others through memory. abort() throws std::runtime_error("aborted") on the thread that
// calls it and makes every blocked receive throw it too. Rethrows the first exception.
void run_thread_ranks(int n, const std::function<void(Ranks&)>& f);

}  // namespace penink
