#include "core/ranks.hpp"

#include <ostream>

#include "core/error.hpp"

#include <dlfcn.h>

#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/mpi_module.hpp"
#include "core/parallel_chunks.hpp"

namespace penink {

namespace {

constexpr const char* module_name = "penink_mpi.so";

int env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    if (!v || !*v) return fallback;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    return *end == '\0' && n > 0 && n < (1 << 24) ? int(n) : fallback;
}

PeninkMpiApi load_module() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    std::string tried;
    for (const std::filesystem::path& p :
         {exe.parent_path() / module_name, (exe.parent_path() / ".." / "lib" / "penink" / module_name).lexically_normal()}) {
        if (!std::filesystem::is_regular_file(p, ec)) {
            tried += (tried.empty() ? "" : ", ") + p.string();
            continue;
        }
        // RTLD_GLOBAL: Open MPI loads plugins of its own that look for its symbols
        void* lib = dlopen(p.c_str(), RTLD_NOW | RTLD_GLOBAL);
        if (!lib) {
            const char* why = dlerror();
            throw std::runtime_error("cannot load " + p.string() + " (" + (why ? why : "dlopen failed") + ")");
        }
        const auto open = reinterpret_cast<PeninkMpiOpenFn>(dlsym(lib, PENINK_MPI_OPEN_SYMBOL));
        if (!open) throw std::runtime_error(p.string() + " lacks " + PENINK_MPI_OPEN_SYMBOL);
        PeninkMpiApi api{};
        open(&api);
        return api;
    }
    throw std::runtime_error(std::string(module_name) + " (MPI) not found (looked for " + tried + ")");
}

void* into_vector(void* ctx, std::uint64_t n) {
    auto* v = static_cast<std::vector<std::uint8_t>*>(ctx);
    v->resize(std::size_t(n));
    return v->data();
}

class MpiRanks final : public Ranks {
public:
    MpiRanks() : api_(load_module()) {
        check(api_.init(&rank_, &size_, error_, sizeof error_));
        local_ = env_int("OMPI_COMM_WORLD_LOCAL_SIZE", env_int("MPI_LOCALNRANKS", 1));
    }
    ~MpiRanks() override { api_.finalize(); }
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    int local_size() const override { return local_; }
    void send(int to, int tag, std::span<const std::uint8_t> bytes) override {
        check(api_.send(to, tag, bytes.data(), bytes.size(), error_, sizeof error_));
    }
    std::vector<std::uint8_t> receive(int from, int tag) override {
        std::vector<std::uint8_t> v;
        check(api_.receive(from, tag, into_vector, &v, error_, sizeof error_));
        return v;
    }
    void broadcast(int root, std::vector<std::uint8_t>& bytes) override {
        check(api_.broadcast(root, bytes.data(), bytes.size(), into_vector, &bytes, error_, sizeof error_));
    }
    [[noreturn]] void abort(int code) override {
        api_.abort(code);
        std::_Exit(code);  // MPI_Abort does not return; should it, the process ends all the same
    }

private:
    void check(int code) {
        if (code != 0) throw std::runtime_error(error_);
    }
    PeninkMpiApi api_;
    int rank_ = 0, size_ = 1, local_ = 1;
    char error_[512] = {};
};

// The mailboxes of run_thread_ranks: one queue per (from, to, tag).
struct Post {
    std::mutex m;
    std::condition_variable cv;
    std::map<std::tuple<int, int, int>, std::deque<std::vector<std::uint8_t>>> box;
    bool aborted = false;
};

class ThreadRanks final : public Ranks {
public:
    ThreadRanks(Post& post, int rank, int size) : post_(post), rank_(rank), size_(size) {}
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    int local_size() const override { return size_; }
    void send(int to, int tag, std::span<const std::uint8_t> bytes) override {
        const std::lock_guard<std::mutex> lock(post_.m);
        post_.box[{rank_, to, tag}].emplace_back(bytes.begin(), bytes.end());
        post_.cv.notify_all();
    }
    std::vector<std::uint8_t> receive(int from, int tag) override {
        std::unique_lock<std::mutex> lock(post_.m);
        auto& q = post_.box[{from, rank_, tag}];
        post_.cv.wait(lock, [&] { return post_.aborted || !q.empty(); });
        if (post_.aborted) throw std::runtime_error("aborted");
        std::vector<std::uint8_t> v = std::move(q.front());
        q.pop_front();
        return v;
    }
    void broadcast(int root, std::vector<std::uint8_t>& bytes) override {
        constexpr int tag = -1;  // a tag of its own
        if (rank_ == root) {
            for (int r = 0; r < size_; ++r)
                if (r != root) send(r, tag, bytes);
        } else {
            bytes = receive(root, tag);
        }
    }
    [[noreturn]] void abort(int) override {
        {
            const std::lock_guard<std::mutex> lock(post_.m);
            post_.aborted = true;
            post_.cv.notify_all();
        }
        throw std::runtime_error("aborted");
    }

private:
    Post& post_;
    int rank_, size_;
};

}  // namespace

bool mpi_launched() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}

std::unique_ptr<Ranks> launched_ranks() {
    if (!mpi_launched()) return nullptr;
    return std::make_unique<MpiRanks>();
}

void run_thread_ranks(int n, const std::function<void(Ranks&)>& f) {
    Post post;
    std::exception_ptr first;  // the first thrown (the others' are "aborted" that it caused)
    std::vector<std::thread> threads;
    for (int k = 0; k < n; ++k)
        threads.emplace_back([&, k] {
            ThreadRanks ranks(post, k, n);
            try {
                f(ranks);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(post.m);  // no rank waits for ever on one that failed
                if (!first) first = std::current_exception();
                post.aborted = true;
                post.cv.notify_all();
            }
        });
    for (std::thread& t : threads) t.join();
    if (first) std::rethrow_exception(first);
}

void abort_reporting(Ranks& ranks, const char* stage, const std::string& file, const std::exception& e,
                     std::ostream& log) {
    const Error* err = dynamic_cast<const Error*>(&e);
    log << (err ? std::string(e.what()) : format_error(stage, file, e.what())) << "\n" << std::flush;
    ranks.abort(err ? int(err->code()) : int(ExitCode::internal));
    std::abort();  // not reached (GCC does not take a virtual function's [[noreturn]] as the call's)
}

int rank_threads(const Ranks* ranks) {
    const int hardware = int(core_count());
    return ranks ? std::max(1, hardware / std::max(1, ranks->local_size())) : hardware;
}

}  // namespace penink
