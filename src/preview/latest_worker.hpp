// One thread that runs tasks in order, for work bound to a thread (an OpenGL context is current
// on the thread that made it). Two kinds of task: queued ones (saves, exports) always run, in
// the order given; a "latest" one (a frame for the page) replaces a latest one still waiting,
// whose `dropped` then runs instead (on the caller's thread) so that its client hears it was
// superseded. A latest task waits behind the queued ones. `start` runs first on the thread,
// `stop` last (making and releasing the context there).
#pragma once
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

namespace penink {

struct WorkerTask {
    std::function<void()> run;
    std::function<void()> dropped;  // a latest task replaced before it ran (may be empty)
};

class LatestWorker {
public:
    LatestWorker(std::function<void()> start = {}, std::function<void()> stop = {});
    ~LatestWorker();  // runs what is queued, drops a waiting latest task, runs stop, joins
    LatestWorker(const LatestWorker&) = delete;
    LatestWorker& operator=(const LatestWorker&) = delete;

    void submit(WorkerTask task);
    void submit_latest(WorkerTask task);

private:
    void loop(std::function<void()> start, std::function<void()> stop);

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<WorkerTask> queued_;
    std::optional<WorkerTask> latest_;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace penink
