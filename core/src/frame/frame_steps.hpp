// The frame's steps (frame.hpp) share these: the report's timing and
// records, and what one step decides for the next. frame.cpp runs the
// steps in order; frame_trace.cpp holds the trace step, the largest.
#pragma once
#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "frame/frame_cache.hpp"
#include "isolux/frame.hpp"

namespace isolux::frame_steps {

using Clock = std::chrono::steady_clock;
using TracedLight = FrameCache::TracedLight;

inline double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// Times one stage into the report for as long as it lives.
struct Timer {
    FrameReport& report;
    Stage stage;
    Clock::time_point start = Clock::now();
    ~Timer() {
        report.ran[int(stage)] = true;
        report.ms[int(stage)] += ms_between(start, Clock::now());
    }
};

// A new revision, unique in the process (FrameState::obstacles_revision).
std::uint64_t next_obstacles_revision();

inline Rect grow(Rect r, int by) { return {r.x - by, r.y - by, r.w + 2 * by, r.h + 2 * by}; }

inline Rect bounding(const std::vector<Rect>& parts) {
    Rect b;
    for (const Rect& r : parts) b = bounding(b, r);
    return b;
}

// Records what a stage wrote: its disjoint parts and their bounding box.
inline void touch(FrameReport& rep, Stage s, std::vector<Rect> parts) {
    std::erase_if(parts, [](const Rect& r) { return r.empty(); });
    rep.touched[int(s)] = bounding(parts);
    rep.touched_parts[int(s)] = std::move(parts);
}

inline int threads_wanted(const FrameOptions& o) {
    return o.threads > 0 ? o.threads : std::max(1, int(std::thread::hardware_concurrency()));
}

// What the obstacle map did this frame: nothing, a part (after an edit), or
// all of it.
struct ObstacleChange {
    bool all = false;
    Rect part;  // rebuilt after an edit; lights meeting it are retraced
};

// Paper 3.2: rays are traced once every l frames. `must`: nothing traced can
// be reused (obstacles or tracing parameters changed).
struct TraceDecision {
    bool must = false, retrace = false;
};

// Paper 3.2 and Algorithm 2: the lights that need it traced, corrected and
// summed into the light texture, the rest reused. A frame that fails or is
// cancelled keeps nothing half-traced: the next one starts afresh.
void trace_step(FrameState& st, const World& world, const Scene& scene, Rect tex_rect, const TraceDecision& trace,
                const ObstacleChange& obstacles, FrameReport& rep);

}  // namespace isolux::frame_steps
