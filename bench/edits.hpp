// Edits cost what they touch (issue: the level editor): one tree placed on
// maps of different sizes, and against a full rebuild.
#pragma once

namespace isolux::bench {

void register_edits();
// Prints edit_cost_map_ratio and edit_cost_vs_full, each the median of
// ratios of the two sides measured interleaved (A, B, A, B, ...), with the
// spread over the pairs.
void print_edit_ratios();

}  // namespace isolux::bench
