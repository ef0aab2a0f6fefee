// Inside core: the threads a frame's stages run on.
//
// A frame's stages split their work into lights or bands of rows and run
// them on a few threads that are kept from frame to frame: starting a thread
// costs tens of microseconds, a fair share of a frame that moved a few
// lights. Threads wait for each other by spinning a while before they sleep,
// since a frame's threads wait at most about one light's work while waking a
// sleeping thread costs about as much.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

#include "isolux/image.hpp"

namespace isolux {

// How long a waiting thread spins before it sleeps.
constexpr std::chrono::microseconds spin_limit{500};

// Waits for `ready` by spinning, for at most `limit`; false when it never was.
template <class Ready>
bool spin_until(const Ready& ready, std::chrono::microseconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    for (unsigned i = 0;; ++i) {
        if (ready()) return true;
        if ((i & 63) == 63 && std::chrono::steady_clock::now() > end) return false;
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
    }
}

// The meeting point of `count` threads: the last to arrive runs
// `completion`, then all go on (std::barrier's, spinning before it sleeps).
// Used once.
class PhaseBarrier {
public:
    PhaseBarrier(int count, const std::function<void()>& completion) : count_(count), completion_(completion) {}
    void arrive_and_wait();

private:
    const int count_;
    const std::function<void()>& completion_;
    std::atomic<int> arrived_{0};
    std::atomic<bool> passed_{false};
};

// Runs `job` on `extra` of the process's pool threads and on the caller's,
// all at once (so a job may wait at a PhaseBarrier for the others); false,
// having run nothing, when the pool is busy with another caller's job.
bool run_on_pool(int extra, const std::function<void()>& job);

// Runs `work` on `count` threads, the caller's among them, and waits for all:
// on the pool when it is free, else on threads of its own.
template <class Work>
void run_on_threads(int count, Work& work) {
    if (count <= 1) return work();
    const std::function<void()> job = [&work] { work(); };
    if (run_on_pool(count - 1, job)) return;
    std::vector<std::jthread> own;
    for (int id = 1; id < count; ++id) own.emplace_back([&work] { work(); });
    work();
}

// Runs band(rows) over every part (disjoint rectangles) split into bands of
// rows, on up to `threads` threads (one for small regions: starting threads
// would cost more). About four bands per thread, cut in proportion to each
// part's pixels, so that threads finish together.
template <class Band>
void in_row_bands(const std::vector<Rect>& parts, int threads, const Band& band) {
    std::int64_t pixels = 0;
    for (const Rect& r : parts) pixels += r.empty() ? 0 : std::int64_t(r.w) * r.h;
    if (pixels == 0) return;
    const int count = pixels < 150000 ? 1 : std::max(1, threads);
    if (count == 1) {
        for (const Rect& r : parts)
            if (!r.empty()) band(r);
        return;
    }
    std::vector<Rect> bands;
    const std::int64_t per_band = pixels / (count * 4) + 1;
    for (const Rect& r : parts) {
        if (r.empty()) continue;
        const int k = int(std::clamp<std::int64_t>((std::int64_t(r.w) * r.h + per_band / 2) / per_band, 1, r.h));
        for (int i = 0; i < k; ++i) {
            const int y0 = r.y + int(std::int64_t(r.h) * i / k), y1 = r.y + int(std::int64_t(r.h) * (i + 1) / k);
            bands.push_back({r.x, y0, r.w, y1 - y0});
        }
    }
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t k; (k = next++) < bands.size();) band(bands[k]);
    };
    run_on_threads(std::min<int>(count, int(bands.size())), work);
}

}  // namespace isolux
