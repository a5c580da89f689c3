// penink command line entry point: dispatches to src/cli/commands (render, drainage, ...).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cstring>
#include <system_error>
#include <thread>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "core/huge_page_malloc.hpp"

namespace {

// Whether a thread can start: under a process limit (ulimit -u, RLIMIT_NPROC) that allows none,
// the GL driver's start would wait for its worker threads for ever; one line instead.
bool threads_can_start() {
    try {
        std::thread([] {}).join();
        return true;
    } catch (const std::system_error& e) {
        std::cerr << penink::format_error("cli", "", std::string("cannot start a thread (") + std::strerror(e.code().value()) +
                                                         "): raise the process limit (ulimit -u)")
                  << "\n";
        return false;
    }
}

}  // namespace

// Every file is closed by the time run_cli returns: the process then ends without the libraries'
// teardown at exit (GDAL's drivers, PROJ's database: a few milliseconds of every command).
int main(int argc, char** argv) {
    // The commands that draw frames run with their heap in huge pages (core/huge_page_malloc.hpp):
    // the restart costs one more start of the program (about 0.1 s), their frames' page faults far more.
    if (argc > 1 && (std::strcmp(argv[1], "render") == 0 || std::strcmp(argv[1], "batch") == 0 ||
                     std::strcmp(argv[1], "preview") == 0))
        penink::restart_with_huge_page_malloc(argv);
#ifdef __GLIBC__
    // Per-cell arrays up to 32 MiB come from the heap and stay there once freed, so the next
    // stage's arrays reuse pages already faulted in instead of glibc unmapping them (a TLB
    // shootdown on every core) and the kernel zero-filling new ones: 3-10 % of a drainage build.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    // A heap grows 16 MiB at a time (address space only until touched): the worker threads'
    // heaps otherwise grow a page per mprotect (some 700 calls in a 1 M-cell build, GDAL's
    // blocks among them), each holding up the other threads' page faults.
    mallopt(M_TOP_PAD, 16 << 20);
#endif
    // A file-size limit (ulimit -f) makes a write fail with EFBIG, reported as a write error and
    // its temporary removed, rather than the process killed with the temporary left.
    std::signal(SIGXFSZ, SIG_IGN);
    const int code = threads_can_start() ? penink::run_cli(argc, argv) : int(penink::ExitCode::bad_input);
    std::cout.flush(), std::cerr.flush(), std::clog.flush();
    std::fflush(nullptr);
    std::_Exit(code);
}
