// The GPU tracer against the CPU's on the benchmark scenes (needs a display,
// as the GL tests do: run under xvfb-run on a machine without one).
#pragma once

namespace isolux::bench {

// Prints gpu_trace_identical (1 when every scene's bytes are the CPU's) and
// the GPU's time over the CPU's, or why it could not run.
void print_gpu_figures();

}  // namespace isolux::bench
