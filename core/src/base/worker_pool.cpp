// The threads a frame's stages run on: worker_pool.hpp.
#include "base/worker_pool.hpp"

#include <condition_variable>
#include <mutex>
#include <stop_token>

namespace isolux {

void PhaseBarrier::arrive_and_wait() {
    if (arrived_.fetch_add(1) + 1 == count_) {
        completion_();
        passed_ = true;
        passed_.notify_all();
        return;
    }
    if (spin_until([&] { return passed_.load(); }, spin_limit)) return;
    passed_.wait(false);
}

namespace {

// Threads kept from frame to frame, one job at a time.
class WorkerPool {
public:
    bool run(int extra, const std::function<void()>& job) {
        std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
        if (!busy) return false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            while (int(workers_.size()) < extra)
                workers_.emplace_back([this, id = int(workers_.size()), seen = generation_.load()](std::stop_token stop) {
                    serve(stop, id, seen);
                });
            job_ = &job;
            wanted_ = extra;
            done_ = 0;
            ++generation_;
        }
        wake_.notify_all();
        job();
        spin_until([&] { return done_.load() == wanted_; }, spin_limit);  // (wanted_ is this thread's write)
        std::unique_lock<std::mutex> lock(mutex_);
        finished_.wait(lock, [&] { return done_.load() == wanted_; });
        job_ = nullptr;
        return true;
    }

private:
    void serve(std::stop_token stop, int id, std::uint64_t seen) {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            // The next job often comes within the spin limit (frames back to
            // back, or a frame's next stage): waiting for it awake saves the
            // wake-up, which costs as much as the spin.
            lock.unlock();
            spin_until([&] { return generation_.load() != seen || stop.stop_requested(); }, spin_limit);
            lock.lock();
            if (!wake_.wait(lock, stop, [&] { return generation_.load() != seen; })) return;  // stopping
            seen = generation_.load();
            if (id >= wanted_) continue;  // this job wants fewer threads
            const std::function<void()>* job = job_;
            lock.unlock();
            (*job)();
            lock.lock();
            if (++done_ == wanted_) finished_.notify_all();
        }
    }

    std::mutex busy_, mutex_;
    std::condition_variable_any wake_, finished_;
    const std::function<void()>* job_ = nullptr;
    int wanted_ = 0;
    std::atomic<int> done_{0};
    std::atomic<std::uint64_t> generation_{0};  // written under mutex_, read spinning without it
    std::vector<std::jthread> workers_;  // last: stopped and joined first
};

}  // namespace

// One pool for every stage: a pool per stage would leave one stage's workers
// spinning while the next stage's run.
bool run_on_pool(int extra, const std::function<void()>& job) {
    static WorkerPool pool;
    return pool.run(extra, job);
}

}  // namespace isolux
