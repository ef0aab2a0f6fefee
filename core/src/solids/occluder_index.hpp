// The occluder map's index kept in place after a part of it changed
// (occluder_map.cpp), for the maps made from it (occluder_scale.cpp).
#pragma once
#include "isolux/occluder_map.hpp"

namespace isolux {

// After the spans and surface of `part` changed (reach_rows already grown
// by its sprite pixels' heights): its has_span flags, and the lists of the
// ground pixels its sprite pixels' points can land on (its columns, from
// its top to reach_rows below it), made again in place as an edit's are
// (padding where they shrink): the same lists index_occluders makes.
void reindex_part(OccluderMap& m, Rect part);

}  // namespace isolux
