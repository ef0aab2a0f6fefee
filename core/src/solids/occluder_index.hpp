// The occluder map's index kept in place after a part of it changed
// (occluder_map.cpp), for the maps made from it (occluder_scale.cpp).
#pragma once
#include <functional>
#include <vector>

#include "isolux/occluder_map.hpp"

namespace isolux {

// After the spans, surface and has_span flags of `part` changed (reach_rows
// already grown by its sprite pixels' heights): the lists of the ground
// pixels its sprite pixels' points can land on (its columns, from its top
// to reach_rows below it), made again in place as an edit's are (padding
// where they shrink): the same lists index_occluders makes.
void reindex_part(OccluderMap& m, Rect part);

// A pan of `m` to region `to`: what it holds of `keep` (in both regions)
// moved into place, the rest of `to` made by make(r) for each part r (its
// spans, surface and has_span flags, reach_rows grown by its sprite
// pixels' heights), and `changed` (parts the world changed) made too. The
// lists of the kept ground pixels whose points cannot have moved are kept
// (all but the rows within reach below `keep`'s top, where anything above it
// was made or dropped); the rest are listed anew (everything, when
// `changed` is not empty).
void pan_occluder_map(OccluderMap& m, Rect to, Rect keep, const std::vector<Rect>& changed,
                      const std::function<void(Rect)>& make);

}  // namespace isolux
