// Inside core: ISOLUX_AVX2 marks a function built for AVX2 (base/cpu.hpp).
// The kernel it calls is [[gnu::always_inline]], so its loops are vectorised
// again at the wider width inside it.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ISOLUX_X86_DISPATCH 1
#define ISOLUX_AVX2 __attribute__((target("avx2")))
// The composite's float kernel also fuses its multiply-adds (every AVX2 CPU
// has FMA as well; wide_kernels() asks for both).
#define ISOLUX_AVX2_FMA __attribute__((target("avx2,fma")))
#else
#define ISOLUX_X86_DISPATCH 0
#define ISOLUX_AVX2
#define ISOLUX_AVX2_FMA
#endif
