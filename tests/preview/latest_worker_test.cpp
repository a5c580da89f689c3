// The preview's drawing thread: queued tasks all run in order, on one thread; latest tasks
// that wait are replaced by newer ones (the replaced ones hear it), and run after the queued.
#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "preview/latest_worker.hpp"

using namespace penink;

TEST(LatestWorker, WaitingFramesCollapseToTheNewest) {
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    std::promise<void> started;
    std::mutex m;
    std::vector<std::string> ran, dropped;
    std::thread::id start_thread, run_thread;
    std::set<std::thread::id> threads;
    std::promise<void> newest_ran;
    {
        LatestWorker worker([&] { start_thread = std::this_thread::get_id(); }, {});
        worker.submit({[&] {
                           started.set_value();
                           released.wait();
                           std::lock_guard l(m);
                           ran.push_back("blocker"), threads.insert(std::this_thread::get_id());
                       },
                       {}});
        started.get_future().wait();  // the worker is busy: what follows waits
        for (const char* name : {"a", "b", "c"})
            worker.submit_latest({[&, name] {
                                      std::lock_guard l(m);
                                      ran.push_back(name), threads.insert(std::this_thread::get_id());
                                      if (std::string(name) == "c") newest_ran.set_value();
                                  },
                                  [&, name] {
                                      std::lock_guard l(m);
                                      dropped.push_back(name);
                                  }});
        worker.submit({[&] {
                           std::lock_guard l(m);
                           ran.push_back("save"), threads.insert(std::this_thread::get_id());
                       },
                       {}});
        {
            std::lock_guard l(m);
            EXPECT_EQ(dropped, (std::vector<std::string>{"a", "b"}));  // told at once, not after the blocker
        }
        release.set_value();
        newest_ran.get_future().wait();
    }
    EXPECT_EQ(ran, (std::vector<std::string>{"blocker", "save", "c"}));  // queued work before the frame
    ASSERT_EQ(threads.size(), 1u);
    EXPECT_EQ(*threads.begin(), start_thread);  // the thread that ran `start` (made the GL context)
    EXPECT_NE(start_thread, std::this_thread::get_id());
}

TEST(LatestWorker, AnIdleWorkerRunsEachFrame) {
    std::atomic<int> runs{0}, drops{0};
    {
        LatestWorker worker;
        for (int i = 0; i < 5; ++i) {
            std::promise<void> done;
            worker.submit_latest({[&] { ++runs, done.set_value(); }, [&] { ++drops, done.set_value(); }});
            done.get_future().wait();
        }
    }
    EXPECT_EQ(runs.load(), 5);
    EXPECT_EQ(drops.load(), 0);
}

TEST(LatestWorker, StopRunsOnTheWorkerLast) {
    std::vector<std::string> order;
    std::thread::id start_thread, stop_thread;
    {
        LatestWorker worker([&] { start_thread = std::this_thread::get_id(), order.push_back("start"); },
                            [&] { stop_thread = std::this_thread::get_id(), order.push_back("stop"); });
        worker.submit({[&] { order.push_back("task"); }, {}});
    }
    EXPECT_EQ(order, (std::vector<std::string>{"start", "task", "stop"}));
    EXPECT_EQ(start_thread, stop_thread);
}
