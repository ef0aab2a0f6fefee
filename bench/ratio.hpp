// Ratios measured honestly on a shared machine: the two sides interleaved
// (A, B, A, B, ...), so a load that comes and goes hits both, and the median
// of the pairs' ratios printed with their spread.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

namespace isolux::bench {

struct Ratio {
    double median = 0, low = 0, high = 0;
    int pairs = 0;
};

// Seconds per call of `work`, over `times` calls.
template <class Work>
double seconds_per(Work&& work, int times) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < times; ++i) work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / times;
}

// A over B: each pair times `a_times` calls of A, then `b_times` of B.
template <class A, class B>
Ratio interleaved(A&& a, int a_times, B&& b, int b_times, int pairs) {
    std::vector<double> r;
    a();
    b();  // warm
    for (int i = 0; i < pairs; ++i) {
        const double ta = seconds_per(a, a_times), tb = seconds_per(b, b_times);
        r.push_back(ta / tb);
    }
    std::sort(r.begin(), r.end());
    return {r[r.size() / 2], r.front(), r.back(), pairs};
}

// A over B for costs the two sides report themselves (e.g. a stage's own
// time from the frame report): each pair calls a() then b().
template <class A, class B>
Ratio interleaved_costs(A&& a, B&& b, int pairs) {
    std::vector<double> r;
    a();
    b();  // warm
    for (int i = 0; i < pairs; ++i) {
        const double ca = a(), cb = b();
        r.push_back(ca / cb);
    }
    std::sort(r.begin(), r.end());
    return {r[r.size() / 2], r.front(), r.back(), pairs};
}

// One line of --ratios: `name median (median of N interleaved pairs, spread
// low-high; target ...)`. `target` may be null (printed, no target).
inline void print_ratio(const char* name, const Ratio& r, const char* target, int digits = 3) {
    std::printf("%s %.*f (median of %d interleaved pairs, spread %.*f-%.*f%s%s)\n", name, digits, r.median, r.pairs,
                digits, r.low, digits, r.high, target ? "; target " : "", target ? target : "");
}

}  // namespace isolux::bench
