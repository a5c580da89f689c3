#include "preview/latest_worker.hpp"

namespace penink {

LatestWorker::LatestWorker(std::function<void()> start, std::function<void()> stop)
    : thread_([this, start = std::move(start), stop = std::move(stop)] { loop(start, stop); }) {}

LatestWorker::~LatestWorker() {
    std::optional<WorkerTask> dropped;
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        dropped.swap(latest_);
    }
    wake_.notify_one();
    if (dropped && dropped->dropped) dropped->dropped();
    thread_.join();
}

void LatestWorker::submit(WorkerTask task) {
    {
        std::lock_guard lock(mutex_);
        queued_.push_back(std::move(task));
    }
    wake_.notify_one();
}

void LatestWorker::submit_latest(WorkerTask task) {
    std::optional<WorkerTask> replaced;
    {
        std::lock_guard lock(mutex_);
        replaced.swap(latest_);
        latest_ = std::move(task);
        if (stopping_) replaced.swap(latest_);  // never runs: dropped at once
    }
    wake_.notify_one();
    if (replaced && replaced->dropped) replaced->dropped();
}

void LatestWorker::loop(std::function<void()> start, std::function<void()> stop) {
    if (start) start();
    for (;;) {
        WorkerTask task;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !queued_.empty() || latest_; });
            if (!queued_.empty()) {
                task = std::move(queued_.front());
                queued_.pop_front();
            } else if (latest_) {
                task = std::move(*latest_);
                latest_.reset();
            } else {
                break;  // stopping, nothing left
            }
        }
        task.run();
    }
    if (stop) stop();
}

}  // namespace penink
