// Beyond the paper: a sprite's 3D occupancy estimated from its alpha alone (no
// manifest shape, no normal map), so that what stands off the ground (a canopy
// above a trunk) can cast a shadow. The paper keeps only where an object
// meets the ground (Algorithm 1's footprint).
//
// Each object is a stack of cross-sections about the vertical axis through
// its footprint's centre, in the ground frame of solid.hpp (screen x = X - Y,
// screen y = (X + Y) / 2 - Z), one per pixel of height. First each is a disc:
// a disc of radius r at height z is drawn as an ellipse r*sqrt(2) wide and
// r/sqrt(2) high on each side of screen row (footprint row - z); each disc is
// the largest whose ellipse lies inside the object's opaque pixels, so the
// solid is the largest of revolution the silhouette allows. Then each
// widens across the view (ground direction (1, -1), screen x) to what the
// silhouette shows at its height: its depth stays the disc's radius, which
// the silhouette cannot tell (docs/beyond.md).
#pragma once
#include <optional>
#include <vector>

#include "isolux/footprint.hpp"
#include "isolux/image.hpp"
#include "isolux/params.hpp"
#include "isolux/solid.hpp"
#include "isolux/tileset.hpp"

namespace isolux {

struct EstimatedObject {
    double center_x = 0, center_y = 0;  // the footprint's centre, sprite pixels (as check-tileset's obstacle_center)
    Rect rect;                          // the footprint's bounding box, sprite pixels
    // Which solid this is. revolution and mound: the ellipse cross-sections
    // below. prism: the rectangle |x| <= half_x, |y| <= half_y of the ground
    // frame (its sides along the tiles' edges) at every height below
    // height(); its radius[z] is then the rectangle's circumscribed circle,
    // so code that bounds a cross-section by its ellipse stays a superset.
    ObjectModel model = ObjectModel::revolution;
    double half_x = 0, half_y = 0;
    // A prism whose columns all rise alike (a wall's, a hedge's, a box's):
    // its top is one flat face, which the points a sprite shows there lie
    // on; a stepped roof's or a town's rises vary.
    bool flat_top = false;
    // A prism whose rises vary (a stepped roof, a town of boxes): its height
    // per screen column, steps[i] over screen x in [i - reach, i + 1 - reach)
    // from the axis (reach = half_x + half_y), each at most height(). Every
    // point the prism fills in a column lies below its step: on a view line
    // screen x is ground x - y, so each column is a flat-topped prism of its
    // own, and the silhouette's top follows the sprite's. Empty: one height.
    std::vector<double> steps;
    // The prism's height over screen column sx (relative to the axis).
    double step_at(double sx) const;
    // A stepped prism's ground per screen column (indexed as steps): how far
    // toward the viewer it reaches, the screen row (relative to the foot)
    // under the column's lowest pixel. Boxes side by side (a town's) leave
    // ground in front of those set back, which the rectangle would fill,
    // and a column the sprite leaves empty holds nothing: what stands there
    // would show. Empty: the rectangle's ground. A user's height replaces
    // the steps and keeps the fronts: the ground the sprite shows is the same.
    std::vector<double> fronts;
    // The front over screen column sx (relative to the axis); +inf: none.
    double front_at(double sx) const;
    // A prism under a pitched roof (a house's): its top falls from height()
    // over the ridge, the rectangle's centre line along one ground axis
    // (ridge_axis 0: x, the roof sloping in y; 1: y, sloping in x), to
    // `eaves` at the rectangle's sides. -1: no ridge.
    int ridge_axis = -1;
    double eaves = 0;
    // The prism's top over the ground-frame point (x, y) relative to the
    // foot: its column's step under its roof.
    double top_at(double x, double y) const;
    // Whether the ground point (x, y) relative to the foot lies behind its column's front.
    bool behind_front(double x, double y) const { return (x + y) / 2 <= front_at(x - y); }
    // A prism's visual hull: the object's pixels (sprite pixels, as
    // center_x/center_y). A point of the prism whose level's middle lies on
    // the view line of a pixel the sprite leaves empty would show there, so
    // the prism holds none there: a fence's gaps under and between its
    // rails let light through. Empty: the prism is not carved.
    Mask hull;
    // Whether sprite pixel (x, y) is one of the hull's (every pixel where there is none).
    bool hull_shows(int x, int y) const { return hull.bits.empty() || hull.get(x, y); }
    // Whether level z over the ground-frame point (x, y) relative to the foot lies on a hull pixel.
    bool in_hull(std::size_t z, double x, double y) const;
    // The cross-section from height z to z + 1, an ellipse about the axis,
    // ground pixels: radius[z] its semi-axis in depth (ground direction
    // (1, 1), along screen y; 0: none), across[z] its semi-axis across the
    // view (ground (1, -1), screen x), at least radius[z]. `across` empty:
    // every cross-section is a disc.
    std::vector<double> radius, across;

