// The hot kernels (box blur, opacity correction) are built twice: for the
// baseline CPU (SSE2 on x86-64) and for AVX2, twice as wide, taken when the
// CPU has it. Integer arithmetic: both give the same bytes, and the tests
// hold them to it.
#pragma once

namespace isolux {

// Whether the AVX2 builds run: on by default when the CPU has AVX2.
bool wide_kernels();
// Off runs the baseline builds (for tests); on has no effect without AVX2.
void set_wide_kernels(bool on);

}  // namespace isolux
