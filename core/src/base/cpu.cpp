#include "base/cpu.hpp"

#include <atomic>

#include "base/cpu_dispatch.hpp"

namespace isolux {

namespace {

bool cpu_has_avx2() {
#if ISOLUX_X86_DISPATCH
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return false;
#endif
}

std::atomic<bool>& wide() {
    static std::atomic<bool> on{cpu_has_avx2()};
    return on;
}

}  // namespace

bool wide_kernels() { return wide().load(std::memory_order_relaxed); }
void set_wide_kernels(bool on) { wide() = on && cpu_has_avx2(); }

}  // namespace isolux