    // The top of the solid above the ground, pixels (0: no solid).
    double height() const { return double(radius.size()); }
    double across_at(std::size_t z) const { return across.empty() ? radius[z] : across[z]; }
    // Whether cross-section z holds the ground-frame point (x, y) relative to the axis's foot.
    bool holds(std::size_t z, double x, double y) const;
    // The heights [z_low, z_high) the solid fills over the ground-frame
    // point (x, y) relative to the axis's foot; false where it fills none.
    bool span_at(double x, double y, double& z_low, double& z_high) const;
    // Whether the ground-frame point `p`, relative to the axis's foot, lies inside.
    bool contains(Vec3 p) const;
    // The outward unit normal of the solid's surface at (or nearest) the
    // ground-frame point `p` relative to the axis's foot, from the model
    // itself: a prism's nearest face; an ellipse stack's gradient of
    // (u / across(z))^2 + (v / radius(z))^2 (u across the view, v in depth),
    // the cross-sections' change with height the central difference of the
    // levels above and below p's.
    Vec3 normal_at(Vec3 p) const;
};

// Where the widest disc hides everything below it (a pine's skirt of
// foliage over a trunk the sprite never shows), the discs below it keep at
// most this share of its radius: a stem. The median of the lone trees'
// visible trunks in the real art nobody here drew
// (RealArt.hiddenStemRatioIsTheRealTreesMedian; docs/beyond.md).
constexpr double hidden_stem_ratio = 0.2;

// Whether the discs from object `o`'s widest one up draw every opaque pixel
// of `object` below the widest disc's centre, but for at most 2 rows a
// column: then the discs below the widest are hidden behind its front edge
// (a pine's skirt of foliage), and nothing in the silhouette says how wide
// they are. A bush or a rock resting on the ground shows a crescent of its
// lower half below its widest disc.
bool hidden_below_widest(const Mask& object, const EstimatedObject& o);

// The object standing in a sprite whose object pixels are `object` (the
// footprint estimate's opacity, baked ground and shadows taken out) and whose
// footprint is `footprint` (both in sprite pixels). None when the footprint
// or the object is empty. `correction` (a sprite's footprint spec) may fix
// where the axis meets the ground (`object_foot`, the centre of that pixel)
// and the solid's height (`object_height`), as a user set them in the
// tileset inspector. With the sprite's `trunks` (FootprintReport::trunks),
// a grove (two or more trunks standing on the tile, each a tree's foot)
// gives one object per tree; with its `crowns` (FootprintReport::crowns)
// too, one per crown, the trees whose trunks the trees in front hide among
// them. With `whole_base` (FootprintReport::whole_base: the footprint is
// the object's whole base), one object stands on its base's centre.
std::vector<EstimatedObject> estimate_objects(const Mask& object, const Mask& footprint,
                                              const FootprintSpec* correction = nullptr,
                                              const std::vector<TrunkFoot>* trunks = nullptr,
                                              bool whole_base = false,
                                              const std::vector<Mask>* crowns = nullptr);
// The objects of a sprite whose footprint estimate saw `report` and whose
// footprint is `footprint`: where the sprite holds parts standing apart on
// its tile (FootprintReport::parts), no grove of trunks and no correction
// of the user's, each part's own; else estimate_objects over the whole.
std::vector<EstimatedObject> estimate_objects(const FootprintReport& report, const Mask& footprint,
                                              const FootprintSpec* correction = nullptr);


// How well objects' silhouette fits an object's pixels: |both| / |either|
// (the silhouette as solid_silhouette draws it). 0 when both are empty.
double silhouette_fit(const std::vector<EstimatedObject>& objects, const Mask& object);

// The prism (a footprint rectangle along the tiles' edges, extruded to one
// height) whose projection fits the object's pixels: the rectangle's front
// corners from the object's lowest pixels (a V of slopes +-1/2, fitted
// robustly so that eaves and gaps between posts do not move it), its back
// corner mirrored through the rectangle's centre, its height the median of
// the columns' rise from the back edges to the object's top. None where no
// such V holds (a rounded base, a trunk). `v_share`, when given, receives
// the share of the object's columns whose lowest pixel lies on the V.
std::optional<EstimatedObject> fit_prism(const Mask& object, double* v_share = nullptr);

// Prism `o` (fit_prism's, its top not flat) given a step per screen column
// where it holds boxes side by side (a town's houses): each column's rise
// from the rectangle's back edges to the object's top (a median over 3
// columns, at least 1 pixel; a column the object leaves empty takes its
// nearest neighbour's), taken where two neighbouring columns' rises differ
// by a third of the prism's height or more. Else `o` is left as it is.
void step_prism(const Mask& object, EstimatedObject& o);

// Prism `o` (fit_prism's, its top neither flat nor stepped) under a pitched
// roof where one fits its top rows clearly better than a flat top: the
// ridge along one ground axis over the rectangle's centre line, its height
// and its eaves' those whose projected top rows miss the object's least
// (each column's miss capped). Else `o` is left as it is.
void ridge_prism(const Mask& object, EstimatedObject& o);
// A taken prism's top: flat, else stepped (step_prism), else pitched (ridge_prism).
void top_prism(const Mask& object, EstimatedObject& o);

// The mound (a half ellipsoid on the ground) whose projection fits the
// object's pixels: its base from the widest row and the lowest row, its
// height from the top row. None when the top does not stand above the base.
std::optional<EstimatedObject> fit_mound(const Mask& object);

// The objects of tileset sprite `s` under preset `p`: its footprint as the
// obstacle map stamps it (tileset_footprint) and the estimate's pixels.
std::vector<EstimatedObject> sprite_objects(const Tileset& tileset, const Sprite& s, const Params& p);

// The sprite pixels (of a w x h sprite) where the objects' cross-sections are drawn:
// the estimated solids' silhouette, for a contact sheet or the inspector.
Mask solid_silhouette(const std::vector<EstimatedObject>& objects, int w, int h);

// The share of the volume two occupancies share, |A and B| / |A or B|, over
// 1-pixel voxels: the estimated objects (relative to the sprite's anchor at
// (anchor_x, anchor_y)) against the manifest's shape. 0 when both are empty.
// Where their bounds hold more than volume_overlap_samples voxels (a huge
// shape), the voxels grow to keep that many, so the time stays bounded.
inline constexpr double volume_overlap_samples = 1 << 22;
double volume_overlap(const std::vector<EstimatedObject>& objects, int anchor_x, int anchor_y,
                      const std::vector<Solid>& shape);

}  // namespace isolux
