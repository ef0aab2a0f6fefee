// The hot kernels (box blur, opacity correction, composite, white-light
// accumulation) are built twice: for the baseline CPU (SSE2 on x86-64) and
// for AVX2 (with FMA), twice as wide, taken when the CPU has both. The
// integer kernels give the same bytes at both widths; the float composite
// checks its rounding and redoes the doubtful pixels in double, so it does
// too. The tests hold them to it.
#pragma once

namespace isolux {

// Whether the AVX2 builds run: on by default when the CPU has AVX2 and FMA.
bool wide_kernels();
// Off runs the baseline builds (for tests); on has no effect without them.
void set_wide_kernels(bool on);

}  // namespace isolux
